"""A polynomial return map read on a family of cycles (a neutral direction), with the drift along the family.

A map whose fixed points form a one-parameter family (multiplier 1) has no isolated fixed point; the fit is read at
the member with ``x[0]`` at an anchor, as ``F(x) = x + c t`` with ``c`` the drift per iterate along the family's
tangent ``t``, linearised there, with a bootstrap over the pairs. Only numpy is used.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
from mjpoincare.analysis.eigenvalues import match_eigenvalues, sort_eigenvalues
from mjpoincare.analysis.returnmap_polynomial import _feature_gradient, _features, _monomials, _pairs


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
