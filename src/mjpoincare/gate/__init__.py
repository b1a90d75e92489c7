"""The regression gate: its forms (``forms``: gated, watched, declared miss; the margins), the environments one
machine emulates (``environments``), the baseline (``baseline``), the planted changes that measure its power
(``power``) and the MuJoCo release history (``releases``).

May import: the commands (a gate case is a validation), the registry, :mod:`mjpoincare.core` and
:mod:`mjpoincare.analysis`; never a page or a face.
"""
