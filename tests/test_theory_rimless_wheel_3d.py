"""3D rimless wheel theory (001 = Coleman, Chatterjee & Ruina 1997) against the derivation page's oracles
(docs/theory/rimless-wheel-3d.md, Sec. 3-4) and against the independent 3D hybrid integrator."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.theory import rimless_wheel_3d as th
from mjpoincare.analysis.theory.rimless_wheel_3d import RimlessWheel3D
from mjpoincare.analysis.theory.rimless_wheel_3d import hybrid as hy

TABLE2 = RimlessWheel3D(16, 0.125, 0.5, math.pi / 10)  # 001 Sec. 8.1 / Table 2 / Fig 4


def wheel(n: int, alpha: float, psi: float, J: float) -> RimlessWheel3D:
    """A wheel from a row of the derivation page's tables, ordered (n, alpha, psi, J) as printed."""
    return RimlessWheel3D(n, alpha, J, psi)


def approx6(v: float) -> object:
    """A value printed with 6 decimals: rtol 1e-5, but never tighter than the rounding (5e-7)."""
    return pytest.approx(v, rel=1e-5, abs=5e-7)


# Derivation page Sec. 4 table: (n, alpha, psi, J), then gamma, mu, mu^2, thd+, thd-, thd(0), T_step, gamma_c, |bank*|,
# Pt/Pn (in-plane, see impact_friction_ratio), Nmin, max|Ft/N|. The printed psi 0.31416/0.52360 are pi/10, pi/6.
ORACLE = [
    ((16, 0.125, math.pi / 10, 0.5), (0.118852, 0.949253, 0.901081, 0.749614, 0.789688, 0.753210, 0.517724,
                                      0.005128, 0.038810, 0.1309, 0.341, 0.1434)),
    ((16, 0.125, 0.0, 0.5), (0.125000, 0.949253, 0.901081, 0.768660, 0.809752, 0.773207, 0.504524, 0.005128,
                             0.000000, 0.1309, 0.308, 0.1496)),
    ((16, 0.125, 0.2875, 0.5), (0.119844, 0.949253, 0.901081, 0.752720, 0.792960, 0.756473, 0.515524, 0.005128,
                                0.035615, 0.1309, 0.335, 0.1427)),
    ((32, 0.0625, math.pi / 10, 0.5), (0.059437, 0.987190, 0.974544, 0.770987, 0.780991, 0.771864, 0.253935,
                                       0.000633, 0.019336, 0.0654, 0.381, 0.0692)),
    ((6, 0.2, 0.0, 0.5), (0.200000, 0.666667, 0.444444, 0.460341, 0.690512, 0.411446, 2.310015, 0.107077,
                          0.000000, 0.3464, 0.346, 0.4001)),
    ((8, 0.1, 0.0, 0.0), (0.100000, 0.707107, 0.500000, 0.390920, 0.552844, 0.278832, 2.364077, 0.068229,
                          0.000000, 0.4142, 0.532, 0.4142)),
    ((10, 0.2, 0.0, 0.25), (0.200000, 0.847214, 0.717771, 0.706844, 0.834316, 0.721878, 0.853497, 0.026199,
                            0.000000, 0.2546, 0.196, 0.2747)),
    ((12, 0.08, math.pi / 6, 1.0), (0.069264, 0.933013, 0.870513, 0.490756, 0.525991, 0.474090, 1.078990,
                                    0.009125, 0.040064, 0.1293, 0.688, 0.1401)),
    ((8, 0.25, 0.3, 1.0), (0.238612, 0.853553, 0.728553, 0.696795, 0.816346, 0.708525, 1.086591, 0.031429,
                           0.075316, 0.1907, 0.242, 0.9057)),
]  # fmt: skip
ORACLE_3D = [row for row in ORACLE if row[0][3] > 0.0]  # the J = 0 row is planar only


