"""Tests of analysis.returnmap on synthetic maps whose fixed points and multipliers are known."""

from __future__ import annotations

import json
import math
from collections.abc import Callable

import numpy as np
import pytest
from mjpoincare.analysis.returnmap import (
    ReturnMapFit,
    convergence_ratio,
    fit_drifting_cycle,
    fit_return_map,
    regress_at,
    sample_pairs,
)

RHO, THETA, REAL = 0.9, 0.4, 0.3


def rotation(theta: float) -> np.ndarray:
    """2x2 rotation matrix."""
    return np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])


def conjugated(block: np.ndarray, seed: int) -> np.ndarray:
    """``T @ block @ T^-1`` for a random, well-conditioned ``T``."""
    dim = block.shape[0]
    t = np.eye(dim) + 0.5 * np.random.default_rng(seed).normal(size=(dim, dim))
    return t @ block @ np.linalg.inv(t)


def affine_map(matrix: np.ndarray, fixed: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """Map ``x -> fixed + matrix (x - fixed)`` acting on rows."""
    return lambda x: fixed + (x - fixed) @ matrix.T


def cloud(fixed: np.ndarray, n: int, seed: int, spread: float = 1.0) -> np.ndarray:
    """``n`` Gaussian section samples around ``fixed``."""
    return fixed + spread * np.random.default_rng(seed).normal(size=(n, fixed.size))


def sorted_truth(values: list[complex]) -> np.ndarray:
    """Known multipliers in the documented order (modulus desc., then angle desc.)."""
    return np.array(sorted(values, key=lambda z: (-round(abs(z), 12), -np.angle(z))), dtype=complex)


MAP_2D = conjugated(RHO * rotation(THETA), seed=1)
MAP_3D = conjugated(np.block([[RHO * rotation(THETA), np.zeros((2, 1))], [np.zeros((1, 2)), REAL]]), seed=2)
FIXED_2D = np.array([0.7, -1.2])
FIXED_3D = np.array([1.0, 2.0, -0.5])
TRUE_2D = sorted_truth([RHO * np.exp(1j * THETA), RHO * np.exp(-1j * THETA)])
TRUE_3D = sorted_truth([RHO * np.exp(1j * THETA), RHO * np.exp(-1j * THETA), REAL])


# --- sample_pairs ---------------------------------------------------------------------------------


def test_regress_at_reads_an_affine_quantity_at_the_point() -> None:
    """Exact for an affine quantity wherever the samples are; the point need not be among them."""
    samples = np.random.default_rng(2).normal(size=(20, 3)) + 5.0
    values = 1.5 + samples @ np.array([0.2, -0.7, 0.4])
    point = np.array([1.0, -2.0, 0.5])
    assert regress_at(point, samples, values) == pytest.approx(1.5 + point @ np.array([0.2, -0.7, 0.4]), abs=1e-12)


def test_regress_at_1d_samples_and_noise_averaged() -> None:
    x = np.linspace(-1.0, 1.0, 401)
    noise = 0.01 * np.random.default_rng(4).normal(size=x.size)
    assert regress_at(np.array([0.25]), x[:, None], 3.0 - 2.0 * x + noise) == pytest.approx(2.5, abs=2e-3)


def test_sample_pairs_skips_gaps_and_sequence_boundaries() -> None:
    first = np.array([0.0, 1.0, np.nan, 3.0, 4.0, 5.0])
    second = np.array([10.0, 11.0])
    lonely = np.array([20.0])
    x, x_next = sample_pairs([first, second, lonely])
    assert x.shape == x_next.shape == (4, 1)
    assert x[:, 0].tolist() == [0.0, 3.0, 4.0, 10.0]
    assert x_next[:, 0].tolist() == [1.0, 4.0, 5.0, 11.0]


def test_sample_pairs_2d_partial_nan_row_is_a_gap() -> None:
    seq = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, np.nan], [3.0, 3.0], [4.0, 4.0]])
    x, x_next = sample_pairs([seq])
    assert x[:, 0].tolist() == [0.0, 3.0]
    assert x_next[:, 0].tolist() == [1.0, 4.0]


def test_sample_pairs_rejects_mixed_dimensions_and_empty_input() -> None:
    with pytest.raises(ValueError, match="dimension"):
        sample_pairs([np.zeros((3, 2)), np.zeros((3, 3))])
    with pytest.raises(ValueError, match="at least one"):
        sample_pairs([])


