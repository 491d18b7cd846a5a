"""Filters, one algorithm per module (import the module: ``from navlib.filters import mahony``).

Each module states its theory and the equations of the paper that introduced it in its
docstring, takes IMU samples as arrays (``w_ib_b``, ``f_b``, ... of shape (..., N, 3)) with a
fixed or per-sample ``dt``, and returns a result whose ``faults`` field is a
:class:`navlib.robust.FaultReport`. A new filter (e.g. Madgwick) is a new module here.
"""
