"""Engines: the seam's implementations (``backends``: MuJoCo C, MJX, MuJoCo Warp, Drake's plant) and the outside
peers (``peers``: Drake's hybrid models).

May import: :mod:`mjpoincare.core` and :mod:`mjpoincare.analysis`; never a scenario, a command or a face.
"""
