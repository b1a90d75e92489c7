"""Commands: what a user runs on scenarios: validate, sweep, converge (and its extrapolation), bench (its paths and
batch scaling), stress, tune (and its pages), render and report.

May import: the registry (:mod:`mjpoincare.scenarios`, its ``base`` and ``gate_cases`` records; never one system's
modules), the simulation, the engines, :mod:`mjpoincare.core` and :mod:`mjpoincare.analysis`; never the gate, the
pages or a face.
"""
