"""Rimless wheel with Coulomb friction (002 Gamus & Or 2015, Sec. 3 and Appendix A) against the oracles of the
derivation page docs/theory/stick-slip.md, Sec. 5, the generic Appendix-A machinery against the closed forms, and
the two step implementations against each other."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.theory import rimless_wheel as rw
from mjpoincare.analysis.theory import rimless_wheel_friction as rf
from mjpoincare.analysis.theory import stick_slip as ss
from mjpoincare.analysis.theory.rimless_wheel_friction import FrictionWheel

ALPHA = math.radians(13.0)
KAPPA = 1.0 / 3.0
PHI = math.pi / 10


def paper(mu: float) -> FrictionWheel:
    """002's parameter set n = 10, kappa = 1/3, alpha = 13 deg."""
    return FrictionWheel(10, KAPPA, ALPHA, mu)


# --- closed forms (derivation page Sec. 1 tables) -------------------------------------------------------------


def test_paper_set_closed_forms():
    w = paper(math.inf)
    assert rf.beta(10, KAPPA) == pytest.approx(0.8567627458, rel=1e-9)
    assert rf.sticking_eigenvalue(w) == pytest.approx(0.7340424026, rel=1e-9)
    assert rf.sticking_fixed_point(w) == pytest.approx(0.876031187, rel=1e-9)
    assert rf.sticking_fixed_point(w) == pytest.approx(rw.rolling_fixed_point(rf.rigid_wheel(w)), rel=1e-12)
    lo, hi = rf.slope_bounds(10, KAPPA)
    assert math.degrees(lo) == pytest.approx(1.40005, abs=6e-6)
    assert math.degrees(hi) == pytest.approx(14.71294, abs=6e-6)
    mu_c, at = rf.critical_friction(w)
    assert mu_c == pytest.approx(0.914121, abs=1e-6)
    assert mu_c == pytest.approx(rw.required_friction(rf.rigid_wheel(w)), rel=1e-9)
    assert at == pytest.approx(PHI, abs=1e-12)
    assert rf.force_ratio(w, PHI) == pytest.approx(-mu_c, rel=1e-12)
    assert rf.impulse_ratio(10, KAPPA) == pytest.approx(-0.2374234, abs=1e-7)
    assert rf.impulse_ratio(10, KAPPA) == pytest.approx(rw.impact_impulse_ratio(rf.rigid_wheel(w)), rel=1e-12)
    th_min, th_max = rf.attraction_window_rigid(w)
    assert th_min == pytest.approx(0.0872388, abs=1e-7)
    assert th_max == pytest.approx(0.9594879, abs=1e-7)
    assert rf.start_slip_threshold(w) == pytest.approx(0.300772, abs=1e-6)
    assert rf.d_sign_boundary(w) == pytest.approx(math.tan(ALPHA), rel=1e-15)
    assert rf.omega_c(2.0, 9.81, 1.0) == pytest.approx(math.sqrt(9.81 / 4.0), rel=1e-15)


def test_eq21_closed_form_equals_the_scan():
    """002 eq 21 (minimum of f_n at theta = phi, Appendix B) with equality at alpha_max, and eq 18 at alpha_min."""
    b = rf.beta(10, KAPPA)
    lo, hi = rf.slope_bounds(10, KAPPA)

    def eq18(a: float) -> float:
        return 4 * b * b / (1 - b * b) * math.sin(a) * math.sin(PHI) + 2 * math.cos(a - PHI) - 2

    def eq21(a: float) -> float:
        core = 3 * math.cos(a + PHI) - 4 * b * b * math.sin(a) * math.sin(PHI) / (1 - b * b) - 2 * math.cos(a - PHI)
        return core * math.cos(PHI) + KAPPA * math.cos(a)

    assert eq18(lo) == pytest.approx(0.0, abs=1e-12)
    assert eq21(hi) == pytest.approx(0.0, abs=1e-12)


