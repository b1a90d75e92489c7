"""Simulation: the chunked event loop over any engine (``simulate``) and the seam's self-test (``seam_check``).

May import: the engines, :mod:`mjpoincare.core` and :mod:`mjpoincare.analysis`; never a scenario, a command or a
face.
"""