# --- 1-D maps -------------------------------------------------------------------------------------


@pytest.mark.parametrize("multiplier", [0.5, -0.7, 1.8])
def test_affine_1d_multiplier_and_fixed_point(multiplier: float) -> None:
    """Contracting (0.5), rocking (-0.7) and unstable (1.8) maps: x* = 2, exact data."""
    x = np.linspace(1.0, 3.0, 15)
    fit = fit_return_map(x, 2.0 + multiplier * (x - 2.0), bootstrap=20)
    assert fit.fixed_point == pytest.approx([2.0], abs=1e-12)
    assert fit.eigenvalues == pytest.approx([multiplier], abs=1e-12)
    assert fit.jacobian.shape == (1, 1)
    assert fit.residual_rms[0] < 1e-12
    assert fit.n_pairs == 15 and fit.degree == 1


B_SQRT, K_SQRT = 0.6, 1.0
W_STAR = B_SQRT * np.sqrt(K_SQRT / (1.0 - B_SQRT**2))  # fixed point of w -> b sqrt(w^2 + K)
SLOPE_STAR = B_SQRT**2  # P'(w*) = b w* / sqrt(w*^2 + K) = b^2


def sqrt_map(w: np.ndarray) -> np.ndarray:
    """The nonlinear 1-D map P(w) = b sqrt(w^2 + K)."""
    return B_SQRT * np.sqrt(w**2 + K_SQRT)


def test_sqrt_map_quadratic_beats_affine_over_20_percent_spread() -> None:
    """Samples +-20% around w*: the quadratic fit removes the affine fit's fixed-point bias.

    (At the centre of a symmetric sample both fits share the same slope; the leftover
    derivative bias of about P''' h^2 / 10 ~ 1e-3 comes from the cubic term.)
    """
    w = W_STAR * np.random.default_rng(3).uniform(0.8, 1.2, 200)
    lin = fit_return_map(w, sqrt_map(w), degree=1, bootstrap=0)
    quad = fit_return_map(w, sqrt_map(w), degree=2, bootstrap=0)
    lin_err = abs(lin.fixed_point[0] - W_STAR)
    quad_err = abs(quad.fixed_point[0] - W_STAR)
    assert quad_err < 1e-4 * W_STAR
    assert quad_err < lin_err / 20
    assert quad.residual_rms[0] < lin.residual_rms[0] / 10
    assert abs(quad.eigenvalues[0].real - SLOPE_STAR) < 3e-3


def test_sqrt_map_quadratic_beats_affine_on_one_sided_samples() -> None:
    """Trajectories released above w* (one-sided data): the affine slope is biased, quadratic is not."""
    w = W_STAR * np.linspace(1.0, 1.2, 60)
    lin = fit_return_map(w, sqrt_map(w), degree=1, bootstrap=0)
    quad = fit_return_map(w, sqrt_map(w), degree=2, bootstrap=0)
    lin_err = abs(lin.jacobian[0, 0] - SLOPE_STAR)
    quad_err = abs(quad.jacobian[0, 0] - SLOPE_STAR)
    assert quad_err < 1e-3
    assert quad_err < lin_err / 10


def test_sqrt_map_quadratic_derivative_to_1e4_on_close_samples() -> None:
    w = W_STAR * np.random.default_rng(4).uniform(0.95, 1.05, 100)
    quad = fit_return_map(w, sqrt_map(w), degree=2, bootstrap=0)
    assert quad.jacobian[0, 0] == pytest.approx(SLOPE_STAR, abs=1e-4)
    assert quad.fixed_point[0] == pytest.approx(W_STAR, abs=1e-6)


def test_convergence_ratio_recovers_positive_multiplier() -> None:
    seq = 2.0 + 0.5 ** np.arange(100)
    assert convergence_ratio(seq, 2.0) == pytest.approx(0.5, rel=1e-9)
    noisy = seq + 1e-7 * np.random.default_rng(0).normal(size=seq.size)
    assert convergence_ratio(noisy, 2.0, noise_floor=1e-4) == pytest.approx(0.5, rel=1e-2)
    assert abs(convergence_ratio(noisy, 2.0) - 0.5) > 0.05  # without the floor, noise dominates
    with pytest.raises(ValueError, match="noise_floor"):
        convergence_ratio(seq, 2.0, noise_floor=10.0)


