"""The MJCF models, one file per system (readable on their own: ``python -m mujoco.viewer --mjcf models/NAME.xml``),
and ``common/``, the files every model includes (``common/looks.xml``: sky, floor material and headlight).

Shipped as the package data ``mjpoincare.mjcf`` and loaded by :mod:`mjpoincare.core.mjcf_loader`.
"""
