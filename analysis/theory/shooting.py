"""Shooting for periodic orbits of hybrid maps: central-difference Jacobians and chord-Newton on P(z) - z.

Shared by the exact references (the friction rimless wheel and compass biped of 002, the 3D rimless wheel of
001): each supplies its return map P as a callable on a section vector z; nothing here knows the model.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]


def central_jacobian(fun: Callable[[Vector], Vector], z: Vector, h: float, relative: bool = False) -> Matrix:
    """dF/dz at z by central differences (truncation O(h^2)), with absolute step h, or h max(1, |z_j|) per
    coordinate when ``relative``."""
    z = np.asarray(z, dtype=float)
    n = z.size
    jac = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = h * max(1.0, abs(z[j])) if relative else h
        jac[:, j] = (fun(z + e) - fun(z - e)) / (2.0 * e[j])
    return jac


def chord_newton(fun: Callable[[Vector], Vector], z0: Vector, *, tol: float, h: float = 1e-7,
                 max_iter: int = 30, jac0: Matrix | None = None, relative_step: bool = False,
                 step_tol: float = 0.0, halvings: int = 6) -> Vector | None:
    """Newton on F(z) = 0 (F = P - id for a fixed point) with a central-difference Jacobian (or ``jac0`` to start
    with), reused while the residual shrinks tenfold per step (chord steps). A step into a failing map (non-finite
    F) is halved up to ``halvings`` times. Converged when max |F| < ``tol`` or the step is below ``step_tol``;
    None if it does not converge."""
    z = np.asarray(z0, dtype=float).copy()
    r = fun(z)
    jac = jac0
    for _ in range(max_iter):
        if not np.all(np.isfinite(r)):
            return None
        if np.max(np.abs(r)) < tol:
            return z
        if jac is None:
            jac = central_jacobian(fun, z, h, relative_step)
            if not np.all(np.isfinite(jac)):
                return None
        try:
            dz = np.linalg.solve(jac, -r)
        except np.linalg.LinAlgError:
            return None
        for _half in range(halvings + 1):
            r_new = fun(z + dz)
            if np.all(np.isfinite(r_new)):
                break
            dz = 0.5 * dz
        else:
            return None
        if not np.max(np.abs(r_new)) < 0.1 * np.max(np.abs(r)):
            jac = None
        z, r = z + dz, r_new
        if np.max(np.abs(dz)) < step_tol:
            return z
    return z if np.max(np.abs(r)) < tol else None