@pytest.mark.parametrize(("params", "values"), ORACLE)
def test_closed_forms_against_note_table(params, values):
    w = wheel(*params)
    gamma, mu, mu2, thd_post, thd_pre, thd_mid, period, gamma_c, bank = values[:9]
    assert w.gamma == approx6(gamma)
    assert th.effective_slope(w.slope, w.heading) == w.gamma
    assert th.collision_coefficient(w.spokes, w.J) == approx6(mu)
    assert w.mu**2 == approx6(mu2)
    assert th.planar_pitch_rate(w) == approx6(thd_post)
    assert th.pre_impact_pitch_rate(w) == approx6(thd_pre)
    assert th.midstance_pitch_rate(w) == approx6(thd_mid)
    assert th.step_period(w) == approx6(period)
    assert th.existence_threshold(w.spokes, w.J) == approx6(gamma_c)
    assert abs(th.planar_bank(w.slope, w.heading)) == approx6(bank)
    assert math.copysign(1.0, w.bank) == -math.copysign(1.0, w.heading) or w.heading == 0.0  # eq 12 sign, R=RzRxRy
    b = w.beta  # the page's Pt/Pn column is the in-plane ratio sin b cos b/(J + cos^2 b)
    assert math.sin(b) * math.cos(b) / (w.J + math.cos(b) ** 2) == pytest.approx(values[9], abs=5e-5)


def test_eq14_both_forms_and_energy_integral():
    for n, alpha, psi, J in [(16, 0.125, math.pi / 10, 0.5), (7, 0.3, -0.4, 2.0), (40, 0.01, 1.2, 0.1)]:
        w = RimlessWheel3D(n, alpha, J, psi)
        b, g, mu = w.beta, w.gamma, w.mu
        form1 = 4 * mu**2 * math.sin(b) * math.sin(g) / ((1 + J) * (1 - mu**2))
        form2 = mu**2 * (1 + J) * math.sin(g) / (math.sin(b) * (J + math.cos(b) ** 2))
        rate = th.planar_pitch_rate(w)
        assert rate**2 == pytest.approx(form1, rel=1e-13)
        assert rate**2 == pytest.approx(form2, rel=1e-13)
        assert th.pitch_rate_at(w, -b) == pytest.approx(rate, rel=1e-13)
        assert th.pitch_rate_at(w, b) == pytest.approx(th.pre_impact_pitch_rate(w), rel=1e-13)
        assert th.planar_return_map(w, rate**2) == pytest.approx(rate**2, rel=1e-13)


def test_planar_return_map_affine_and_exact_against_hybrid():
    w = TABLE2
    gain = 4 * math.sin(w.beta) * math.sin(w.gamma) / (1 + w.J)
    r2 = np.array([0.1, 0.5, 2.0])
    assert np.allclose(th.planar_return_map(w, r2), w.mu**2 * (r2 + gain), rtol=1e-15)
    # a planar start off the cycle (any theta_dot, psi_dot = phi_dot = 0, phi = phi*) stays planar: eq 11 exactly
    for rate in (0.3, 0.9, 1.6):
        x_next, _ = hy.step(w, [w.heading, w.bank, 0.0, 0.0, rate])
        assert x_next[4] ** 2 == pytest.approx(th.planar_return_map(w, rate**2), rel=1e-11)
        assert np.max(np.abs(x_next[:4] - [w.heading, w.bank, 0.0, 0.0])) < 1e-11
    slow = RimlessWheel3D(16, 0.01, 0.5, 0.0)  # gamma < beta: too slow to pass the top -> rocks back
    assert math.isnan(th.planar_return_map(slow, 1e-4))
    assert math.isnan(th.planar_return_map(w, -1.0))
    with pytest.raises(RuntimeError, match="rolled back"):
        hy.step(slow, [0.0, 0.0, 0.0, 0.0, 1e-2])


