"""mcar specs: what the robot can do, computed from its description and proven in MuJoCo
(issue 42). :mod:`.figures` holds the shapes every part shares: a :class:`~.figures.Figure`
(a value with its unit, source and assumptions, and MuJoCo's proof where physics can give
one) and a :class:`~.figures.Section` of them."""
