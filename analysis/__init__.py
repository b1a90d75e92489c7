"""The analysis layer, shipped as ``mjpoincare.analysis``: sections, return-map fits, signals, checks, tables, and
``theory/`` (one folder per system: the papers' analytic results and their exact references).

May import: numpy, scipy and its own modules only; never MuJoCo, dm_control or any other layer of the package.
"""