# n, kappa, alpha (deg), beta, theta_dot*, theta_dot^-, step time, mu_c, mu_c at (+1: +phi, -1: -phi), sigma~,
# alpha_min (deg), alpha_max (deg), theta_dot_min, theta_dot_max (derivation page Sec. 1 "Other parameter sets").
OTHER_SETS = [
    (10, 1 / 3, 5, 0.856763, 0.545285, 0.636448, 1.18308, 0.24414, -1, -0.23742, 1.400, 14.713, 0.22641, 1.07793),
    (10, 1 / 3, 14, 0.856763, 0.908475, 1.060358, 0.66043, 2.73769, 1, -0.23742, 1.400, 14.713, 0.06980, 0.94292),
    (8, 1 / 3, 10, 0.780330, 0.643321, 0.824422, 1.19026, 0.32211, -1, -0.29788, 2.812, 16.646, 0.21773, 0.96587),
    (6, 1 / 2, 15, 0.666667, 0.643514, 0.965271, 1.53522, 0.83813, 1, -0.34641, 6.135, 19.394, 0.26105, 0.86438),
    (12, 0.2, 8, 0.888355, 0.734395, 0.826691, 0.69735, 0.22826, -1, -0.22065, 0.892, 12.784, 0.12210, 0.99069),
    (10, 1, 10, 0.904508, 0.982642, 1.086382, 0.62663, 0.37818, 1, -0.15431, 0.910, 15.739, 0.13951, 1.30529),
    (10, 0, 6, 0.809017, 0.494740, 0.611533, 1.28624, 0.32492, -1, -0.32492, 1.916, 13.750, 0.20906, 0.88563),
]


@pytest.mark.parametrize("row", OTHER_SETS)
def test_other_parameter_sets(row):
    n, k, a_deg, b, th_star, th_pre, period, mu_c, end, sig, a_min, a_max, th_min, th_max = row
    w = FrictionWheel(n, k, math.radians(a_deg), math.inf)
    rf.validate(w)
    assert rf.beta(n, k) == pytest.approx(b, abs=6e-7)
    assert rf.sticking_fixed_point(w) == pytest.approx(th_star, abs=6e-7)
    crit, at = rf.critical_friction(w)
    assert crit == pytest.approx(mu_c, abs=6e-6)
    assert at == pytest.approx(end * math.pi / n, abs=1e-9)
    assert rf.impulse_ratio(n, k) == pytest.approx(sig, abs=6e-6)
    lo, hi = rf.slope_bounds(n, k)
    assert (math.degrees(lo), math.degrees(hi)) == pytest.approx((a_min, a_max), abs=6e-4)
    assert rf.attraction_window_rigid(w) == pytest.approx((th_min, th_max), abs=6e-6)
    rec = rf.step(w, (rf.sticking_fixed_point(w), 0.0))  # mu = inf: stick throughout, eq 13 + eq 14
    assert rec.phases == ("stick",) and rec.impact == "sticking"
    assert rec.theta_dot == pytest.approx(rf.sticking_fixed_point(w), rel=1e-10)
    assert rec.theta_dot_pre == pytest.approx(th_pre, abs=6e-7)
    assert rec.duration == pytest.approx(period, abs=6e-6)


def test_n4_has_no_admissible_slope():
    lo, hi = rf.slope_bounds(4, KAPPA)
    assert (math.degrees(lo), math.degrees(hi)) == pytest.approx((27.9, 17.6), abs=0.05)
    with pytest.raises(ValueError, match="slope: no admissible slope"):
        rf.validate(FrictionWheel(4, KAPPA, math.radians(20), 1.0))


