"""Empirical Poincaré return maps fitted from section samples.

A batch of simulated trajectories gives, on a Poincaré section, consecutive samples
``x_k -> x_{k+1}``.  This module fits a low-degree polynomial map ``x_next = F(x)`` to those
pairs by least squares, locates its fixed point, linearises it there and estimates the
uncertainty of all of it by a bootstrap over the pairs.  The resulting multipliers
(eigenvalues of the Jacobian) are what the analytic results are compared against.

A map with a one-parameter family of fixed points (a neutral direction, multiplier 1) has no
isolated fixed point; :func:`fit_drifting_cycle` reads such a map at one member of the family
instead, together with the drift along the family that a biased map shows there.

Only numpy and scipy are used.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from itertools import combinations_with_replacement
from typing import Any

import numpy as np
from mjpoincare.analysis.checks import jsonable
from mjpoincare.analysis.eigenvalues import match_eigenvalues, sort_eigenvalues

__all__ = ["DriftingCycleFit", "ReturnMapFit", "convergence_ratio", "fit_drifting_cycle", "fit_return_map",
           "regress_at", "replicate_list", "sample_pairs"]

_SUPPORTED_DEGREES = (1, 2, 3)
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


def sample_pairs(sequences: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Build the pairs ``(x_k, x_{k+1})`` from sequences of consecutive section samples.

    Args:
        sequences: one array per trajectory, of shape ``(n_i, d)`` or ``(n_i,)`` (then ``d = 1``),
            holding consecutive section crossings.  A row containing NaN marks a missing crossing:
            no pair is formed with it, so pairs never span a gap.  Pairs never span two sequences.

    Returns:
        ``(x, x_next)``, each of shape ``(N, d)``.

    Raises:
        ValueError: if no sequence is given, a sequence has more than two dimensions, or the
            sequences disagree on ``d``.
    """
    if len(sequences) == 0:
        raise ValueError("sample_pairs needs at least one sequence")
    dim: int | None = None
    firsts: list[np.ndarray] = []
    seconds: list[np.ndarray] = []
    for index, sequence in enumerate(sequences):
        samples = np.asarray(sequence, dtype=float)
        if samples.ndim == 1:
            samples = samples[:, None]
        if samples.ndim != 2:
            raise ValueError(f"sequence {index} must have shape (n,) or (n, d), got {samples.shape}")
        if dim is None:
            dim = samples.shape[1]
        elif samples.shape[1] != dim:
            raise ValueError(f"sequence {index} has dimension {samples.shape[1]}, expected {dim}")
        present = ~np.isnan(samples).any(axis=1)
        keep = present[:-1] & present[1:]
        firsts.append(samples[:-1][keep])
        seconds.append(samples[1:][keep])
    return np.concatenate(firsts, axis=0), np.concatenate(seconds, axis=0)


def _monomials(dim: int, degree: int) -> list[tuple[int, ...]]:
    """Index tuples of all monomials of total degree ``<= degree`` (``()`` is the constant)."""
    terms: list[tuple[int, ...]] = []
    for order in range(degree + 1):
        terms.extend(combinations_with_replacement(range(dim), order))
    return terms


@lru_cache(maxsize=64)
def _exponents(terms: tuple[tuple[int, ...], ...], dim: int) -> np.ndarray:
    """``(p, d)`` integer exponents of the monomials ``terms`` (read-only)."""
    out = np.zeros((len(terms), dim), dtype=int)
    for row, term in enumerate(terms):
        for var in term:
            out[row, var] += 1
    out.setflags(write=False)
    return out


def _features(z: np.ndarray, terms: list[tuple[int, ...]]) -> np.ndarray:
    """Regression matrix ``(N, p)`` of the monomials evaluated at the rows of ``z`` ``(N, d)``."""
    powers = _exponents(tuple(terms), z.shape[1])
    return np.prod(z[:, None, :] ** powers[None, :, :], axis=2)