def test_existence_threshold_eq10():
    for n, J in [(16, 0.5), (5, 1.0), (8, 0.0), (3, 2.0)]:
        gc = th.existence_threshold(n, J)
        beta = math.pi / n
        assert 0.0 < gc < beta
        assert th.planar_cycle_exists(RimlessWheel3D(n, gc * (1 + 1e-9), J))
        assert not th.planar_cycle_exists(RimlessWheel3D(n, gc * (1 - 1e-9), J))
        assert math.isnan(th.planar_pitch_rate(RimlessWheel3D(n, gc * (1 - 1e-9), J)))
    assert th.existence_threshold(200, 0.5) == pytest.approx((math.pi / 200) ** 3 / 1.5, rel=1e-3)  # eq 16
    assert math.isnan(th.existence_threshold(3, 0.4))  # mu < 0: no forward cycle at any slope


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"spokes": 2, "slope": 0.1}, r"^spokes: .*>= 3"),
        ({"spokes": 16.0, "slope": 0.1}, r"^spokes: .*integer"),
        ({"spokes": 16, "slope": 0.0}, r"^slope: .*\(0, pi/2\)"),
        ({"spokes": 16, "slope": math.pi / 2}, r"^slope: .*\(0, pi/2\)"),
        ({"spokes": 16, "slope": 0.1, "J": 0.0}, r"^J: must be > 0.*ill-posed"),
        ({"spokes": 16, "slope": 0.1, "J": -1.0}, r"^J: must be > 0"),
        ({"spokes": 16, "slope": 0.1, "heading": math.pi / 2}, r"^heading: .*\(-pi/2, pi/2\)"),
        ({"spokes": 16, "slope": 0.1, "heading": -2.0}, r"^heading: "),
        ({"spokes": 3, "slope": 1.0, "J": 0.4}, r"^J: collision coefficient mu = .* <= 0 for spokes=3 .*J > 0\.5"),
        (
            {"spokes": 16, "slope": 0.00505, "J": 0.5, "heading": 0.3},
            r"^slope: effective slope 0\.004824 below the existence threshold 0\.005128 "
            r"for spokes=16, J=0\.5, heading=0\.3$",
        ),
    ],
)
def test_validate_refusals(kwargs, match):
    w = RimlessWheel3D(**kwargs)
    with pytest.raises(ValueError, match=match):
        th.validate(w)
    with pytest.raises(ValueError, match=match):
        hy.step(w, np.zeros(5))


def test_validate_accepts_and_j0_only_planar():
    th.validate(TABLE2)
    th.validate(RimlessWheel3D(16, 0.00515, 0.5, 0.0))  # just above gamma_c = 0.005128
    planar = RimlessWheel3D(8, 0.1, 0.0)
    assert th.planar_pitch_rate(planar) == approx6(0.390920)
    with pytest.raises(ValueError, match="J"):
        th.impact_matrix(8, 0.0, 0.0)


@pytest.mark.parametrize(("params", "values"), ORACLE_3D)
def test_hybrid_fixed_point_and_contact_requirements(params, values):
    w = wheel(*params)
    x_star = hy.planar_fixed_point(w)
    rec = hy.step_record(w, x_star)
    assert np.max(np.abs(rec.x_next - x_star)) < 1e-10
    assert rec.pre_impact[2] == pytest.approx(w.beta, abs=1e-12)  # impact at theta = +pi/n (foot-height event)
    assert rec.theta_after == pytest.approx(-w.beta, abs=1e-12)
    assert rec.pre_impact[5] == pytest.approx(th.pre_impact_pitch_rate(w), rel=1e-10)
    assert rec.time == pytest.approx(th.step_period(w), rel=1e-9)
    assert rec.min_normal_force == pytest.approx(values[10], abs=5e-4)
    assert rec.max_friction_ratio == pytest.approx(values[11], abs=5e-5)
    # impulse: slope-frame ratio (closed form), which equals the page's in-plane column only at psi = 0
    assert rec.impulse_ratio == pytest.approx(th.impact_friction_ratio(w), rel=1e-9)
    if w.heading == 0.0:
        assert rec.impulse_ratio == pytest.approx(values[9], abs=5e-5)
    else:
        assert rec.impulse_ratio > values[9] + 1e-3
    assert rec.normal_impulse > 0.0