# --- 2-D and 3-D maps with a complex pair ---------------------------------------------------------


@pytest.mark.parametrize(
    ("matrix", "fixed", "truth"), [(MAP_2D, FIXED_2D, TRUE_2D), (MAP_3D, FIXED_3D, TRUE_3D)]
)
@pytest.mark.parametrize("degree", [1, 2])
def test_complex_pair_exact(matrix: np.ndarray, fixed: np.ndarray, truth: np.ndarray, degree: int) -> None:
    x = cloud(fixed, 80, seed=5)
    fit = fit_return_map(x, affine_map(matrix, fixed)(x), degree=degree, bootstrap=10)
    assert np.abs(fit.eigenvalues - truth).max() < 1e-8
    assert np.abs(fit.fixed_point - fixed).max() < 1e-8
    assert np.abs(fit.jacobian - matrix).max() < 1e-8
    assert fit.eigenvalues[0].imag > 0 and fit.eigenvalues[1] == np.conj(fit.eigenvalues[0])


def test_quadratic_2d_map_with_cross_terms_and_unstable_multiplier() -> None:
    """Exactly quadratic map with multipliers 1.6 (unstable) and 0.5: recovered by degree 2."""
    matrix = conjugated(np.diag([1.6, 0.5]), seed=6)

    def quad_map(x: np.ndarray) -> np.ndarray:
        dx = x - FIXED_2D
        bend = np.stack([0.3 * dx[:, 0] * dx[:, 1], -0.2 * dx[:, 0] ** 2 + 0.1 * dx[:, 1] ** 2], axis=1)
        return FIXED_2D + dx @ matrix.T + bend

    x = cloud(FIXED_2D + 0.3, 60, seed=7, spread=0.5)
    fit = fit_return_map(x, quad_map(x), degree=2, bootstrap=10)
    assert np.abs(fit.fixed_point - FIXED_2D).max() < 1e-9
    assert np.abs(fit.jacobian - matrix).max() < 1e-9
    assert fit.eigenvalues == pytest.approx([1.6, 0.5], abs=1e-9)
    assert np.abs(fit_return_map(x, quad_map(x), degree=1, bootstrap=0).jacobian - matrix).max() > 1e-2


def test_cubic_3d_map_recovered_by_degree_3_and_biases_degree_2() -> None:
    """A 3-D map with cubic terms and multipliers (-0.75, -0.41, 0.11), like the compass biped near its flip:
    over a +-0.3 cloud the quadratic fit's Jacobian absorbs the cubic terms (error > 1e-2); the cubic fit is exact."""
    matrix = conjugated(np.diag([-0.75, -0.41, 0.11]), seed=8)

    def cubic_map(x: np.ndarray) -> np.ndarray:
        dx = x - FIXED_3D
        bend = np.stack([0.4 * dx[:, 0] ** 3 - 0.2 * dx[:, 1] * dx[:, 2], 0.3 * dx[:, 0] ** 2 * dx[:, 1],
                         -0.5 * dx[:, 2] ** 3 + 0.1 * dx[:, 0] ** 2], axis=1)
        return FIXED_3D + dx @ matrix.T + bend

    x = cloud(FIXED_3D, 120, seed=9, spread=0.3)
    cubic = fit_return_map(x, cubic_map(x), degree=3, bootstrap=10)
    assert np.abs(cubic.fixed_point - FIXED_3D).max() < 1e-9
    assert np.abs(cubic.jacobian - matrix).max() < 1e-9
    assert np.sort(cubic.eigenvalues.real) == pytest.approx([-0.75, -0.41, 0.11], abs=1e-9)
    assert np.abs(fit_return_map(x, cubic_map(x), degree=2, bootstrap=0).jacobian - matrix).max() > 1e-2


