"""Period-1 gaits of the compass biped with Coulomb friction: Newton shooting, multipliers, continuation in mu.

Source: 002 = Gamus & Or (2015), "Dynamic bipedal walking under stick-slip transitions", SIAM J. Appl. Dyn. Syst.,
Secs. 4.2 and 5: fixed points of the post-impact map (3-D for a sticking impact, 4-D for a slipping one), the
eigenvalues of its Jacobian (Figs 4.2b, 5.2a plot the largest modulus), natural-parameter continuation in mu (Figs
4.2b, 5.2) and the mu at which a gait loses stability; derivation page docs/theory/stick-slip.md, Secs. 3 and 7.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np
from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory.compass_biped_friction.actuation import PASSIVE, Actuation
from mjpoincare.analysis.theory.compass_biped_friction.one_step import StepRecord, classify, return_map, step
from mjpoincare.analysis.theory.compass_biped_friction.params import FrictionBiped, Matrix, Vector
from mjpoincare.analysis.theory.shooting import central_jacobian, chord_newton
from numpy.typing import ArrayLike, NDArray

#: Absolute central-difference step on the section coordinates (rad, rad/s, m/s) for Jacobians. The map is smooth
#: while the phase sequence and impact kind are unchanged; the stance integration error (rtol 1e-11) then puts the
#: Jacobian noise at ~1e-6 and the truncation error at ~1e-10. Where a perturbation of size FD_STEP changes the phase
#: sequence (a stick phase grazing the cone, a slip speed grazing 0) or the impact kind, the map is only piecewise
#: smooth (continuous, with a kink) and the central difference is the mean of the one-sided derivatives.
FD_STEP = 1e-5
#: Newton converges when the largest |P(z) - z| is below this.
NEWTON_TOL = 1e-10


def _gap(bp: FrictionBiped, actuation: Actuation | None, dim: int, kind: str | None) -> Callable[[Vector], Vector]:
    """P(z) - z restricted to ``dim`` section coordinates; NaN when the step fails or (``kind``) has the wrong
    impact kind."""

    def gap(z: Vector) -> Vector:
        rec = step(bp, z, actuation)
        if rec.failure is not None or (kind is not None and rec.impact != kind):
            return np.full(dim, math.nan)
        return rec.z[:dim] - z

    return gap


def fixed_point(bp: FrictionBiped, guess: ArrayLike, actuation: Actuation | None = None,
                jacobian: ArrayLike | None = None) -> Vector:
    """Period-1 gait z* = (theta*, theta1_dot+, theta2_dot+, x_dot+) by Newton shooting on the post-impact section
    (002 Secs. 4-5): a 3-vector guess shoots on the 3-D map with x_dot+ = 0 (sticking impact: Gaits A, B, I), a
    4-vector on the 4-D map (slipping impact: Gaits C, II, III). ``jacobian``: a map Jacobian dP/dz (e.g. of a
    nearby gait) to start Newton with. ValueError if Newton does not converge or the converged step has the other
    impact kind."""
    g = np.asarray(guess, dtype=float)
    if g.size not in (3, 4):
        raise ValueError(f"guess must have 3 or 4 components (got {g.size})")
    kind = "sticking" if g.size == 3 else "slipping"
    jac0 = None if jacobian is None else np.asarray(jacobian, dtype=float) - np.eye(g.size)
    z = chord_newton(_gap(bp, actuation, g.size, kind), g, tol=NEWTON_TOL, jac0=jac0)
    if z is None:
        raise ValueError(f"fixed-point shooting from {g!r} did not converge to a {kind}-impact gait (mu = {bp.mu!r})")
    out = np.zeros(4)
    out[: g.size] = z
    return out


def map_jacobian(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                 h: float = FD_STEP) -> Matrix:
    """dP/dz of the post-impact map at z* by central differences (step ``h``, see FD_STEP): 3 x 3 when the step's
    impact sticks (then x_dot+ = 0 for every nearby state, so the 4-D map only adds an exact multiplier 0), 4 x 4
    when it slips (002 Sec. 4.2)."""
    z = np.asarray(z_star, dtype=float)
    rec = step(bp, z, actuation)
    if rec.failure is not None:
        raise ValueError(f"the step from {z!r} fails ({rec.failure})")
    dim = 3 if rec.impact == "sticking" else 4
    return central_jacobian(lambda v: return_map(bp, v, actuation), z[:dim], h)


def eigenvalues(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None,
                h: float = FD_STEP) -> NDArray[np.complex128]:
    """Eigenvalues of the linearised Poincaré map at the gait z* (:func:`map_jacobian`), sorted by modulus,
    descending (002 Figs 4.2b, 5.2a plot the largest modulus)."""
    return sort_eigenvalues(np.linalg.eigvals(map_jacobian(bp, z_star, actuation, h)).astype(complex))


def spectral_radius(bp: FrictionBiped, z_star: ArrayLike, actuation: Actuation | None = None) -> float:
    """|lambda|max of :func:`eigenvalues`."""
    return float(np.max(np.abs(eigenvalues(bp, z_star, actuation))))


@dataclass(frozen=True)
class Gait:
    """A period-1 gait: the biped, its actuation, the fixed point z* (4 components), the map Jacobian and its
    eigenvalues (sorted by modulus, descending: :func:`~mjpoincare.analysis.eigenvalues.sort_eigenvalues`), the step
    record (with forces) and its :func:`classify` label."""

    biped: FrictionBiped
    actuation: Actuation
    z: Vector
    jacobian: Matrix
    eigenvalues: NDArray[np.complex128]
    record: StepRecord
    kind: str

    @property
    def spectral_radius(self) -> float:
        """|lambda|max."""
        return float(np.max(np.abs(self.eigenvalues)))


def find_gait(bp: FrictionBiped, guess: ArrayLike, actuation: Actuation | None = None,
              jacobian: ArrayLike | None = None) -> Gait:
    """:func:`fixed_point`, :func:`map_jacobian` with its eigenvalues and the step record (with forces) in one
    (002 Secs. 4-5)."""
    act = PASSIVE if actuation is None else actuation
    z = fixed_point(bp, guess, act, jacobian)
    jac = map_jacobian(bp, z, act)
    rec = step(bp, z, act, forces=True)
    return Gait(bp, act, z, jac, sort_eigenvalues(np.linalg.eigvals(jac).astype(complex)), rec, classify(rec))


class _Solved(NamedTuple):
    z: Vector
    jacobian: Matrix


def continuation(bp: FrictionBiped, mus: Sequence[float], z_start: ArrayLike,
                 actuation: Actuation | None = None, max_halvings: int = 4, mu_start: float | None = None
                 ) -> list[Gait]:
    """Natural-parameter continuation of a gait in mu (002 Figs 4.2b, 5.2): the gait at each mu of ``mus`` (in
    order), Newton started from a predictor with the previous map Jacobian. ``z_start`` is the gait at ``mu_start``
    (refined there first), or a guess for the first mu when ``mu_start`` is None. Predictor: the secant through the
    last two gaits, or after the first one the tangent dz/dmu = (I - J)^-1 dP/dmu (dP/dmu by a central difference
    of 1e-5). Where Newton fails the mu step is halved (intermediate gaits are not returned), up to
    ``max_halvings`` times; then the continuation stops (the list is shorter than ``mus``). The length of
    ``z_start`` (3 or 4) fixes the impact kind, as in :func:`fixed_point`."""
    dim = np.asarray(z_start).size
    z_first = np.asarray(z_start, dtype=float)[:dim]
    act = PASSIVE if actuation is None else actuation
    path: list[tuple[float, Vector]] = []  # (mu, z) of every gait found, for the predictor
    jac: Matrix | None = None

    def solve(mu: float, guess: Vector) -> _Solved | None:
        b = replace(bp, mu=mu)
        try:
            z = fixed_point(b, guess, act, jac if jac is not None and jac.shape == (dim, dim) else None)
            return _Solved(z, map_jacobian(b, z, act))
        except ValueError:
            return None

    def predict(mu: float) -> Vector:
        if not path:
            return z_first
        m1, z1 = path[-1]
        if len(path) >= 2:
            m0, z0 = path[-2]
            return z1 + (z1 - z0) / (m1 - m0) * (mu - m1)
        if jac is None or jac.shape != (dim, dim):
            return z1
        d = 1e-5
        dp = (return_map(replace(bp, mu=m1 + d), z1, act) - return_map(replace(bp, mu=m1 - d), z1, act)) / (2 * d)
        if not np.all(np.isfinite(dp)):
            return z1
        return z1 + np.linalg.solve(np.eye(dim) - jac, dp) * (mu - m1)

    if mu_start is not None:
        first = solve(mu_start, z_first)
        path.append((mu_start, first.z[:dim] if first is not None else z_first))
        jac = first.jacobian if first is not None else None
    out: list[Gait] = []
    for target in (float(m) for m in mus):
        gait = solve(target, predict(target)) if not (path and path[-1][0] == target and jac is not None) else None
        if gait is None and path and path[-1][0] == target and jac is not None:
            gait = _Solved(np.concatenate([path[-1][1], np.zeros(4 - dim)]), jac)
        if gait is None and path:
            start = path[-1][0]
            for k in range(1, max_halvings + 1):
                sub = np.linspace(start, target, 2**k + 1)[1:]
                saved = (list(path), jac)
                for mu in sub:
                    gait = solve(float(mu), predict(float(mu)))
                    if gait is None:
                        break
                    path.append((float(mu), gait.z[:dim]))
                    jac = gait.jacobian
                if gait is not None:
                    break
                path, jac = saved
        if gait is None:
            break
        if not path or path[-1][0] != target:
            path.append((target, gait.z[:dim]))
        jac = gait.jacobian
        b = replace(bp, mu=target)
        rec = step(b, gait.z, act, forces=True)
        lam = sort_eigenvalues(np.linalg.eigvals(gait.jacobian).astype(complex))
        out.append(Gait(b, act, gait.z, gait.jacobian, lam, rec, classify(rec)))
    return out


def stability_loss_mu(bp: FrictionBiped, z_start: ArrayLike, mu_start: float, mu_stop: float,
                      actuation: Actuation | None = None, mu_step: float = 0.01, tol: float = 1e-5) -> float:
    """mu at which |lambda|max of a gait continued from (z_start, mu_start) towards mu_stop crosses 1 (002 Sec. 4.2:
    Gait B "loses stability at mu ~ 0.11"; Sec. 5: Gait I "stable for mu > 0.11"): :func:`continuation` on a grid of
    at most ``mu_step``, then regula falsi (Illinois) on |lambda|max(mu) - 1 inside the bracketing grid interval to
    |lambda|max - 1 < 1e-6 (the finite-difference noise) or a bracket below ``tol``, each Newton started from the
    linear interpolation of the bracketing gaits with their map Jacobian. ValueError if it does not cross on
    [mu_stop, mu_start] or the branch ends first."""
    n = max(1, math.ceil(abs(mu_start - mu_stop) / mu_step - 1e-9))
    grid = np.linspace(mu_start, mu_stop, n + 1)
    gaits = continuation(bp, grid, z_start, actuation, mu_start=mu_start)
    dim = np.asarray(z_start).size
    rho = [g.spectral_radius - 1.0 for g in gaits]
    for i in range(len(gaits) - 1):
        if rho[i] * rho[i + 1] <= 0.0:
            lo, hi = gaits[i], gaits[i + 1]

            def f(mu: float, lo: Gait = lo, hi: Gait = hi) -> float:
                w = (mu - lo.biped.mu) / (hi.biped.mu - lo.biped.mu)
                guess = (1 - w) * lo.z[:dim] + w * hi.z[:dim]
                b = replace(bp, mu=mu)
                z = fixed_point(b, guess, actuation, lo.jacobian)
                return spectral_radius(b, z, actuation) - 1.0

            # Illinois regula falsi: |lambda|max(mu) is smooth and nearly linear inside one grid interval
            a, fa, b, fb = lo.biped.mu, rho[i], hi.biped.mu, rho[i + 1]
            for _ in range(40):
                if fb == fa:
                    break
                c = b - fb * (b - a) / (fb - fa)
                fc = f(c)
                if fc * fb < 0.0:
                    a, fa = b, fb
                else:
                    fa *= 0.5
                b, fb = c, fc
                if abs(fc) < 1e-6 or abs(b - a) < tol:
                    break
            return float(b)
    raise ValueError(f"|lambda|max does not cross 1 on the continued branch ({len(gaits)} of {grid.size} gaits)")