def test_table2_banked_impulse_ratio_correction():
    assert th.impact_friction_ratio(TABLE2) == pytest.approx(0.13662, abs=5e-6)  # in-plane ratio 0.1309 (page Sec. 1)


def test_impact_matrix_equals_vector_law():
    rng = np.random.default_rng(20240601)
    for n, J in [(16, 0.5), (5, 0.3), (8, 2.0), (3, 1.0), (40, 0.05)]:
        w = RimlessWheel3D(n, 1.2, J, 0.0)
        for _ in range(6):
            psi, phi = rng.uniform(-1.4, 1.4), rng.uniform(-1.2, 1.2)
            rates = rng.normal(size=3)
            law = hy.impact_rates(w, psi, phi, rates)
            assert np.max(np.abs(law - th.impact_matrix(n, J, phi) @ rates)) < 1e-12
    t = th.impact_matrix(16, 0.5, 0.0)
    assert t[2, 2] == th.collision_coefficient(16, 0.5)
    assert t[1, 0] < 0.0  # sign of the (2,1) entry in the R = Rz Rx Ry convention


def test_euler_helpers_round_trip():
    rng = np.random.default_rng(7)
    for _ in range(5):
        psi, phi, theta = rng.uniform(-1.5, 1.5, size=3)
        assert np.allclose(hy.euler_angles(hy.pose(psi, phi, theta)), (psi, phi, theta), atol=1e-13)
        rates = rng.normal(size=3)
        assert np.allclose(hy.euler_rates(psi, phi, hy.angular_velocity(psi, phi, rates)), rates, atol=1e-13)
        q = hy.euler_state(hy.pose(psi, phi, theta), hy.angular_velocity(psi, phi, rates))
        assert np.allclose(q, [psi, phi, theta, *rates], atol=1e-13)


# Derivation page Sec. 4 3D eigenvalue table: (n, alpha, psi, J), |lambda3|, arg lambda3, lambda5, lambda2.
EIGEN_ROWS = [
    ((16, 0.125, math.pi / 10, 0.5), 0.98837, 0.39895, 0.96133, 0.90108),  # Table 2 numerical row
    ((16, 0.125, 0.0, 0.5), 0.98907, 0.41245, 0.95997, 0.90108),
    ((24, 1.5 / 24, 0.0, 0.5), 0.99222, 0.21733, 0.98806, 0.95508),
    ((8, 0.25, 0.3, 1.0), 0.95215, 0.95891, 0.88766, 0.72855),
    ((16, 1.15 / 16, 0.0, 0.5), 0.92192, 0.14806, 1.10492, 0.90108),  # unstable: lambda5 > 1
]


@pytest.mark.parametrize(("params", "modulus", "angle", "lam5", "lam2"), EIGEN_ROWS)
def test_3d_eigenvalues_against_note(params, modulus, angle, lam5, lam2):
    w = wheel(*params)
    e = hy.eigenvalues_3d(w)
    tol = 1e-5  # the page prints 5 decimals (rounding 5e-6); finite-difference noise is ~1e-8
    assert abs(e.heading - 1.0) < 1e-7
    assert e.wobble_modulus == pytest.approx(modulus, abs=tol)
    assert e.wobble_angle == pytest.approx(angle, abs=tol)
    assert e.lambda5 == pytest.approx(lam5, abs=tol)
    assert e.lambda2 == pytest.approx(lam2, abs=tol)
    assert e.lambda2 == pytest.approx(w.mu**2, abs=1e-7)  # exact identity lambda2 = mu^2
    assert e.wobble[1] == pytest.approx(np.conj(e.wobble[0]))
    assert np.allclose(np.sort_complex(e.all), np.sort_complex(np.linalg.eigvals(hy.jacobian(w))), atol=1e-12)