@pytest.mark.parametrize("seed", range(5))
def test_noisy_3d_estimate_within_bootstrap_error(seed: int) -> None:
    sigma = 0.01
    rng = np.random.default_rng(100 + seed)
    x = cloud(FIXED_3D, 300, seed=200 + seed)
    y = affine_map(MAP_3D, FIXED_3D)(x) + sigma * rng.normal(size=x.shape)
    fit = fit_return_map(x, y, bootstrap=100, seed=seed)
    assert np.all(np.abs(fit.fixed_point - FIXED_3D) <= 4 * fit.fixed_point_std)
    err = fit.eigenvalues - TRUE_3D
    assert np.all(np.abs(err.real) <= 4 * fit.eigenvalue_std.real)
    assert np.all(np.abs(err.imag) <= 4 * fit.eigenvalue_std.imag)
    assert np.all(np.abs(fit.jacobian - MAP_3D) <= 4 * fit.jacobian_std)
    assert np.abs(err).max() < 0.02
    assert fit.residual_rms == pytest.approx(np.full(3, sigma), rel=0.15)
    assert fit.eigenvalue_std[2].imag == 0.0  # the real multiplier stays real
    assert np.all(fit.eigenvalue_std.real > 1e-4)  # not degenerate: the noise is felt


def test_bootstrap_std_matches_monte_carlo_spread() -> None:
    """Bootstrap std of the multipliers agrees within a factor ~1.6 with their sampling std."""
    sigma = 0.02
    step = affine_map(MAP_2D, FIXED_2D)

    def noisy_fit(seed: int, bootstrap: int) -> ReturnMapFit:
        rng = np.random.default_rng(seed)
        x = FIXED_2D + rng.normal(size=(150, 2))
        return fit_return_map(x, step(x) + sigma * rng.normal(size=x.shape), bootstrap=bootstrap)

    estimates = np.array([noisy_fit(seed, 0).eigenvalues for seed in range(1, 60)])
    mc_std = np.concatenate([estimates.real.std(axis=0), estimates.imag.std(axis=0)])
    boot = noisy_fit(0, 300).eigenvalue_std
    boot_std = np.concatenate([boot.real, boot.imag])
    assert np.all(boot_std / mc_std > 0.6) and np.all(boot_std / mc_std < 1.6)


def test_bootstrap_std_belongs_to_the_right_multiplier() -> None:
    """Multiplier 0.2 is well determined, 0.8 poorly: each std must follow its own multiplier.

    ``eigvals`` lists them as (0.2, 0.8), the fit sorts them (0.8, 0.2): the bootstrap replicates
    must be matched to the point estimate, not taken in ``eigvals`` order.
    """
    rng = np.random.default_rng(8)
    x = rng.normal(size=(200, 2))
    y = x * [0.2, 0.8] + rng.normal(size=x.shape) * [1e-4, 0.05]
    fit = fit_return_map(x, y, bootstrap=100)
    assert fit.eigenvalues.real == pytest.approx([0.8, 0.2], abs=0.03)
    assert fit.eigenvalue_std.real[0] > 50 * fit.eigenvalue_std.real[1]


# --- determinism, serialisation, errors -----------------------------------------------------------


def noisy_2d(seed: int = 11) -> tuple[np.ndarray, np.ndarray]:
    """A small noisy 2-D sample."""
    rng = np.random.default_rng(seed)
    x = cloud(FIXED_2D, 50, seed=seed)
    return x, affine_map(MAP_2D, FIXED_2D)(x) + 0.01 * rng.normal(size=x.shape)


def test_deterministic_given_seed() -> None:
    x, y = noisy_2d()
    a, b = (fit_return_map(x, y, degree=2, bootstrap=30, seed=3) for _ in range(2))
    assert json.dumps(a.to_dict()) == json.dumps(b.to_dict())
    c = fit_return_map(x, y, degree=2, bootstrap=30, seed=4)
    assert not np.array_equal(a.fixed_point_std, c.fixed_point_std)
    assert np.array_equal(a.fixed_point, c.fixed_point)


def test_to_dict_json_ready_with_complex_pairs() -> None:
    x, y = noisy_2d()
    fit = fit_return_map(x, y, bootstrap=20)
    data = json.loads(json.dumps(fit.to_dict(), allow_nan=False))
    assert data["eigenvalues"] == [[z.real, z.imag] for z in fit.eigenvalues]
    assert data["eigenvalue_std"] == [[z.real, z.imag] for z in fit.eigenvalue_std]
    assert data["jacobian"] == fit.jacobian.tolist()
    assert data["n_pairs"] == 50 and data["degree"] == 1
    assert data["condition"] == pytest.approx(fit.condition)
    no_boot = fit_return_map(x, y, bootstrap=0).to_dict()
    assert no_boot["fixed_point_std"] == [None, None]
    json.dumps(no_boot, allow_nan=False)


