"""``mcar view``: the robot in a browser through viser (the optional extra ``mcar[view]``).

:mod:`.model` loads and checks the robot as ``mcar render`` does, :mod:`.server` serves it
with joint sliders and display switches, :mod:`.watch` sees edits to its files, and
:mod:`.dimensions` gives a robot built from a config.xacro its dimension sliders.
"""
