"""Core: the records and mechanisms every layer above shares: parameters and simulator settings, the result record
and its outputs, the rollout seam's protocol, the job loop and progress, MuJoCo's log and compatibility shims, the
MJCF loader, the run stamp and the allowance of two runs' comparison.

May import: :mod:`mjpoincare.analysis` (numpy and scipy only) and its own modules; never an engine, a scenario, a
command or a face.
"""