def test_table2_rectangular_pair_and_lambda2_column():
    e = hy.eigenvalues_3d(TABLE2)
    assert e.wobble[0] == pytest.approx(0.91075 + 0.38393j, abs=1e-5)  # the paper's "0.91085" is a typo
    jac = hy.jacobian(TABLE2)
    column = np.zeros(5)
    column[4] = TABLE2.mu ** 2
    assert np.max(np.abs(jac[:, 4] - column)) < 1e-7  # planar subspace invariant: J e_thd = mu^2 e_thd


def test_real_wobble_pair_when_disk_criterion_fails():
    w = RimlessWheel3D(16, 0.9 / 16, 0.5, 0.0)  # page Sec. 4: 1.38094, 1, 0.90108, 0.90086, 0.75488
    e = hy.eigenvalues_3d(w)
    assert e.wobble == pytest.approx((1.38094, 0.75488), abs=1e-5)
    assert e.wobble_modulus == pytest.approx(1.38094, abs=1e-5)
    assert e.wobble_angle == 0.0
    assert e.lambda5 == pytest.approx(0.90086, abs=1e-5)
    assert e.lambda2 == pytest.approx(w.mu**2, abs=1e-7)
    assert th.asymptotic_coefficients(w)[0] > 0.0  # f0 > 0: eq 33 violated


def test_asymptotic_row_table2():
    lam = th.asymptotic_eigenvalues(TABLE2)
    f0, f1, f2 = th.asymptotic_coefficients(TABLE2)
    assert (f0, f1, f2) == pytest.approx((-42.5851, -48.4409, 9.9356), abs=1e-4)
    assert lam[0] == 0.0 and lam[1] == 1.0
    assert lam[2].real == pytest.approx(0.89719, abs=5e-6)
    assert abs(lam[3]) == pytest.approx(0.99301, abs=5e-6)
    assert np.angle(lam[3]) == pytest.approx(0.42325, abs=5e-6)
    assert lam[4] == np.conj(lam[3])
    assert lam[5].real == pytest.approx(0.96119, abs=5e-6)
    # |lambda3,4| ~ 1 + (f1 + |f0|) eps^2/2 with f1 + |f0| = -4 pi^2 J g1/((2+J)(2(1+J) g1 - pi))
    g1 = 16 * 0.125 * math.cos(math.pi / 10)
    assert f1 - f0 == pytest.approx(-4 * math.pi**2 * 0.5 * g1 / (2.5 * (3 * g1 - math.pi)), rel=1e-12)


def test_asymptotic_error_is_order_n_cubed():
    ns = np.array([16, 32, 64])
    errors = []
    for n in ns:
        w = RimlessWheel3D(int(n), 2.0 / n, 0.5, math.pi / 10)
        e, a = hy.eigenvalues_3d(w), th.asymptotic_eigenvalues(w)
        errors.append(max(abs(e.wobble[0] - a[3]), abs(e.lambda5 - a[5]), abs(e.lambda2 - a[2])))
    slope = np.polyfit(np.log(ns), np.log(errors), 1)[0]
    # measured: errors 2.45e-2, 3.04e-3, 3.80e-4 (the wobble pair dominates), slope -3.006;
    # a wrong f1 or f2 would leave an O(n^-2) term, slope -2
    assert slope < -2.5
    assert errors[0] > errors[1] > errors[2]