def test_center_changes_nothing_but_conditioning() -> None:
    x, y = noisy_2d()
    default = fit_return_map(x, y, degree=2, bootstrap=0)
    shifted = fit_return_map(x, y, degree=2, bootstrap=0, center=FIXED_2D + 5.0)
    assert np.allclose(default.fixed_point, shifted.fixed_point, atol=1e-9)
    assert np.allclose(default.eigenvalues, shifted.eigenvalues, atol=1e-9)
    assert shifted.condition > default.condition


def test_errors_too_few_pairs() -> None:
    with pytest.raises(ValueError, match="too few pairs"):
        fit_return_map(np.array([1.0, 2.0]), np.array([1.5, 2.0]))
    x = cloud(FIXED_3D, 10, seed=0)  # a 3-D quadratic has 10 coefficients per coordinate
    with pytest.raises(ValueError, match="too few pairs"):
        fit_return_map(x, x, degree=2)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_errors_non_finite(bad: float) -> None:
    x, y = noisy_2d()
    y[3, 1] = bad
    with pytest.raises(ValueError, match="finite"):
        fit_return_map(x, y)


def test_errors_degenerate_samples() -> None:
    x = np.tile([1.0, 2.0], (20, 1))
    with pytest.raises(ValueError, match="do not span the section"):
        fit_return_map(x, x)
    line = np.linspace(0.0, 1.0, 20)
    on_a_line = np.stack([line, 2.0 * line + 1.0], axis=1)
    with pytest.raises(ValueError, match="rank-deficient"):
        fit_return_map(on_a_line, on_a_line * 0.5)


def test_errors_bad_arguments_and_missing_fixed_point() -> None:
    x = np.linspace(-1.0, 1.0, 20)
    with pytest.raises(ValueError, match="degree"):
        fit_return_map(x, x, degree=4)
    with pytest.raises(ValueError, match="same shape"):
        fit_return_map(x, x[:-1])
    with pytest.raises(ValueError, match="did not converge"):
        fit_return_map(x, x**2 + 1.0, degree=2)  # x^2 + 1 = x has no real root


# --- fit_drifting_cycle: a family of fixed points -------------------------------------------------


def curved_family_map(k: float, lam: float, drift: float, anchor: float) -> Callable[[np.ndarray], np.ndarray]:
    """Quadratic map of (s, y) whose fixed points are the curve y = s^2/2, moved by ``drift`` times the curve's
    tangent (1, anchor) at s = ``anchor``: there F(x) = x + drift t exactly, DF = [[1 - k s, k], [(1 - lam) s, lam]],
    multipliers 1 (along the curve) and lam - k s."""
    def f(x: np.ndarray) -> np.ndarray:
        s, y = x[:, 0], x[:, 1]
        g = 0.5 * s**2
        return np.stack([s + k * (y - g), g + lam * (y - g)], axis=1) + drift * np.array([1.0, anchor])

    return f


def test_drifting_cycle_on_a_linear_family() -> None:
    """Affine map with a line of fixed points p0 + s v and a drift c along it: the cycle at x[0] = anchor is
    p0 + (anchor - p0[0]) v, the drift is c and the multipliers are 1, 0.8, 0.5, for the affine and quadratic fit."""
    v, p0, drift, anchor = np.array([1.0, 0.3, -0.2]), np.array([0.1, 1.0, -0.5]), 2e-3, 0.25
    basis = np.column_stack([v, [0.2, 1.0, 0.1], [-0.1, 0.3, 1.0]])
    matrix = basis @ np.diag([1.0, 0.8, 0.5]) @ np.linalg.inv(basis)
    x = cloud(p0, 60, seed=0, spread=0.1)
    x_next = p0 + (x - p0) @ matrix.T + drift * v
    for degree in (1, 2):
        fit = fit_drifting_cycle(x, x_next, 3.0 * v, anchor, degree=degree, bootstrap=0)
        np.testing.assert_allclose(fit.fixed_point, p0 + (anchor - p0[0]) * v, atol=1e-10)
        assert fit.fixed_point[0] == anchor
        assert fit.drift == pytest.approx(drift, abs=1e-12)
        np.testing.assert_allclose(fit.jacobian, matrix, atol=1e-9)
        np.testing.assert_allclose(fit.eigenvalues, [1.0, 0.8, 0.5], atol=1e-9)
        assert fit.degree == degree and fit.n_pairs == 60 and fit.replicates == 0
        assert np.isnan(fit.fixed_point_std).all() and math.isnan(fit.drift_std)


