"""The MJCF models, one file per system (readable on their own: ``python -m mujoco.viewer --mjcf models/NAME.xml``).

Shipped as the package data ``mjpoincare.mjcf`` and loaded by :mod:`mjpoincare.models`.
"""