@pytest.mark.parametrize(
    ("wheel", "match"),
    [
        (FrictionWheel(2, KAPPA, ALPHA, 1.0), "spokes must be an integer >= 3"),
        (FrictionWheel(10.0, KAPPA, ALPHA, 1.0), "spokes must be an integer >= 3"),  # type: ignore[arg-type]
        (FrictionWheel(10, -0.1, ALPHA, 1.0), r"kappa must be in \[0, 1\]"),
        (FrictionWheel(10, 1.5, ALPHA, 1.0), r"kappa must be in \[0, 1\]"),
        (FrictionWheel(10, KAPPA, ALPHA, -0.1), "mu must be >= 0"),
        (FrictionWheel(10, KAPPA, ALPHA, math.nan), "mu must be >= 0"),
        (FrictionWheel(10, KAPPA, math.radians(1.0), 1.0), r"slope must be in \(0.0244355, 0.256789\) rad"),
        (FrictionWheel(10, KAPPA, math.radians(15.0), 1.0), r"slope must be in \(0.0244355, 0.256789\) rad"),
        (FrictionWheel(3, 0.3, 0.3, 1.0), "slope: no admissible slope for spokes=3"),
    ],
)
def test_validate_refuses(wheel, match):
    with pytest.raises(ValueError, match=match):
        rf.validate(wheel)


def test_validate_accepts_and_generic_model_needs_kappa():
    rf.validate(paper(0.0))
    rf.validate(paper(math.inf))
    rf.validate(FrictionWheel(4, 1.0, math.radians(20), 1.0))  # n = 4 has a window for kappa = 1 (15.7-25.3 deg)
    with pytest.raises(ValueError, match="slope: no admissible slope for spokes=3"):
        rf.validate(FrictionWheel(3, 1.0, math.radians(33), 1.0))  # n = 3: alpha_min 38.2 > alpha_max 28.7 deg
    with pytest.raises(ValueError, match="kappa must be > 0 for the generic model"):
        rf.contact_model(FrictionWheel(10, 0.0, math.radians(6), 1.0))


# --- generic Appendix-A matrices against the closed forms (rtol 1e-10) -----------------------------------------


def _states(seed: int, count: int) -> list[tuple[float, float, float]]:
    rng = np.random.default_rng(seed)
    return [(rng.uniform(-PHI, PHI), rng.uniform(0.05, 1.3), rng.uniform(0.0, 1.0)) for _ in range(count)]


@pytest.mark.parametrize("mu", [0.0, 0.3, 1.0])
def test_generic_slip_equals_eq42(mu):
    w = paper(mu)
    model = rf.contact_model(w)
    for th, thd, xd in _states(1, 10):
        for mode, sign in (("slip+", 1.0), ("slip-", -1.0)):
            cs = ss.contact_state(model, np.array([0.0, 0.0, th]), np.array([sign * xd, 0.0, thd]), mode, mu)
            thdd, xdd, f_n, den = rf.slip_dynamics(w, th, thd, sign)
            assert cs.qdd[2] == pytest.approx(thdd, rel=1e-10, abs=1e-12)
            assert cs.qdd[0] == pytest.approx(xdd, rel=1e-10, abs=1e-12)
            assert cs.qdd[1] == pytest.approx(0.0, abs=1e-12)  # v_n stays 0
            assert cs.force[1] / w.gravity == pytest.approx(f_n, rel=1e-10, abs=1e-12)
            assert cs.force[0] == pytest.approx(-sign * mu * cs.force[1], rel=1e-12, abs=1e-14)
            assert np.sign(cs.denominator) == np.sign(den)


def test_generic_stick_equals_eq19_and_eq12():
    w = paper(1.0)
    model = rf.contact_model(w)
    for th, thd, _ in _states(2, 10):
        cs = ss.contact_state(model, np.array([0.0, 0.0, th]), np.array([0.0, 0.0, thd]), "stick", 1.0)
        f_t, f_n = rf.sticking_forces(w, th, thd)
        assert cs.force / w.gravity == pytest.approx([f_t, f_n], rel=1e-10, abs=1e-13)
        assert cs.qdd == pytest.approx([0.0, 0.0, math.sin(th + ALPHA)], rel=1e-10, abs=1e-13)


