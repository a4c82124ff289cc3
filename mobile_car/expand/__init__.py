"""Stage 1: xacro expansion with the real xacro library, its errors located in the sources,
run under a guard on time and memory."""
