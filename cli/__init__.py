"""The click command layer of mcar: one module per command; installed as ``mobile_car.cli``."""