def test_painleve_denominator():
    """Forward slip at theta < 0 is Painleve-inconsistent for mu > (kappa + sin^2)/(|sin| cos) (1.459 at -phi)."""
    limit = (KAPPA + math.sin(PHI) ** 2) / (math.sin(PHI) * math.cos(PHI))
    assert limit == pytest.approx(1.459, abs=5e-4)
    assert rf.slip_dynamics(paper(limit * 1.01), -PHI, 1.0, 1.0)[3] < 0.0
    assert rf.slip_dynamics(paper(limit * 0.99), -PHI, 1.0, 1.0)[3] > 0.0


@pytest.mark.parametrize("mu", [0.05, 0.24, 0.3, 1.0])
def test_generic_impacts_equal_eq43_eq45(mu):
    w = paper(mu)
    model = rf.contact_model(w)
    q = np.array([0.0, 0.0, PHI])
    mass, swing = model.mass_matrix(q), model.swing_jacobian(q)
    assert swing == pytest.approx(np.array([[1, 0, 0], [0, 1, -2 * math.sin(PHI)]]), abs=1e-15)  # W~_c of eq 11
    for _, thd, xd in _states(3, 8):
        qd = np.array([xd, 0.0, thd])
        qd_plus, imp = ss.sticking_impact(mass, swing, qd)
        cf = rf.sticking_impact(w, thd, xd)
        assert qd_plus[2] == pytest.approx(cf.theta_dot, rel=1e-10)
        assert (swing @ qd_plus) == pytest.approx([0.0, 0.0], abs=1e-14)
        assert imp == pytest.approx([cf.impulse_t, cf.impulse_n], rel=1e-10)
        for sign in (-1.0, 1.0):
            qd_plus, imp, _ = ss.slipping_impact(mass, swing, qd, mu, sign)
            cf = rf.slipping_impact(w, thd, xd, sign)
            assert qd_plus[2] == pytest.approx(cf.theta_dot, rel=1e-10, abs=1e-14)
            assert (swing @ qd_plus)[0] == pytest.approx(cf.x_dot, rel=1e-10, abs=1e-14)
            assert (swing @ qd_plus)[1] == pytest.approx(0.0, abs=1e-14)
            assert imp == pytest.approx([cf.impulse_t, cf.impulse_n], rel=1e-10, abs=1e-14)
        kind, cf = rf.impact_closed_form(w, thd, xd)
        out = ss.impact(model, q, qd, mu)
        assert out.kind == kind
        assert out.qd_plus[2] == pytest.approx(cf.theta_dot, rel=1e-10)
        assert out.liftoff_velocity == pytest.approx(2 * math.sin(PHI) * cf.theta_dot, rel=1e-10)


def test_impact_law_limits():
    w = paper(0.3)
    b = rf.beta(10, KAPPA)
    # eq 44 (corrected) at x_dot^- = 0 is eq 25; as x_dot^-/theta_dot^- -> inf it tends to (k + s^2)/(s c)
    cand = rf.sticking_impact(w, 1.0, 0.0)
    assert cand.impulse_t / cand.impulse_n == pytest.approx(rf.impulse_ratio(10, KAPPA), rel=1e-12)
    cand = rf.sticking_impact(w, 1.0, 1e9)
    limit = (KAPPA + math.sin(PHI) ** 2) / (math.sin(PHI) * math.cos(PHI))
    assert abs(cand.impulse_t / cand.impulse_n) == pytest.approx(limit, rel=1e-8)
    # continuity of the two laws at mu = |sigma~| (x_dot^- = 0), frictionless gain, 002's slipping gains
    edge = paper(abs(rf.impulse_ratio(10, KAPPA)))
    assert rf.slipping_impact(edge, 1.0, 0.0, -1.0).theta_dot == pytest.approx(b, rel=1e-12)
    assert rf.slipping_impact(edge, 1.0, 0.0, -1.0).x_dot == pytest.approx(0.0, abs=1e-14)
    gain0 = (KAPPA - math.sin(PHI) ** 2) / (KAPPA + math.sin(PHI) ** 2)
    assert rf.slipping_impact(paper(0.0), 1.0, 0.0, -1.0).theta_dot == pytest.approx(gain0, rel=1e-12)
    # 0.80158 = 0.775514/0.967486 of the Type D table (derivation page Sec. 2)
    assert rf.slipping_impact(paper(0.2), 1.0, 1.0, -1.0).theta_dot == pytest.approx(0.80158, abs=1e-5)
    assert rf.slipping_impact(paper(0.3), 1.0, 1.0, -1.0).theta_dot == pytest.approx(0.9570, abs=1e-4)


