"""Outside peers: simulators nobody here wrote, run on the same parameters as a scenario, to check the suite's
analytic values (and to set the row a user would pick instead of MuJoCo beside the bench's MuJoCo rows).

One peer so far, :mod:`mjpoincare.peers.drake` (the optional extra ``mjpoincare[peers]``).
"""