@pytest.mark.parametrize(
    ("J", "g1", "psi", "rtol"),
    [(0.5, 2.0 * math.cos(math.pi / 10), math.pi / 10, 3e-4), (1.0, 3.0, 0.0, 3e-4), (0.25, 1.5, 0.4, 3e-3)],
)
def test_eq32_coefficients_by_richardson_extrapolation(J, g1, psi, rtol):
    """f1 = lim 2 n^2 (Re lambda3 - 1), f0 = -lim (n Im lambda3)^2, f2 = lim n^2 (1 - lambda5) at fixed
    g1 = n alpha cos psi, extrapolated from n = 32, 64, 128 (removing the 1/n and 1/n^2 terms).
    Measured relative errors: <= 7e-5 for the first two cases, 1.5e-3 for the third (near the pole
    2(1+J) g1 = pi, slower convergence)."""
    rows = []
    for n in (32, 64, 128):
        e = hy.eigenvalues_3d(RimlessWheel3D(n, g1 / (n * math.cos(psi)), J, psi))
        rows.append([2 * n**2 * (e.wobble[0].real - 1), -((n * e.wobble[0].imag) ** 2), n**2 * (1 - e.lambda5)])
    r = np.array(rows)
    f1, f0, f2 = (8 * r[2] - 6 * r[1] + r[0]) / 3
    want = th.asymptotic_coefficients(RimlessWheel3D(64, g1 / (64 * math.cos(psi)), J, psi))
    assert (f0, f1, f2) == pytest.approx(want, rel=rtol)


def test_stability_thresholds_eqs_33_36():
    J = 0.5
    s = th.stability_thresholds(J)
    assert s.disk == pytest.approx(math.pi / 3) and s.lambda5 == pytest.approx(math.pi / 2.5)
    assert s.rate2_disk == pytest.approx(s.disk / math.pi) and s.rate2_lambda5 == pytest.approx(s.lambda5 / math.pi)
    assert s.lambda5 > s.disk  # eq 34 is the stricter for J > 0
    n = 64  # f0 vanishes at the disk threshold, f2 at the lambda5 threshold
    assert th.asymptotic_coefficients(RimlessWheel3D(n, s.disk / n, J))[0] == pytest.approx(0.0, abs=1e-12)
    assert th.asymptotic_coefficients(RimlessWheel3D(n, s.lambda5 / n, J))[2] == pytest.approx(0.0, abs=1e-12)
    alpha_min = th.minimum_stable_slope_asymptotic(16, J, math.pi / 10)
    assert alpha_min == pytest.approx(math.pi / (2.5 * 16 * math.cos(math.pi / 10)))
    # the page's exact thresholds (lambda5 = 1): n alpha = 1.30927 at psi = 0, alpha = 0.086051 at psi = pi/10 (n = 16)
    for alpha, psi in [(1.30927 / 16, 0.0), (0.086051, math.pi / 10)]:
        assert hy.eigenvalues_3d(RimlessWheel3D(16, alpha, J, psi)).lambda5 == pytest.approx(1.0, abs=5e-5)
        assert alpha_min * math.cos(math.pi / 10) / math.cos(psi) < alpha  # finite n needs a steeper slope


def test_midstance_section():
    w = TABLE2
    xm = hy.midstance_fixed_point(w)
    assert xm[4] == approx6(0.753210)
    x_next, period = hy.midstance_map(w, xm)
    assert np.max(np.abs(x_next - xm)) < 1e-10
    assert period == pytest.approx(th.step_period(w), rel=1e-9)
    assert np.max(np.abs(hy.midstance_state(w, hy.planar_fixed_point(w)) - xm)) < 1e-10
    # conjugacy: mid(step(x)) = midstance_map(mid(x)) off the cycle too
    x = hy.planar_fixed_point(w) + np.array([0.01, -0.004, 0.02, -0.01, 0.03])
    lhs = hy.midstance_state(w, hy.step(w, x)[0])
    rhs = hy.midstance_map(w, hy.midstance_state(w, x))[0]
    assert np.max(np.abs(lhs - rhs)) < 1e-10
    em, ep = hy.midstance_eigenvalues(w), hy.eigenvalues_3d(w)
    assert np.max(np.abs(em.all - ep.all)) < 1e-6