# --- the two step implementations, and the sticking map ----------------------------------------------------------


@pytest.mark.parametrize(
    ("mu", "state", "phases"),
    [
        (0.3, (0.88075, 0.0), ("stick", "slip+")),
        (0.24, (0.875749, 0.012098), ("slip+", "stick", "slip+")),
        (0.3, (1.12, 0.7), ("slip+",)),
        (0.3, (0.5, -0.3), ("slip-", "stick")),
        (1.0, (1.1374, 0.0), ("stick", "slip+")),
        (0.26, (0.1, 0.0), ("slip+",)),
        (0.1, (0.9, -0.2), ("slip-", "slip+", "stick", "slip+")),  # slip reversal (002 eq 35)
        (0.02, (0.6, -0.5), ("slip-", "slip+", "slip-")),
    ],
)
def test_fast_step_equals_generic_step(mu, state, phases):
    w = paper(mu)
    fast = rf.step(w, state)
    gen = rf.step(w, state, method="generic")
    assert fast.phases == gen.phases == phases
    assert fast.failure == gen.failure
    assert fast.phase_angles == pytest.approx(gen.phase_angles, abs=1e-9)
    if fast.failure is None:
        assert fast.impact == gen.impact
        assert (fast.theta_dot, fast.x_dot) == pytest.approx((gen.theta_dot, gen.x_dot), abs=1e-9)
        assert (fast.theta_dot_pre, fast.x_dot_pre) == pytest.approx((gen.theta_dot_pre, gen.x_dot_pre), abs=1e-9)
        assert fast.duration == pytest.approx(gen.duration, abs=1e-9)
        assert fast.midstance == pytest.approx(gen.midstance, abs=1e-9)
        assert fast.min_fn == pytest.approx(gen.min_fn, abs=1e-6)
    else:
        assert fast.failure_angle == pytest.approx(gen.failure_angle, abs=1e-8)


def test_generic_stance_log():
    w = paper(0.3)
    res = ss.integrate_stance(rf.contact_model(w), [0.0, 0.0, -PHI], [0.0, 0.0, 0.88075], 0.3)
    assert res.impacted and not res.detached and res.failure is None
    assert [p.mode for p in res.phases] == ["stick", "slip+"]
    mode, t_start, q_start = res.phases[1][:3]
    assert mode == "slip+" and t_start > 0 and q_start[2] == pytest.approx(0.2061690, abs=1e-6)
    assert res.q_end[2] == pytest.approx(PHI, abs=1e-10)


@pytest.mark.parametrize("theta_dot", [0.3, 0.6, 0.876031187, 0.94])
def test_sticking_map_is_eq15_for_large_mu(theta_dot):
    w = paper(1e3)
    rec = rf.step(w, (theta_dot, 0.0))
    assert rec.phases == ("stick",) and rec.impact == "sticking" and rec.x_dot == 0.0
    assert rec.theta_dot == pytest.approx(rf.sticking_map(w, theta_dot), rel=1e-10)
    assert rec.duration == pytest.approx(rw.step_period(rf.rigid_wheel(w), theta_dot), rel=1e-9)
    assert rec.midstance[0] == pytest.approx(rw.phase_speed(rf.rigid_wheel(w), theta_dot, ALPHA), rel=1e-10)


# --- gaits (derivation page Sec. 2 tables and Sec. 5 oracles) ----------------------------------------------------


