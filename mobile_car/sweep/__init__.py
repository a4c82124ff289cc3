"""``mcar sweep``: many variants of the car's dimensions built, checked and simulated, and
the results drawn (:mod:`.plot`). Needs the optional extra ``mcar[sweep]``."""
