"""``mcar sim``: the robot in MuJoCo, headless: does it stand, drive straight and turn in
place as its geometry promises? (model: URDF -> MjSpec; drive: which joints drive;
scenarios: drop, drive, spin; lint: what a simulator would disagree with; record: GIF.)

MuJoCo is imported only here, and only by the commands that simulate.
"""