def test_type_a():
    g = rf.find_gait(paper(2.0), "A")
    assert g is not None and g.kind == "A" and g.phases == ("stick",) and g.impact == "sticking"
    assert g.fixed_point[0] == pytest.approx(0.876031187, rel=1e-9)
    assert g.eigenvalues[0].real == pytest.approx(0.7340424026, abs=1e-5)
    assert g.period == pytest.approx(0.686850, abs=1e-6)
    assert rf.midstance_rate(g) == pytest.approx(0.900600, abs=1e-6)
    assert rf.find_gait(paper(0.5), "A") is None
    assert rf.find_gait(paper(2.0), "B") is None


@pytest.mark.parametrize(
    ("mu", "th_star", "lam", "onset", "x_pre", "th_pre", "ratio", "phases"),
    [
        (0.3, 0.880750, 0.76226, 0.20617, 0.011785, 1.018186, -0.24283, ("stick", "slip+")),
        (0.5, 0.877345, 0.74963, 0.26475, 0.003358, 1.021227, -0.23896, ("stick", "slip+")),
        (0.25, 0.882570, 0.76696, 0.17865, 0.016099, 1.016718, -0.24481, ("slip+", "stick", "slip+")),
    ],
)
def test_type_b(mu, th_star, lam, onset, x_pre, th_pre, ratio, phases):
    g = rf.find_gait(paper(mu), "B")
    assert g is not None and g.kind == "B" and g.impact == "sticking" and g.phases == phases
    assert g.fixed_point[0] == pytest.approx(th_star, abs=2e-6)
    assert g.eigenvalues[0].real == pytest.approx(lam, abs=2e-5)
    assert g.phase_angles[-1] == pytest.approx(onset, abs=2e-5)
    assert g.pre_impact == pytest.approx((th_pre, x_pre), abs=2e-6)
    assert g.impulse_ratio == pytest.approx(ratio, abs=2e-5)


def test_type_b_midstance():
    assert rf.midstance_rate(rf.find_gait(paper(0.3), "B")) == pytest.approx(0.905190, abs=1e-6)
    assert rf.midstance_rate(rf.find_gait(paper(0.5), "B")) == pytest.approx(0.901877, abs=1e-6)
    assert rf.midstance_x_dot(rf.find_gait(paper(0.3), "B")) == 0.0


def test_type_c():
    g = rf.find_gait(paper(0.24), "C")
    assert g is not None and g.kind == "C" and g.impact == "slipping"
    assert g.phases == ("slip+", "stick", "slip+")
    assert g.fixed_point == pytest.approx([0.875749, 0.012098], abs=2e-6)
    assert abs(g.eigenvalues[0]) == pytest.approx(0.78125, abs=2e-5)
    assert abs(g.eigenvalues[1]) < 1e-6  # the slip -> stick event erases x_dot: rank-1 Jacobian
    assert g.pre_impact[1] == pytest.approx(0.01770, abs=1e-5)
    assert g.impulse_ratio == pytest.approx(-0.24, rel=1e-12)
    assert rf.find_gait(paper(0.3), "C") is None
    assert rf.find_gait(paper(0.24), "B") is None


@pytest.mark.parametrize(
    ("mu", "kind", "th_star", "lam", "dx", "th_pre", "period", "mid"),
    [
        (0.3, "D-", 1.072038, 0.35599, -0.051723, 1.120204, 0.57589, 1.089526),
        (0.2, "D+", 0.775514, 0.34416, 0.030536, 0.967486, 0.76144, 0.809861),
    ],
)
def test_type_d(mu, kind, th_star, lam, dx, th_pre, period, mid):
    w = paper(mu)
    g = rf.find_gait(w, "D")
    assert g is not None and g.kind == kind and g.phases == ("slip+",) and g.impact == "slipping"
    assert g.fixed_point[0] == pytest.approx(th_star, abs=2e-6)
    assert g.eigenvalues[0].real == pytest.approx(lam, abs=2e-5)
    assert g.dx_per_step == pytest.approx(dx, abs=2e-6)
    assert g.pre_impact[0] == pytest.approx(th_pre, abs=2e-6)
    assert g.period == pytest.approx(period, abs=2e-5)
    assert rf.midstance_rate(g) == pytest.approx(mid, abs=2e-6)
    # exact identities derived here: affine slip map, and momentum balance Delta x_dot = g T (sin a - mu cos a)
    th_lin, lam_lin = rf.type_d_linear(w)
    assert g.fixed_point[0] == pytest.approx(th_lin, rel=1e-9)
    assert g.eigenvalues[0].real == pytest.approx(lam_lin, abs=1e-6)
    assert g.dx_per_step == pytest.approx(w.gravity * g.period * (math.sin(ALPHA) - mu * math.cos(ALPHA)), rel=1e-8)