def _feature_gradient(z: np.ndarray, terms: list[tuple[int, ...]]) -> np.ndarray:
    """Derivative ``(p, d)`` of the monomials with respect to ``z`` at the single point ``z``: column j is
    e_j z_j^(e_j - 1) times the other factors, for each monomial with exponents e."""
    powers = _exponents(tuple(terms), z.size)
    grad = np.zeros(powers.shape)
    for j in range(z.size):
        has = powers[:, j] > 0
        lowered = powers[has].copy()
        lowered[:, j] -= 1
        grad[has, j] = powers[has, j] * np.prod(z[None, :] ** lowered, axis=1)
    return grad


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


def _as_2d(array: np.ndarray, name: str) -> np.ndarray:
    """Return ``array`` as float ``(N, d)``, promoting ``(N,)`` to ``(N, 1)``."""
    out = np.asarray(array, dtype=float)
    if out.ndim == 1:
        out = out[:, None]
    if out.ndim != 2:
        raise ValueError(f"{name} must have shape (N,) or (N, d), got {np.shape(array)}")
    return out


def _pairs(x: np.ndarray, x_next: np.ndarray, degree: int) -> tuple[np.ndarray, np.ndarray]:
    """``(x, x_next)`` as float ``(N, d)`` arrays of one shape; raise on mismatched shapes or a bad degree."""
    xs = _as_2d(x, "x")
    ys = _as_2d(x_next, "x_next")
    if xs.shape != ys.shape:
        raise ValueError(f"x and x_next must have the same shape, got {xs.shape} and {ys.shape}")
    if degree not in _SUPPORTED_DEGREES:
        raise ValueError(f"degree must be one of {_SUPPORTED_DEGREES}, got {degree}")
    return xs, ys


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


@dataclass(frozen=True)
class DriftingCycleFit:
    """Result of :func:`fit_drifting_cycle`.

    Attributes:
        fixed_point: ``(d,)`` the fitted map's cycle ``x`` with ``x[0]`` at the anchor.
        drift: its change of ``x[0]`` per iterate, ``F(x) = x + drift * t``.
        jacobian: ``(d, d)`` derivative ``dF/dx`` at ``fixed_point``.
        eigenvalues: ``(d,)`` complex multipliers, ordered as in :class:`ReturnMapFit`.
        fixed_point_std: ``(d,)`` bootstrap standard deviation of ``fixed_point``.
        drift_std: bootstrap standard deviation of ``drift``.
        eigenvalue_std: ``(d,)`` complex, as in :class:`ReturnMapFit`.
        label_std: bootstrap standard deviation of each value the ``label`` callable names.
        residual_rms: ``(d,)`` root-mean-square one-step residual of the fit.
        n_pairs: number of pairs used.
        degree: degree of the fit used (1 when the requested one had no cycle near the samples).
        replicates: number of bootstrap replicates kept.
        eigenvalue_replicates: ``(replicates, d)`` complex: each kept replicate's multipliers, matched to
            ``eigenvalues``.

    The standard deviations are NaN when fewer than two replicates were kept.
    """

    fixed_point: np.ndarray
    drift: float
    jacobian: np.ndarray
    eigenvalues: np.ndarray
    fixed_point_std: np.ndarray
    drift_std: float
    eigenvalue_std: np.ndarray
    label_std: dict[str, float]
    residual_rms: np.ndarray
    n_pairs: int
    degree: int
    replicates: int
    eigenvalue_replicates: np.ndarray


def _drifting_cycle(coef: np.ndarray, terms: list[tuple[int, ...]], center: np.ndarray, scale: np.ndarray,
                    anchor: float, t: np.ndarray, start: tuple[np.ndarray, float] | None = None
                    ) -> tuple[np.ndarray, float, np.ndarray]:
    """``(x, c, DF(x))`` with ``F(x) = x + c t`` and ``x[0] = anchor``, for ``F(x) = phi((x - center) / scale) @ coef``
    (``coef`` ``(p, d)``, ``t`` ``(d,)`` with ``t[0] = 1``), by Newton on ``(x[1:], c)`` from ``start`` (default: the
    center, no drift)."""
    dim = center.size

    def value(x: np.ndarray) -> np.ndarray:
        return _features(((x - center) / scale)[None, :], terms)[0] @ coef

    def jac(x: np.ndarray) -> np.ndarray:
        return (coef.T @ _feature_gradient((x - center) / scale, terms)) / scale[None, :]

    if start is None:
        x, drift = np.array(center, dtype=float), 0.0
    else:
        x, drift = np.array(start[0], dtype=float), float(start[1])
    x[0] = anchor
    for _ in range(50):
        step = np.linalg.solve(np.column_stack([(jac(x) - np.eye(dim))[:, 1:], -t]), -(value(x) - x - drift * t))
        x[1:] += step[: dim - 1]
        drift += step[dim - 1]
        if not np.all(np.isfinite(x)):
            break
        if np.linalg.norm(step) <= 1e-13 * (1.0 + np.linalg.norm(x)):
            return x, float(drift), jac(x)
    raise ValueError("no cycle of the fitted map near the samples (Newton did not converge)")


