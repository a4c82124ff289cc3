"""Stage 2: the checker: check_urdf's tree and verdict, and the rules check_urdf misses."""