def test_type_d_edges_of_existence():
    assert rf.find_gait(paper(0.35), "D") is None  # detaches during the slip
    assert rf.find_gait(paper(0.07), "D") is None  # rolls back
    g = rf.find_gait(paper(0.08), "D")
    assert g is not None and g.fixed_point[0] == pytest.approx(0.422903, abs=2e-6)
    assert g.period == pytest.approx(4.66105, abs=1e-4)


def test_transient_fig36():
    """mu = 0.3 from (1.12, 0.7): D- transient, first sticking impact at k = 15, then Type B (002 Fig. 3.6)."""
    w = paper(0.3)
    z = (1.12, 0.7)
    table = {1: (1.08935, 0.68189), 2: (1.07823, 0.64237), 5: (1.07232, 0.49370), 10: (1.07204, 0.23539),
             14: (1.072038, 0.028505), 15: (1.05548, 0.0)}
    records = []
    for k in range(1, 16):
        rec = rf.step(w, z)
        records.append(rec)
        z = rec.post
        if k in table:
            assert z == pytest.approx(table[k], abs=6e-6)
        assert rec.impact == ("sticking" if k == 15 else "slipping")
    assert rf.classify(records[:14]) == "D-"
    assert rf.classify(records) == "B"
    settled = rf.settle(w, (1.12, 0.7))
    assert settled.outcome == "B"
    assert settled.records[-1].theta_dot == pytest.approx(0.880750, abs=2e-6)


def test_settle_d_plus_and_classify():
    settled = rf.settle(paper(0.2), (0.8, 0.5), tol=1e-8)
    assert settled.outcome == "D+"
    assert settled.records[-1].theta_dot == pytest.approx(0.775514, abs=2e-6)
    assert rf.classify([]) is None
    assert rf.classify([rf.step(paper(0.3), (0.05, 0.0))]) == "backward"


# --- regions of attraction (002 Sec. 3.4, Fig. 3.8) -------------------------------------------------------------


def test_attraction_window_mu_inf_is_eq26():
    assert rf.attraction_window(paper(math.inf)) == pytest.approx(rf.attraction_window_rigid(paper(math.inf)),
                                                                  abs=1e-7)


@pytest.mark.parametrize(("mu", "lower", "upper"), [(1.0, 0.0872388, 1.13734), (0.28, 0.09173, 1.14238)])
def test_attraction_window_finite_mu(mu, lower, upper):
    lo, hi = rf.attraction_window(paper(mu))
    assert lo == pytest.approx(lower, abs=1e-5)
    assert hi == pytest.approx(upper, abs=2e-5)
    assert hi > rf.attraction_window_rigid(paper(mu))[1] + 0.15  # slip enlarges the region (002 Sec. 3.4)


def test_attraction_window_large_mu_limit():
    assert rf.attraction_upper_limit(paper(1e6)) == pytest.approx(1.12050, abs=1e-5)
    assert rf.attraction_window(paper(1e6))[1] == pytest.approx(rf.attraction_upper_limit(paper(1e6)), abs=1e-6)
    assert rf.step(paper(1e6), (1.121, 0.0)).failure == "painleve"


