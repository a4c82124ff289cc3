"""``mcar sweep``: many variants of a robot's dimensions, each validated, built, checked and
simulated, on a local process pool or a Dask cluster; the rows become a results file and a
plot."""
