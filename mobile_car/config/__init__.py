"""The robot's dimensions: config.xacro's spec, overrides (--set/--config), their
evaluation by xacro itself, and units."""