def test_drifting_cycle_quadratic_fit_follows_a_curved_family() -> None:
    """On a curved family the quadratic fit recovers the cycle, drift and Jacobian at the anchor; the affine fit,
    over samples spread 0.2, misses the transverse multiplier lam - k s by more than 1e-3."""
    k, lam, drift, anchor = 0.5, 0.6, 1e-3, 0.3
    fixed = np.array([anchor, 0.5 * anchor**2])
    x = cloud(fixed, 80, seed=1, spread=0.2)
    x_next = curved_family_map(k, lam, drift, anchor)(x)
    tangent = np.array([1.0, anchor])
    quadratic = fit_drifting_cycle(x, x_next, tangent, anchor, degree=2, bootstrap=0)
    np.testing.assert_allclose(quadratic.fixed_point, fixed, atol=1e-10)
    assert quadratic.drift == pytest.approx(drift, abs=1e-12)
    np.testing.assert_allclose(quadratic.jacobian, [[1 - k * anchor, k], [(1 - lam) * anchor, lam]], atol=1e-9)
    np.testing.assert_allclose(quadratic.eigenvalues, [1.0, lam - k * anchor], atol=1e-9)
    affine = fit_drifting_cycle(x, x_next, tangent, anchor, degree=1, bootstrap=0)
    assert abs(affine.eigenvalues[1] - (lam - k * anchor)) > 1e-3


def test_drifting_cycle_bootstrap_and_labels() -> None:
    """Noisy pairs: the bootstrap spreads are finite and of the noise's size, deterministic given the seed, labelled
    by the ``label`` callable's names; replicates whose label raises are dropped."""
    k, lam, drift, anchor = 0.5, 0.6, 1e-3, 0.3
    x = cloud(np.array([anchor, 0.5 * anchor**2]), 200, seed=2, spread=0.2)
    x_next = curved_family_map(k, lam, drift, anchor)(x) + 1e-4 * np.random.default_rng(3).normal(size=x.shape)
    tangent = np.array([1.0, anchor])

    def label(jac: np.ndarray) -> dict[str, float]:
        return {"trace": float(np.trace(jac)), "det": float(np.linalg.det(jac))}

    fit = fit_drifting_cycle(x, x_next, tangent, anchor, bootstrap=50, seed=4, label=label)
    again = fit_drifting_cycle(x, x_next, tangent, anchor, bootstrap=50, seed=4, label=label)
    assert fit.replicates == 50 and set(fit.label_std) == {"trace", "det"}
    assert 1e-6 < fit.drift_std < 1e-4 and 1e-6 < fit.label_std["trace"] < 1e-3
    assert fit.fixed_point_std[0] < 1e-12 < 1e-6 < fit.fixed_point_std[1] < 1e-4  # x[0] is the anchor
    assert np.all(np.abs(fit.eigenvalue_std) < 1e-3)
    assert fit.drift == pytest.approx(drift, abs=5 * fit.drift_std)
    assert fit.label_std == again.label_std and np.array_equal(fit.fixed_point_std, again.fixed_point_std)

    def refuse(jac: np.ndarray) -> dict[str, float]:
        raise ValueError("unlabelled")

    dropped = fit_drifting_cycle(x, x_next, tangent, anchor, bootstrap=10, label=refuse)
    assert dropped.replicates == 0 and dropped.label_std == {} and math.isnan(dropped.drift_std)
    np.testing.assert_array_equal(dropped.fixed_point, fit_drifting_cycle(x, x_next, tangent, anchor,
                                                                          bootstrap=0).fixed_point)


def test_drifting_cycle_errors() -> None:
    x = cloud(np.zeros(3), 10, seed=0)  # a 3-D quadratic has 10 coefficients per coordinate
    with pytest.raises(ValueError, match="too few pairs"):
        fit_drifting_cycle(x, x, np.array([1.0, 0.0, 0.0]), 0.0)
    with pytest.raises(ValueError, match="degree"):
        fit_drifting_cycle(x, x, np.array([1.0, 0.0, 0.0]), 0.0, degree=4)
    with pytest.raises(ValueError, match="same shape"):
        fit_drifting_cycle(x, x[:-1], np.array([1.0, 0.0, 0.0]), 0.0)