def fit_drifting_cycle(
    x: np.ndarray,
    x_next: np.ndarray,
    tangent: np.ndarray,
    anchor: float,
    *,
    degree: int = 2,
    bootstrap: int = 100,
    seed: int = 0,
    label: Callable[[np.ndarray], Mapping[str, float]] | None = None,
) -> DriftingCycleFit:
    """Fit ``x_next = F(x)`` by a polynomial and linearise it on a family of cycles parametrised by ``x[0]``.

    When the fixed points form a family with tangent ``tangent`` (``tangent[0] != 0``; its multiplier is 1), a
    fitted map has no isolated fixed point, and a biased one moves its cycle along the family. The cycle read here
    is ``F(x) = x + c t`` with ``t = tangent / tangent[0]`` and ``x[0] = anchor``, solved by Newton for
    ``(x[1:], c)`` from the affine fit's cycle; ``c`` is the drift per iterate. The regression is numpy's least
    squares of ``x_next`` on the monomials of total degree ``<= degree`` in ``z = (x - mean) / std``; when the
    polynomial map has no such cycle near the samples (a noisy quadratic term), the affine fit is used instead.
    The bootstrap resamples pairs with replacement, refits, and solves from the point estimate; replicates where
    that fails, or where ``label`` (named values of a replicate's Jacobian) raises ``ValueError``, are skipped.

    Args:
        x: ``(N, d)`` section states.
        x_next: ``(N, d)`` the next crossing of each.
        tangent: ``(d,)`` tangent of the family of fixed points.
        anchor: the value of ``x[0]`` at which the cycle is read.
        degree: polynomial degree (1, 2 or 3).
        bootstrap: number of bootstrap replicates (0 disables; the stds are then NaN).
        seed: seed of the bootstrap resampling.
        label: named values ``{name: value}`` of a ``(d, d)`` Jacobian whose bootstrap spread is wanted.

    Returns:
        The :class:`DriftingCycleFit`.

    Raises:
        ValueError: on bad shapes or degree, too few pairs, or no cycle of the affine fit near the samples.
    """
    xs, ys = _pairs(x, x_next, degree)
    n_pairs, dim = xs.shape
    terms = _monomials(dim, degree)
    if n_pairs <= len(terms):
        raise ValueError(f"too few pairs ({n_pairs}) for a degree-{degree} map in {dim}-D ({len(terms)} coefficients)")
    center, spread = xs.mean(axis=0), xs.std(axis=0)
    scale = np.where(spread > 0.0, spread, 1.0)
    zs = (xs - center) / scale
    t = tangent / tangent[0]
    linear = _monomials(dim, 1)
    c_lin, *_ = np.linalg.lstsq(_features(zs, linear), ys, rcond=None)
    start = _drifting_cycle(c_lin, linear, center, scale, anchor, t)[:2]
    try:
        phi = _features(zs, terms)
        coef, *_ = np.linalg.lstsq(phi, ys, rcond=None)
        point, drift, jacobian = _drifting_cycle(coef, terms, center, scale, anchor, t, start)
    except ValueError:
        terms, degree = linear, 1
        phi = _features(zs, terms)
        coef = c_lin
        point, drift, jacobian = _drifting_cycle(coef, terms, center, scale, anchor, t, start)
    eigenvalues = sort_eigenvalues(np.linalg.eigvals(jacobian).astype(complex))

    rng = np.random.default_rng(seed)
    replicates: list[list[float]] = []
    spectra: list[np.ndarray] = []
    names: list[str] = []
    for _ in range(bootstrap):
        rows = rng.integers(0, n_pairs, size=n_pairs)
        try:
            c_rep, *_ = np.linalg.lstsq(phi[rows], ys[rows], rcond=None)
            p_rep, d_rep, a_rep = _drifting_cycle(c_rep, terms, center, scale, anchor, t, (point, drift))
            labels = label(a_rep) if label is not None else {}
        except (ValueError, np.linalg.LinAlgError):
            continue
        names = list(labels)
        replicates.append([*p_rep, d_rep, *labels.values()])
        spectra.append(match_eigenvalues(eigenvalues, np.linalg.eigvals(a_rep)))
    std = np.std(replicates, axis=0, ddof=1) if len(replicates) >= 2 else np.full(dim + 1 + len(names), np.nan)
    eigenvalue_std = (np.std(np.real(spectra), axis=0, ddof=1) + 1j * np.std(np.imag(spectra), axis=0, ddof=1)
                      if len(spectra) >= 2 else np.full(dim, np.nan + 1j * np.nan))
    return DriftingCycleFit(
        fixed_point=point,
        drift=drift,
        jacobian=jacobian,
        eigenvalues=eigenvalues,
        fixed_point_std=std[:dim],
        drift_std=float(std[dim]),
        eigenvalue_std=eigenvalue_std,
        label_std=dict(zip(names, std[dim + 1 :].tolist(), strict=True)),
        residual_rms=np.sqrt(np.mean((ys - phi @ coef) ** 2, axis=0)),
        n_pairs=n_pairs,
        degree=degree,
        replicates=len(replicates),
        eigenvalue_replicates=np.array(spectra, dtype=complex).reshape(-1, dim),
    )


