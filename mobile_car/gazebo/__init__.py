"""What Gazebo makes of a robot: Gazebo never simulates a URDF, it simulates what libsdformat
converts it to. A small C++ helper (``helpers/mcar-sdformat.cc``, built by the Makefile) runs
that conversion; :mod:`.helper` finds and runs it within bounds, :mod:`.wire` checks its
answer, :mod:`.changes` says what the conversion changed (``mcar check --gazebo``) and
:mod:`.sdf` gives the SDF it writes (``mcar build --format sdf``).
"""
