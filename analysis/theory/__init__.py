"""Analytic results of the papers: one package per system (its ``__init__`` the system's closed forms, its modules
the parameters, maps, exact hybrid references and the measurements of recorded rows in the papers' terms), and the
mechanisms two systems share (stick-slip contact and impact, shooting for periodic orbits).

May import: numpy, scipy and :mod:`mjpoincare.analysis`; nothing of the simulator.
"""