def test_fig38b_and_fig38c():
    """mu = 1, theta_dot0 = 1: stick -> slip at 0.1629; the sticking continuation would reach f_n = 0 at 0.2562.
    At theta_dot0 just above theta_dot_max(1): slip from -0.1455, detachment near theta = 0 (paper -0.01)."""
    rec = rf.step(paper(1.0), (1.0, 0.0))
    assert rec.phases == ("stick", "slip+") and rec.impact == "sticking"
    assert rec.phase_angles[1] == pytest.approx(0.16290, abs=1e-5)
    assert rec.x_dot_pre == pytest.approx(0.03102, abs=1e-5)
    assert rec.impulse_ratio == pytest.approx(-0.2504, abs=1e-4)
    rigid = rf.step(paper(math.inf), (1.0, 0.0))
    assert rigid.failure == "detached" and rigid.failure_angle == pytest.approx(0.25624, abs=1e-5)
    top = rf.step(paper(1.0), (1.13734 + 1e-5, 0.0))
    assert top.failure == "detached"
    assert top.phase_angles[1] == pytest.approx(-0.1455, abs=2e-4)
    assert abs(top.failure_angle) < 0.01


def test_basin_outcome():
    w = paper(0.3)
    labels, steps = rf.basin_outcome(w, [0.05, 0.5, 0.88, 1.12, 1.3], [0.0, 0.0, 0.0, 0.7, 0.0])
    assert list(labels) == ["backward", "B", "B", "B", "detached"]
    assert steps[0] == steps[4] == -1
    assert steps[3] > 15  # the D- transient of Fig. 3.6 first
    grid_labels, _ = rf.basin_outcome(w, np.array([[0.5], [0.6]]), 0.0)
    assert grid_labels.shape == (2, 1)
    # slip slows convergence: from the same start, Type B (mu = 0.3) needs more steps than Type A (mu = 2)
    _, steps_a = rf.basin_outcome(paper(2.0), 0.5, 0.0, tol=1e-6)
    _, steps_b = rf.basin_outcome(w, 0.5, 0.0, tol=1e-6)
    assert steps_b > steps_a > 0


# --- gait-type boundaries in mu (derivation page Sec. 5, atol 2e-3) ---------------------------------------------


def test_gait_boundaries():
    b = rf.gait_boundaries(KAPPA, 10, ALPHA)
    assert b.ab == pytest.approx(0.91412, abs=2e-3)
    assert b.ab == pytest.approx(rf.critical_friction(paper(math.inf))[0], abs=2e-6)
    assert b.bc == pytest.approx(0.24505, abs=2e-3)
    assert b.d_sign == pytest.approx(0.23087, abs=2e-3)
    assert b.d_sign == pytest.approx(math.tan(ALPHA), abs=2e-6)
    assert b.d_upper == pytest.approx(0.3213, abs=2e-3)
    assert b.d_lower == pytest.approx(0.0800, abs=2e-3)
    assert b.start_slip == pytest.approx(0.3008, abs=2e-3)
    assert b.c_lower == pytest.approx(math.tan(ALPHA), abs=2e-5)  # C ends where D has Delta x_dot = 0 (grazing)
    # the paper's rounded values (+-0.01): A mu >= 0.91, B [0.25, 0.91], C (0.24, 0.25), D [0.1, 0.32]
    assert (b.ab, b.bc, b.d_upper) == pytest.approx((0.91, 0.25, 0.32), abs=0.01)


def test_longest_period_and_no_gait_reason():
    w = paper(0.3)
    rigid = rf.find_gait(paper(math.inf), "A")
    longest = max(rf.attractors(w)[0].period, rigid.period)
    assert rf.longest_period(w, [0.3]) == pytest.approx(longest)
    assert rf.longest_period(w, [0.3, 2.0]) >= longest
    low = paper(0.05)
    assert not rf.attractors(low)
    assert rf.no_gait_reason(low).startswith(f"mu must be >= {rf.gait_boundaries(KAPPA, 10, ALPHA).d_lower:.4f}")