def regress_at(point: np.ndarray, samples: np.ndarray, values: np.ndarray, degree: int = 1) -> float:
    """A per-step quantity read at the fixed point: polynomial least squares (total degree ``degree``; 1: affine)
    of ``values`` (n,) on the section samples ``samples`` (n, d), evaluated at ``point`` (d,): e.g. a gait's step
    period and length from the steps of starts around its fixed point. An affine fit of a curved quantity is biased
    by the samples' spread about ``point``; degree 2 removes that bias at first order. NaN unless there are more
    samples than the polynomial has terms."""
    samples = np.asarray(samples, float).reshape(len(values), -1)
    terms = _monomials(samples.shape[1], degree)
    if len(values) <= len(terms):
        return float("nan")
    design = _features(samples - point, terms)
    coef, *_ = np.linalg.lstsq(design, values, rcond=None)
    return float(coef[0])


def convergence_ratio(sequence: np.ndarray, fixed_point: float, noise_floor: float = 0.0) -> float:
    """Fit-free multiplier estimate of a 1-D map: median of ``|x_{k+1} - x*| / |x_k - x*|``.

    Valid for a positive real multiplier (for a negative one it returns its modulus).  Steps
    where ``|x_k - x*| <= noise_floor`` (the ratio would be dominated by noise) or where either
    sample is NaN are ignored.

    Args:
        sequence: ``(n,)`` (or ``(n, 1)``) consecutive section samples of one trajectory.
        fixed_point: the fixed point ``x*``.
        noise_floor: distance from ``x*`` below which a step is ignored (>= 0).

    Returns:
        The median ratio.

    Raises:
        ValueError: on a non-1-D sequence, a negative noise floor, or no usable step.
    """
    samples = np.asarray(sequence, dtype=float)
    if samples.ndim == 2 and samples.shape[1] == 1:
        samples = samples[:, 0]
    if samples.ndim != 1:
        raise ValueError(f"convergence_ratio needs a 1-D sequence, got shape {np.shape(sequence)}")
    if noise_floor < 0:
        raise ValueError(f"noise_floor must be >= 0, got {noise_floor}")
    distance = np.abs(samples - float(fixed_point))
    before, after = distance[:-1], distance[1:]
    usable = np.isfinite(before) & np.isfinite(after) & (before > noise_floor)
    if not np.any(usable):
        raise ValueError("no step of the sequence is farther than noise_floor from the fixed point")
    return float(np.median(after[usable] / before[usable]))
