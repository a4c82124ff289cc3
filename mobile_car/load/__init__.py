"""The one way in: what the user names (files, folders, ``-``, part names, xacro arguments,
dimension overrides) becomes expanded robots, for every command."""
