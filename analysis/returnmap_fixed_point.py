"""A polynomial return map fitted by least squares, linearised at its isolated fixed point, with a bootstrap.

The map ``x_next = F(x)`` is fitted to section pairs in centred and scaled coordinates, its fixed point found (a
linear solve for an affine fit, Newton otherwise), its Jacobian and multipliers taken there, and the uncertainty of
all of it estimated by a bootstrap over the pairs. Only numpy is used.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.eigenvalues import match_eigenvalues, sort_eigenvalues
from mjpoincare.analysis.returnmap_polynomial import _feature_gradient, _features, _monomials, _pairs

_NEWTON_MAX_ITER = 60
_NEWTON_STEP_TOL = 1e-12
_GRAM_RTOL = 1e-12  # bootstrap replicates with cond(regression matrix) > 1e6 are skipped
_REPLICATE_DIGITS = 7  # significant digits of the bootstrap eigenvalues in JSON (float32 precision: a plot's cloud)


@dataclass(frozen=True)
class ReturnMapFit:
    """Result of :func:`fit_return_map`.

    Attributes:
        fixed_point: ``(d,)`` fixed point ``x*`` of the fitted map.
        jacobian: ``(d, d)`` derivative ``dF/dx`` of the fitted map at ``x*``.
        eigenvalues: ``(d,)`` complex multipliers, sorted by modulus descending; ties in modulus
            are ordered by angle descending (so a conjugate pair lists the member with positive
            imaginary part first).
        fixed_point_std: ``(d,)`` bootstrap standard deviation of ``fixed_point``.
        eigenvalue_std: ``(d,)`` complex: ``std(real part) + 1j * std(imag part)`` over the
            bootstrap, each replicate's eigenvalues matched to the point estimate by optimal
            assignment.
        jacobian_std: ``(d, d)`` bootstrap standard deviation of ``jacobian``.
        residual_rms: ``(d,)`` root-mean-square one-step residual ``x_next - F(x)`` of the fit.
        n_pairs: number of pairs used.
        degree: total polynomial degree of the fit (1 affine, 2 quadratic, 3 cubic).
        condition: condition number of the centred and scaled regression matrix.
        eigenvalue_replicates: ``(n, d)`` complex: each kept bootstrap replicate's multipliers, matched to
            ``eigenvalues`` (the samples ``eigenvalue_std`` is the spread of).

    The standard deviations are NaN when fewer than two bootstrap replicates were available.
    """

    fixed_point: np.ndarray
    jacobian: np.ndarray
    eigenvalues: np.ndarray
    fixed_point_std: np.ndarray
    eigenvalue_std: np.ndarray
    jacobian_std: np.ndarray
    residual_rms: np.ndarray
    n_pairs: int
    degree: int
    condition: float
    eigenvalue_replicates: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        """Return a JSON-ready dict: arrays as (nested) lists, complex numbers as ``[re, im]``.

        Non-finite floats (e.g. NaN standard deviations) become ``None`` so that the output is
        strict JSON. The replicates' multipliers are rounded to float32 precision (:func:`replicate_list`).
        """
        def real(a: np.ndarray) -> Any:
            return jsonable(np.asarray(a, dtype=float))

        def cplx(a: np.ndarray) -> Any:
            return jsonable(np.asarray(a, dtype=complex))

        return {
            "fixed_point": real(self.fixed_point),
            "jacobian": real(self.jacobian),
            "eigenvalues": cplx(self.eigenvalues),
            "fixed_point_std": real(self.fixed_point_std),
            "eigenvalue_std": cplx(self.eigenvalue_std),
            "jacobian_std": real(self.jacobian_std),
            "residual_rms": real(self.residual_rms),
            "n_pairs": int(self.n_pairs),
            "degree": int(self.degree),
            "condition": jsonable(float(self.condition)),
            "eigenvalue_replicates": replicate_list(self.eigenvalue_replicates),
        }


def replicate_list(samples: np.ndarray) -> list[list[list[float | None]]]:
    """Bootstrap multipliers ``(n, d)`` complex as JSON: per replicate a list of ``[re, im]``, each rounded to
    float32 precision (7 significant digits; enough to draw the cloud, half the text of full precision)."""
    return [[[jsonable(float(f"{v:.{_REPLICATE_DIGITS}g}")) for v in (z.real, z.imag)] for z in row]
            for row in np.asarray(samples, dtype=complex)]


@dataclass(frozen=True)
class _Scaled:
    """A fitted map in scaled coordinates ``z = (x - center) / scale``: ``z_next = phi(z) @ coef``."""

    coef: np.ndarray
    terms: list[tuple[int, ...]]

    def value(self, z: np.ndarray) -> np.ndarray:
        """Evaluate the map at a single point ``z`` ``(d,)``."""
        return _features(z[None, :], self.terms)[0] @ self.coef

    def jacobian(self, z: np.ndarray) -> np.ndarray:
        """Derivative ``(d, d)`` of the map at ``z``, ``[i, j] = d z_next_i / d z_j``."""
        return self.coef.T @ _feature_gradient(z, self.terms)


def _least_squares(phi: np.ndarray, target: np.ndarray) -> tuple[np.ndarray, float]:
    """Least-squares coefficients and condition number; raise if ``phi`` is rank-deficient."""
    u, sing, vt = np.linalg.svd(phi, full_matrices=False)
    tol = sing[0] * max(phi.shape) * np.finfo(float).eps
    if sing[0] == 0.0 or sing[-1] <= tol:
        raise ValueError(
            "rank-deficient regression: samples do not span the section; "
            "start the batch from more spread initial conditions"
        )
    coef = vt.T @ ((u.T @ target) / sing[:, None])
    return coef, float(sing[0] / sing[-1])


def _resampled_least_squares(phi: np.ndarray, target: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """Least squares on the rows of ``phi`` repeated ``counts`` times (a bootstrap replicate).

    Solved by the weighted normal equations, which is much cheaper than an SVD of the resampled
    matrix; raises ``ValueError`` when the replicate is (numerically) rank-deficient.
    """
    weighted = counts[:, None] * phi
    gram = phi.T @ weighted
    spectrum = np.linalg.eigvalsh(gram)
    if spectrum[-1] <= 0.0 or spectrum[0] <= spectrum[-1] * _GRAM_RTOL:
        raise ValueError("rank-deficient bootstrap replicate")
    return np.linalg.solve(gram, weighted.T @ target)


def _fixed_point(model: _Scaled, degree: int, start: np.ndarray | None) -> np.ndarray:
    """Fixed point of the scaled map: a linear solve for degree 1, Newton otherwise.

    ``start`` is the Newton initial guess (ignored for degree 1).
    """
    dim = model.coef.shape[1]
    identity = np.eye(dim)
    if degree == 1:
        try:
            return np.linalg.solve(identity - model.coef[1:].T, model.coef[0])
        except np.linalg.LinAlgError:
            raise ValueError("fitted affine map has a multiplier 1: no isolated fixed point") from None
    z = np.array(start, dtype=float)
    for _ in range(_NEWTON_MAX_ITER):
        try:
            step = np.linalg.solve(model.jacobian(z) - identity, z - model.value(z))
        except np.linalg.LinAlgError:
            raise ValueError("Newton for the fixed point hit a singular Jacobian (multiplier 1)") from None
        z = z + step
        if not np.all(np.isfinite(z)):
            break
        if np.linalg.norm(step) <= _NEWTON_STEP_TOL * (1.0 + np.linalg.norm(z)):
            return z
    raise ValueError(
        "Newton for the fixed point of the polynomial map did not converge from the affine "
        "estimate; the fitted map may have no fixed point near the samples (try degree=1)"
    )


def fit_return_map(
    x: np.ndarray,
    x_next: np.ndarray,
    *,
    degree: int = 1,
    bootstrap: int = 200,
    seed: int = 0,
    center: np.ndarray | None = None,
) -> ReturnMapFit:
    """Fit ``x_next = F(x)`` by a polynomial and linearise it at its fixed point.

    The regression uses all monomials of total degree ``<= degree`` in the coordinates
    ``z = (x - center) / scale`` (``scale`` = per-coordinate std of ``x``, 1 where that is zero),
    with ``z_next`` scaled the same way.  The fixed point solves ``(I - A) x* = b`` for an affine
    fit; for a quadratic or cubic fit it is found by Newton's method on ``F(x) - x`` started from the
    affine fit's fixed point.  Uncertainties come from a bootstrap over pairs (rows resampled with
    replacement, replicates whose regression is degenerate are skipped), fully determined by
    ``seed``.

    Args:
        x: ``(N, d)`` or ``(N,)`` section states.
        x_next: same shape, the next crossing of each state (e.g. from :func:`sample_pairs`).
        degree: 1 (affine), 2 (quadratic) or 3 (cubic: when the samples spread far enough for the map's
            cubic terms to bias the quadratic fit's Jacobian).
        bootstrap: number of bootstrap replicates (0 disables; the stds are then NaN).
        seed: seed of the bootstrap resampling.
        center: centring point ``(d,)``; defaults to the mean of ``x``.

    Returns:
        The :class:`ReturnMapFit`.

    Raises:
        ValueError: on bad shapes or degree, non-finite inputs, fewer pairs than coefficients + 1,
            a rank-deficient regression, or a fitted map without a computable fixed point.
    """
    xs, ys = _pairs(x, x_next, degree)
    if bootstrap < 0:
        raise ValueError(f"bootstrap must be >= 0, got {bootstrap}")
    if not (np.all(np.isfinite(xs)) and np.all(np.isfinite(ys))):
        raise ValueError("x and x_next must be finite (remove missing crossings with sample_pairs)")
    n_pairs, dim = xs.shape
    terms = _monomials(dim, degree)
    if n_pairs <= len(terms):
        raise ValueError(
            f"too few pairs: {n_pairs} given, a degree-{degree} fit in {dim} dimensions has "
            f"{len(terms)} coefficients per coordinate and needs at least {len(terms) + 1} pairs"
        )

    if center is None:
        origin = xs.mean(axis=0)
    else:
        origin = np.broadcast_to(np.asarray(center, dtype=float), (dim,)).copy()
        if not np.all(np.isfinite(origin)):
            raise ValueError("center must be finite")
    spread = xs.std(axis=0)
    negligible = spread <= 1e-12 * np.maximum(1.0, np.abs(origin))
    scale = np.where(negligible, 1.0, spread)
    zs = (xs - origin) / scale
    zs_next = (ys - origin) / scale

    phi = _features(zs, terms)
    coef, condition = _least_squares(phi, zs_next)
    model = _Scaled(coef, terms)
    start = None
    if degree >= 2:
        affine = _Scaled(_least_squares(phi[:, : dim + 1], zs_next)[0], terms[: dim + 1])
        start = _fixed_point(affine, 1, None)
    z_star = _fixed_point(model, degree, start)

    def to_x_jacobian(jac_z: np.ndarray) -> np.ndarray:
        """Convert a Jacobian in scaled coordinates to original units."""
        return jac_z * scale[:, None] / scale[None, :]

    fixed_point = origin + scale * z_star
    jacobian = to_x_jacobian(model.jacobian(z_star))
    eigenvalues = sort_eigenvalues(np.linalg.eigvals(jacobian).astype(complex))
    residual_rms = np.sqrt(np.mean(((zs_next - phi @ coef) * scale) ** 2, axis=0))

    rng = np.random.default_rng(seed)
    boot_points: list[np.ndarray] = []
    boot_jacobians: list[np.ndarray] = []
    boot_eigenvalues: list[np.ndarray] = []
    for _ in range(bootstrap):
        counts = np.bincount(rng.integers(0, n_pairs, size=n_pairs), minlength=n_pairs)
        try:
            replicate = _Scaled(_resampled_least_squares(phi, zs_next, counts.astype(float)), terms)
            z_rep = _fixed_point(replicate, degree, z_star)
        except ValueError:
            continue
        jac_rep = to_x_jacobian(replicate.jacobian(z_rep))
        boot_points.append(origin + scale * z_rep)
        boot_jacobians.append(jac_rep)
        boot_eigenvalues.append(match_eigenvalues(eigenvalues, np.linalg.eigvals(jac_rep).astype(complex)))

    if len(boot_points) >= 2:
        eig_samples = np.array(boot_eigenvalues)
        fixed_point_std = np.std(boot_points, axis=0, ddof=1)
        jacobian_std = np.std(boot_jacobians, axis=0, ddof=1)
        eigenvalue_std = np.std(eig_samples.real, axis=0, ddof=1) + 1j * np.std(
            eig_samples.imag, axis=0, ddof=1
        )
    else:
        fixed_point_std = np.full(dim, np.nan)
        jacobian_std = np.full((dim, dim), np.nan)
        eigenvalue_std = np.full(dim, np.nan + 1j * np.nan)

    return ReturnMapFit(
        fixed_point=fixed_point,
        jacobian=jacobian,
        eigenvalues=eigenvalues,
        fixed_point_std=fixed_point_std,
        eigenvalue_std=eigenvalue_std,
        jacobian_std=jacobian_std,
        residual_rms=residual_rms,
        n_pairs=n_pairs,
        degree=degree,
        condition=condition,
        eigenvalue_replicates=np.array(boot_eigenvalues, dtype=complex).reshape(-1, dim),
    )