def test_midstance_planar_map_family_tangent_and_names():
    """Eq 11 moved to mid-stance: fixed at the cycle's theta_dot(0) and exact against the hybrid for planar starts off
    the cycle; the family tangent d x*/d psi is an eigenvector of eigenvalue 1 (001 Table 1); the named eigenvalues."""
    w = TABLE2
    xm = hy.midstance_fixed_point(w)
    assert th.midstance_return_map(w, xm[4]) == pytest.approx(xm[4], rel=1e-12)
    for rate in (0.7, 0.9):
        x_next, _ = hy.midstance_map(w, [w.heading, w.bank, 0.0, 0.0, rate])
        assert x_next[4] == pytest.approx(th.midstance_return_map(w, rate), rel=1e-10)
    t = hy.family_tangent(hy.midstance_fixed_point, w)
    assert np.max(np.abs(hy.midstance_jacobian(w) @ t - t)) < 1e-5 * np.linalg.norm(t)
    named = hy.midstance_eigenvalues(w).named()
    assert tuple(named) == hy.Eigen3D.NAMES
    assert named["lambda2"] == pytest.approx(w.mu**2, abs=1e-6)

def test_fig4_350_impacts():
    w = TABLE2
    x_star = hy.planar_fixed_point(w)
    x0 = x_star + np.array([0.0, 0.001, 0.0, 0.0, 0.0])  # bank 0.0388 -> 0.0378 (toward upright; phi* < 0 here)
    assert abs(x0[1]) == pytest.approx(0.0378, abs=5e-5)
    final = hy.simulate(w, x0, 350)[-1]
    assert final[0] == pytest.approx(0.2875, abs=5e-5)  # eq 21
    assert final[1] == pytest.approx(-0.0356, abs=5e-5)
    assert final[4] == pytest.approx(0.75272, abs=5e-5)  # the page's nonlinear value (eq 21 prints 0.7529)
    # the new planar cycle at the final heading (eqs 12, 14), up to the residual wobble |lambda3|^350 ~ 0.017
    settled = RimlessWheel3D(16, 0.125, 0.5, float(final[0]))
    assert final[1] == pytest.approx(settled.bank, abs=5e-5)
    assert final[4] == pytest.approx(th.planar_pitch_rate(settled), abs=5e-5)
    linear = x_star + np.linalg.matrix_power(hy.jacobian(w), 350) @ (x0 - x_star)  # eq 20
    assert linear[[0, 1, 4]] == pytest.approx([0.2872, -0.0356, 0.7529], abs=5e-5)


def test_minimum_stable_slope_exact_eqs_33_36():
    """The exact least stable slope (transverse modulus = 1 of the solve_ivp map) against the derivation page's
    thresholds, above eq 34's asymptotic slope at finite n, with lambda5 the eigenvalue that crosses (J > 0)."""
    J = 0.5
    assert hy.minimum_stable_slope(16, J, math.pi / 10) == pytest.approx(0.086051, abs=1e-5)
    for n, n_alpha in [(8, 1.48537), (16, 1.30927)]:
        assert n * hy.minimum_stable_slope(n, J) == pytest.approx(n_alpha, abs=1e-4)
    alpha = hy.minimum_stable_slope(16, J, math.pi / 10)
    assert alpha > th.minimum_stable_slope_asymptotic(16, J, math.pi / 10)
    at = hy.eigenvalues_3d(RimlessWheel3D(16, alpha, J, math.pi / 10))
    assert at.lambda5 == pytest.approx(1.0, abs=1e-6) and at.wobble_modulus < 1.0
    assert hy.transverse_modulus(RimlessWheel3D(16, 0.98 * alpha, J, math.pi / 10)) > 1.0
    assert hy.transverse_modulus(RimlessWheel3D(16, 1.02 * alpha, J, math.pi / 10)) < 1.0
