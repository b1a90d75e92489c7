"""Rimless-wheel theory (003 Kiša 2020 Sec. 3; 002 Gamus & Or 2015 Sec. 3.1) against published numbers
and against the independent event-driven reference simulator."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.theory import rimless_wheel as rw
from mjpoincare.analysis.theory.rimless_wheel import RimlessWheel
from mjpoincare.analysis.theory.rimless_wheel import hybrid as hy

ALPHA8 = math.pi / 8
KAPPA_PAPER = 1.0 / 3.0


def paper_wheel(spokes: int = 10, kappa: float = KAPPA_PAPER, slope_deg: float = 13.0) -> RimlessWheel:
    """002's parameter sets (l = 1, g = 9.81); gyration = l sqrt(kappa)."""
    return RimlessWheel(spokes, math.radians(slope_deg), gyration=math.sqrt(kappa))


# --- docs/theory/rimless-wheel-and-compass-gait.md Sec. 1.6: (n, gamma, region, omega_f, omega_b, omega*, -omega_f/c,
# T*) ---------------------------------------------------------------------------------------------------------------
TABLE_16 = [
    (8, math.pi / 15, 5, 0.57318, -1.85759, 1.76695, -0.81060, 0.41762),
    (8, math.pi / 8, 2, 0.0, -2.39720, 2.39720, 0.0, 0.28806),
    (8, math.pi / 7, 1, 0.0, -2.55857, 2.55253, None, 0.26815),
    (8, 0.08, 5, 0.97542, -1.46679, 1.09546, -1.37945, 1.03455),
    (10, 0.1, 5, 0.66949, -1.28793, 1.51437, -0.82753, 0.42319),
    (6, 0.3, 5, 0.69887, -2.50730, 1.39022, -1.39775, 0.66047),
]


@pytest.mark.parametrize(
    ("n", "gamma", "region", "omega_f", "omega_b", "omega_star", "edge", "period"), TABLE_16
)
def test_table_16(n, gamma, region, omega_f, omega_b, omega_star, edge, period):
    w = RimlessWheel(n, gamma)
    assert rw.region(w) == region
    assert rw.forward_threshold(w) == pytest.approx(omega_f, abs=6e-6)
    assert rw.rolling_fixed_point(w) == pytest.approx(omega_star, abs=6e-6)
    assert rw.rolling_multiplier(w) == pytest.approx(math.cos(2 * w.alpha) ** 2, rel=1e-12)
    assert rw.step_period(w, rw.rolling_fixed_point(w)) == pytest.approx(period, abs=6e-6)
    if region != 1:  # the printed omega_b is the (3.7) value; for gamma > alpha the threshold is -sqrt(K)
        assert rw.backward_threshold(w) == pytest.approx(omega_b, abs=6e-6)
        assert -rw.forward_threshold(w) / w.beta == pytest.approx(edge, abs=6e-6)
    else:
        assert rw.backward_threshold(w) == pytest.approx(
            -2 * math.sqrt(9.81 * math.sin(gamma) * math.sin(ALPHA8))
        )


def test_omega3_has_no_rolling_point():
    w = RimlessWheel(8, 0.025)  # Fig 5: the formula gives 0.61268 < omega_f = 1.14519
    assert rw.region(w) == 3
    assert not rw.rolling_exists(w)
    assert math.isnan(rw.rolling_fixed_point(w))
    assert rw.standing_exists(w)
    assert rw.standing_multiplier(w) == pytest.approx(-math.cos(math.pi / 4))
    assert rw.forward_threshold(w) == pytest.approx(1.14519, abs=6e-6)


def test_omega1_has_no_standing_point():
    w = RimlessWheel(8, math.pi / 7)
    assert not rw.standing_exists(w)
    assert math.isnan(rw.standing_multiplier(w))


def test_existence_bound_table():
    expected = {5: 0.339721, 6: 0.178160, 7: 0.105767, 8: 0.068229, 10: 0.033439, 12: 0.018904, 16: 0.007794}
    for n, gamma_star in expected.items():
        assert rw.existence_bound(n) == pytest.approx(gamma_star, abs=6e-7)
    # g-independent for kappa = 0; on the curve omega_f = omega_roll = 1.011817 (n = 8) and the region is 4
    assert rw.existence_bound(8, gravity=1.62) == pytest.approx(rw.existence_bound(8), rel=1e-12)
    gs = rw.existence_bound(8)
    on_curve = RimlessWheel(8, gs)
    assert rw.region(on_curve) == 4
    assert rw.forward_threshold(on_curve) == pytest.approx(1.011817, abs=6e-7)
    assert rw.rolling_exists(RimlessWheel(8, gs * (1 + 1e-6)))
    assert not rw.rolling_exists(RimlessWheel(8, gs * (1 - 1e-6)))


def test_no_flight_bound_table():
    expected = {5: 0.248587, 6: 0.266954, 8: 0.262076, 10: 0.239978, 12: 0.216104, 16: 0.175727, 20: 0.146163}
    for n, gamma_fly in expected.items():
        assert rw.no_flight_bound(n) == pytest.approx(gamma_fly, abs=6e-7)
    # kappa = 0: the condition of derivation page Sec. 1.9 is 4 sin g sin a / sin^2 2a = cos(g + a) at the bound
    g, a = rw.no_flight_bound(8), ALPHA8
    assert 4 * math.sin(g) * math.sin(a) / math.sin(2 * a) ** 2 == pytest.approx(math.cos(g + a), rel=1e-10)


# --- 002 oracles for the paper set and other parameter sets (nondimensional speeds, omega_c = sqrt(rate2)) --
def test_paper_set_oracles():
    w = paper_wheel()
    wc = math.sqrt(w.rate2)
    star = rw.rolling_fixed_point(w)
    assert w.beta == pytest.approx(0.8567627458, abs=1e-10)
    assert rw.rolling_multiplier(w) == pytest.approx(0.7340424026, abs=1e-10)
    assert star / wc == pytest.approx(0.876031187, abs=1e-9)
    assert rw.phase_speed(w, star, w.slope + w.alpha) / wc == pytest.approx(1.022489822, abs=1e-9)
    assert rw.phase_speed(w, star, w.slope) / wc == pytest.approx(0.900600, abs=1e-6)
    assert rw.step_period(w, star) * wc == pytest.approx(0.686850, abs=1e-6)
    assert math.degrees(rw.existence_bound(10, math.sqrt(KAPPA_PAPER))) == pytest.approx(1.40005, abs=1e-5)
    assert math.degrees(rw.no_flight_bound(10, math.sqrt(KAPPA_PAPER))) == pytest.approx(14.71294, abs=1e-5)
    assert rw.required_friction(w) == pytest.approx(0.914121, abs=1e-6)
    assert rw.impact_impulse_ratio(w) == pytest.approx(-0.2374234, abs=1e-7)
    assert rw.forward_threshold(w) / wc == pytest.approx(0.0872388, abs=1e-7)
    # theta_dot_max = 0.9594879: largest post-impact speed whose first step keeps f_n >= 0
    assert rw.step_stays_in_contact(w, 0.959487 * wc)
    assert not rw.step_stays_in_contact(w, 0.959489 * wc)


# (n, kappa, slope deg, theta*, step time, mu_c, sigma~, alpha_min deg, alpha_max deg)
TABLE_002 = [
    (10, 1 / 3, 5, 0.545285, 1.18308, 0.24414, -0.23742, 1.400, 14.713),
    (8, 1 / 3, 10, 0.643321, 1.19026, 0.32211, -0.29788, 2.812, 16.646),
    (6, 1 / 2, 15, 0.643514, 1.53522, 0.83813, -0.34641, 6.135, 19.394),
    (10, 1.0, 10, 0.982642, 0.62663, 0.37818, -0.15431, 0.910, 15.739),
    (10, 0.0, 6, 0.494740, 1.28624, 0.32492, -0.32492, 1.916, 13.750),
]


@pytest.mark.parametrize(("n", "kappa", "deg", "star", "period", "mu", "sigma", "amin", "amax"), TABLE_002)
def test_002_parameter_sets(n, kappa, deg, star, period, mu, sigma, amin, amax):
    w = paper_wheel(n, kappa, deg)
    wc = math.sqrt(w.rate2)
    assert rw.rolling_fixed_point(w) / wc == pytest.approx(star, abs=6e-6)
    assert rw.step_period(w, rw.rolling_fixed_point(w)) * wc == pytest.approx(period, abs=6e-5)
    assert rw.required_friction(w) == pytest.approx(mu, abs=6e-5)
    assert rw.impact_impulse_ratio(w) == pytest.approx(sigma, abs=6e-6)
    assert math.degrees(rw.existence_bound(n, math.sqrt(kappa))) == pytest.approx(amin, abs=6e-4)
    assert math.degrees(rw.no_flight_bound(n, math.sqrt(kappa))) == pytest.approx(amax, abs=6e-4)


def test_kappa_zero_force_identities():
    w = RimlessWheel(8, 0.08)
    th = np.linspace(w.slope - w.alpha, w.slope + w.alpha, 7)
    om = np.linspace(0.3, 1.7, 7)
    fn = rw.normal_force_ratio(w, th, om)
    ft = rw.tangential_force_ratio(w, th, om)
    np.testing.assert_allclose(fn, (np.cos(th) - om**2 / 9.81) * np.cos(th - w.slope), rtol=1e-13)
    np.testing.assert_allclose(ft / fn, np.tan(th - w.slope), rtol=1e-12, atol=1e-15)  # force along the spoke
    assert rw.required_friction(w) == pytest.approx(math.tan(ALPHA8), rel=1e-10)
    assert rw.impact_impulse_ratio(w) == pytest.approx(-math.tan(ALPHA8), rel=1e-13)


# --- return map ---------------------------------------------------------------------------------------------
def test_corrected_backward_branch_for_steep_slope():
    w = RimlessWheel(8, 0.8)  # gamma > alpha: threshold -sqrt(K) = -3.28210, not omega_b = -3.51813
    assert rw.backward_threshold(w) == pytest.approx(-3.28210, abs=6e-6)
    assert rw.return_map(w, -3.40011) == pytest.approx(-0.627931, abs=3e-5)  # printed input is rounded
    assert rw.return_map(w, -3.40011) == pytest.approx(hy.hybrid_return_map(w, -3.40011), abs=1e-9)
    assert rw.return_map(w, rw.backward_threshold(w)) == pytest.approx(
        0.0, abs=1e-7
    )  # continuous at -sqrt(K)


@pytest.mark.parametrize(
    ("n", "gamma", "omega"),
    [
        (8, 0.08, 1.5),  # forward
        (8, 0.08, 0.6),  # rocking forward
        (8, 0.08, -1.0),  # rocking backward
        (8, 0.08, -2.5),  # backward step through the vertical
        (8, 0.8, -2.0),  # gamma > alpha rocking
        (8, 0.8, 0.0),  # gamma > alpha, start at rest
    ],
)
def test_return_map_matches_hybrid(n, gamma, omega):
    w = RimlessWheel(n, gamma)
    assert rw.return_map(w, omega) == pytest.approx(hy.hybrid_return_map(w, omega), abs=1e-9)


def test_return_map_with_hub_inertia_matches_hybrid():
    w = paper_wheel()
    for omega in (0.3, -0.5, -3.0):
        assert rw.return_map(w, omega) == pytest.approx(hy.hybrid_return_map(w, omega), abs=1e-9)


def test_return_map_vectorised_and_thresholds_nan():
    w = RimlessWheel(8, 0.08)
    om = np.array([-3.0, -1.0, 0.5, 2.0, rw.forward_threshold(w), rw.backward_threshold(w)])
    out = rw.return_map(w, om)
    np.testing.assert_array_equal(out[:4], [rw.return_map(w, x) for x in om[:4]])
    assert np.isnan(out[4:]).all()
    assert isinstance(rw.return_map(w, 2.0), float)


def test_return_map_derivative_by_finite_differences():
    for w, oms in (
        (RimlessWheel(8, 0.08), (-2.5, -1.0, 0.5, 1.6)),
        (RimlessWheel(8, 0.8), (-4.0, -2.0, 1.0)),
    ):
        h = 1e-6
        for om in oms:
            fd = (rw.return_map(w, om + h) - rw.return_map(w, om - h)) / (2 * h)
            assert rw.return_map_derivative(w, om) == pytest.approx(fd, rel=1e-7)
    w = RimlessWheel(8, 0.08)
    assert rw.return_map_derivative(w, rw.rolling_fixed_point(w)) == pytest.approx(rw.rolling_multiplier(w))
    assert rw.return_map_derivative(w, 0.0) == pytest.approx(rw.standing_multiplier(w))


# docs/theory/rimless-wheel-and-compass-gait.md Sec. 1.8 post-impact sequences (gamma, sequence)
FIGS = [
    (0.025, [1.660746, 1.251689, 0.985418, -0.696796, 0.492709, -0.348398]),
    (math.pi / 7, [3.918914, 3.307060, 2.953986, 2.760566, 2.658584, 2.606097]),
    (math.pi / 15, [-3.551090, -2.178088, -0.900545, 0.636781, 1.328081, 1.562994]),
    (math.pi / 15, [-3.445503, -2.091577, -0.791387, 0.559595, -0.395694, 0.279798]),
]


@pytest.mark.parametrize(("gamma", "seq"), FIGS)
def test_figure_sequences(gamma, seq):
    w = RimlessWheel(8, gamma)
    seq = np.array(seq)
    np.testing.assert_allclose(rw.return_map(w, seq[:-1]), seq[1:], atol=3e-6)


def test_first_impact_from_mid_swing_state():
    # Fig 5 (theta, theta_dot) = (-0.132, 2) and Fig 6 (0.292, 5): pull back to the section, step, impact
    for gamma, theta, omega, first in ((0.025, -0.132, 2.0, 1.660746), (math.pi / 7, 0.292, 5.0, 3.918914)):
        w = RimlessWheel(8, gamma)
        post = rw.post_impact_speed(w, theta, omega)
        assert rw.phase_speed(w, post, theta) == pytest.approx(omega, rel=1e-13)
        assert w.beta * rw.phase_speed(w, post, w.slope + w.alpha) == pytest.approx(first, abs=6e-7)


def test_figure_radial_forces():
    # derivation page Sec. 1.8: the last column is the spoke (radial) force N/(mg) = f_n/(mg cos psi);
    # here the minima sit at psi = +-alpha
    for gamma, seq, radial in (
        (math.pi / 7, [3.918914, 3.307060, 2.953986, 2.760566], [-1.113, -0.887, -0.775]),
        (math.pi / 15, [-3.551090, -2.178088, -0.900545, 0.636781], [0.341, 0.741, 0.465]),
    ):
        w = RimlessWheel(8, gamma)
        got = [rw.excursion_min_normal_force(w, om) / math.cos(w.alpha) for om in seq[1:]]
        np.testing.assert_allclose(got, radial, atol=6e-4)


# --- basins -------------------------------------------------------------------------------------------------
BANDS = [
    ((-1.857591, -0.810603), (-2.106243, -1.857591)),
    ((-3.165974, -2.106243), (-3.463326, -3.165974)),
    ((-4.813408, -3.463326), (-5.206857, -4.813408)),
    ((-7.032773, -5.206857), (-7.572636, -7.032773)),
    ((-10.101579, -7.572636), (-10.854112, -10.101579)),
]


def _iterate_outcome(w: RimlessWheel, omega: float | np.ndarray, steps: int = 80) -> np.ndarray:
    for _ in range(steps):
        omega = rw.return_map(w, omega)
    return np.where(np.abs(omega) < 1e-6, "standing", "rolling")


def test_basin_bands_table_and_outcomes():
    w = RimlessWheel(8, math.pi / 15)
    omega1, omega2 = rw.basin_band_edges(w, 4)
    assert omega1.shape == (5,) and omega2.shape == (6,)
    for m, (roll, stop) in enumerate(BANDS):
        np.testing.assert_allclose([omega1[m], omega2[m]], roll, atol=6e-7)
        np.testing.assert_allclose([omega2[m + 1], omega1[m]], stop, atol=6e-7)
        for band, label in ((roll, "rolling"), (stop, "standing")):
            mid = 0.5 * (band[0] + band[1])
            assert rw.predicted_outcome(w, mid) == label == _iterate_outcome(w, mid)
    # P^m(omega_1^m) = omega_b
    x = omega1[3]
    for _ in range(3):
        x = float(rw.return_map(w, x))
    assert x == pytest.approx(rw.backward_threshold(w), abs=1e-12)
    for om in (-0.5, 0.0, 0.3):
        assert rw.predicted_outcome(w, om) == "standing"
    assert rw.predicted_outcome(w, 1.0) == "rolling"
    assert rw.predicted_outcome(w, -3.551090) == "rolling"  # Fig 12
    assert rw.predicted_outcome(w, -3.445503) == "standing"  # Fig 13
    assert rw.predicted_outcome(w, omega2[2] + 5e-10) == "boundary"
    assert rw.predicted_outcome(w, rw.forward_threshold(w)) == "boundary"


def test_outcomes_in_other_regions():
    rng = np.random.default_rng(3)
    for gamma in (math.pi / 7, math.pi / 8, 0.025):
        w = RimlessWheel(8, gamma)
        oms = rng.uniform(-8, 8, 25)
        expected = _iterate_outcome(w, oms, 200)
        assert [rw.predicted_outcome(w, om) for om in oms] == list(expected)
    assert (
        rw.predicted_outcome(RimlessWheel(8, math.pi / 8), 0.0) == "boundary"
    )  # Ω2: unstable standing point
    w3 = RimlessWheel(8, 0.025)
    preimage = math.sqrt((rw.forward_threshold(w3) / w3.beta) ** 2 - w3.K)  # lands on omega_f: in H
    assert rw.predicted_outcome(w3, preimage) == "boundary"
    w4 = RimlessWheel(8, rw.existence_bound(8))
    assert rw.predicted_outcome(w4, 3.0) == "rolling"
    assert rw.predicted_outcome(w4, 0.5) == "standing"
    with pytest.raises(ValueError, match="beta"):
        rw.predicted_outcome(RimlessWheel(4, 0.1), 1.0)


def test_flight_free():
    assert not rw.flight_free(RimlessWheel(8, math.pi / 7), 3.918914, 3)  # Fig 6 flies
    assert rw.flight_free(RimlessWheel(8, 0.025), 1.660746, 30)  # Fig 5 stays down while it rocks to rest
    assert rw.flight_free(RimlessWheel(8, 0.08), 1.2, 10)


# --- the hybrid reference -----------------------------------------------------------------------------------
@pytest.mark.parametrize("w", [RimlessWheel(8, 0.08), paper_wheel(), RimlessWheel(6, 0.2, leg_length=0.7)])
def test_fixed_point_period_forces_against_hybrid(w):
    star = rw.rolling_fixed_point(w)
    assert hy.hybrid_fixed_point(w) == pytest.approx(star, rel=1e-8)
    res = hy.simulate_hybrid(w, star, 1)
    assert res.kinds == ("forward",) and res.outcome == "rolling"
    assert res.t_impacts[0] == pytest.approx(rw.step_period(w, star), rel=1e-9)
    assert res.min_normal_force[0] == pytest.approx(rw.excursion_min_normal_force(w, star), abs=1e-8)
    assert res.max_friction_ratio[0] == pytest.approx(rw.required_friction(w), rel=1e-7)
    assert res.impulse_ratio[0] == pytest.approx(rw.impact_impulse_ratio(w), rel=1e-9)


def test_required_friction_infinite_when_orbit_flies():
    assert rw.required_friction(RimlessWheel(6, 0.3)) == math.inf  # 0.3 > gamma_fly(6) = 0.266954
    assert math.isnan(rw.required_friction(RimlessWheel(8, 0.025)))  # no rolling gait


def test_multiplier_against_hybrid():
    w = paper_wheel()
    assert hy.hybrid_multiplier(w) == pytest.approx(rw.rolling_multiplier(w), abs=1e-6)


def test_contact_force_against_constrained_dynamics():
    rng = np.random.default_rng(7)
    for w in (
        RimlessWheel(8, 0.08, mass=2.5),
        paper_wheel(),
        RimlessWheel(12, 0.2, leg_length=0.4, gyration=0.1),
    ):
        theta = rng.uniform(w.slope - w.alpha, w.slope + w.alpha, 6)
        omega = rng.uniform(-3, 3, 6)
        psi = theta - w.slope
        qd = np.stack(
            [w.leg_length * omega * np.cos(psi), -w.leg_length * omega * np.sin(psi), omega], axis=-1
        )
        qdd, lam = hy.stance_dynamics(w, psi, qd)
        np.testing.assert_allclose(qdd[:, 2], w.rate2 * np.sin(theta), rtol=1e-12)
        mg = w.mass * w.gravity
        np.testing.assert_allclose(lam[:, 1] / mg, rw.normal_force_ratio(w, theta, omega), atol=1e-12)
        np.testing.assert_allclose(lam[:, 0] / mg, rw.tangential_force_ratio(w, theta, omega), atol=1e-12)


def test_hybrid_sequence_and_flight_flag():
    w = RimlessWheel(8, math.pi / 15)
    res = hy.simulate_hybrid(w, -3.551090, 6)
    expected = [-3.551090]
    for _ in range(6):
        expected.append(float(rw.return_map(w, expected[-1])))
    np.testing.assert_allclose(res.omega_post, expected[1:], atol=1e-9)
    assert res.kinds == ("backward", "backward", "rock", "forward", "forward", "forward")
    assert res.outcome == "rolling" and res.flight  # first stance has f_n < 0 (derivation page Sec. 1.8)
    expected_fn = [rw.excursion_min_normal_force(w, om) for om in expected[:-1]]
    np.testing.assert_allclose(res.min_normal_force, expected_fn, atol=1e-8)
    stopped = hy.simulate_hybrid(w, -3.551090, 6, stop_on_flight=True)
    assert stopped.outcome == "flight" and stopped.omega_post.size == 1


def test_hybrid_zeno_standing():
    # derivation page Sec. 1.5: alpha = pi/8, gamma = 0.025, omega0 = 0.5 rocks to rest at t ~ 0.950 s
    res = hy.simulate_hybrid(RimlessWheel(8, 0.025), 0.5, 200)
    assert res.outcome == "standing"
    assert res.t_impacts[-1] == pytest.approx(0.950, abs=2e-3)
    assert set(res.kinds) == {"rock"}
    np.testing.assert_allclose(res.omega_post[1:] / res.omega_post[:-1], -math.cos(math.pi / 4), rtol=1e-7)


def test_hybrid_four_spokes_stop_dead():
    res = hy.simulate_hybrid(RimlessWheel(4, 0.1), 2.0, 3)  # beta = kappa/(1+kappa) = 0
    assert res.outcome == "standing" and abs(res.omega_post[0]) < 1e-7


# --- validation ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"spokes": 2}, "spokes must be"),
        ({"slope": -0.1}, r"slope must be in \(0, pi/2\)"),
        ({"slope": math.pi / 2}, "slope must be"),
        ({"leg_length": 0.0}, "leg_length must be > 0"),
        ({"gyration": -0.1}, "gyration must be >= 0 and <= leg_length"),
        ({"gyration": 1.5}, "gyration must be"),
        ({"gravity": 0.0}, "gravity must be > 0"),
        ({"mass": -1.0}, "mass must be > 0"),
    ],
)
def test_validation(kwargs, message):
    params = {"spokes": 8, "slope": 0.1} | kwargs
    with pytest.raises(ValueError, match=message):
        rw.validate(RimlessWheel(**params))
    with pytest.raises(ValueError, match=message):
        hy.simulate_hybrid(RimlessWheel(**params), 1.0, 1)


def test_small_spoke_counts_are_valid():
    rw.validate(RimlessWheel(3, 0.1))
    assert RimlessWheel(4, 0.1, gyration=0.5).beta == pytest.approx(0.25 / 1.25)


def test_start_speeds_and_band_table() -> None:
    w = RimlessWheel(8, 0.08, gyration=0.01)
    star, omega_f = rw.rolling_fixed_point(w), rw.forward_threshold(w)
    fit = rw.fit_initial_speeds(w, 6)
    assert fit.shape == (6,) and np.all(np.diff(fit) > 0)
    assert omega_f < fit[0] < star < fit[-1] <= 1.15 * star
    assert all(rw.step_stays_in_contact(w, float(om)) for om in fit)
    bands = rw.basin_bands(w)
    assert len(bands) == 8 and bands[-1] == [omega_f, 1.3 * star, "rolling"]
    for low, high, label in bands:
        assert low < high
        assert rw.predicted_outcome(w, 0.5 * (float(low) + float(high))) == label
    probes = rw.basin_initial_speeds(w)
    assert probes.shape == (12,) and np.all(np.diff(probes) > 0)
    assert {rw.predicted_outcome(w, float(om)) for om in probes} == {"rolling", "standing"}
    edges = rw.basin_edges(w)
    omega1, omega2 = rw.basin_band_edges(w, 8)
    assert edges.size == 2 + omega1.size + omega2.size and edges[0] == omega_f and edges[1] == 0.0
    assert min(abs(om - e) for om in probes for e in edges) > 0.0


# --- 003 figure runs from mid-swing states, Fig. 14's curve, the gamma > alpha branch run in MuJoCo ----------------
FIGURE_RUNS = [  # derivation page Sec. 1.8: (gamma, theta(0), theta_dot(0), theta_dot_0 .. theta_dot_5)
    (0.025, -0.132, 2.0, [1.660746, 1.251689, 0.985418, -0.696796, 0.492709, -0.348398]),
    (math.pi / 7, 0.292, 5.0, [3.918914, 3.307060, 2.953986, 2.760566, 2.658584, 2.606097]),
    (math.pi / 15, -0.105, -5.0, [-3.551090, -2.178088, -0.900545, 0.636781, 1.328081, 1.562994]),
    (math.pi / 15, -0.105, -4.85, [-3.445503, -2.091577, -0.791387, 0.559595, -0.395694, 0.279798]),
]


@pytest.mark.parametrize(("gamma", "theta", "omega", "seq"), FIGURE_RUNS)
def test_figure_sequence_from_mid_swing_state(gamma, theta, omega, seq):
    from mjpoincare.analysis.theory.rimless_wheel.figures import figure_sequence

    np.testing.assert_allclose(figure_sequence(RimlessWheel(8, gamma), theta, omega, 6), seq, atol=6e-6)


def _first_impact_by_ode(w: RimlessWheel, theta: float, omega: float) -> float:
    """theta'' = (g/l) sin theta from (theta, omega) until a spoke lands (theta = gamma +- alpha), times beta."""
    from scipy.integrate import solve_ivp

    def lands(_t, y, edge):
        return y[0] - edge

    events = []
    for edge in (w.slope + w.alpha, w.slope - w.alpha):
        ev = lambda t, y, e=edge: lands(t, y, e)  # noqa: E731
        ev.terminal = True
        events.append(ev)
    sol = solve_ivp(lambda _t, y: [y[1], w.rate2 * math.sin(y[0])], (0.0, 20.0), [theta, omega], events=events,
                    rtol=1e-12, atol=1e-12)
    hit = next(e for e in sol.y_events if e.size)
    return w.beta * float(hit[0, 1])


@pytest.mark.parametrize(("gamma", "theta", "omega"), [(g, t, o) for g, t, o, _ in FIGURE_RUNS]
                         + [(0.025, -0.132, 0.3), (0.025, 0.2, -0.4), (math.pi / 15, 0.3, 0.5)])
def test_first_post_impact_speed_against_ode(gamma, theta, omega):
    from mjpoincare.analysis.theory.rimless_wheel.figures import first_post_impact_speed

    w = RimlessWheel(8, gamma, gyration=0.01)
    assert first_post_impact_speed(w, theta, omega) == pytest.approx(_first_impact_by_ode(w, theta, omega), abs=1e-9)


def test_existence_bound_curve_matches_spoke_counts():
    from mjpoincare.analysis.theory.rimless_wheel.figures import existence_bound_curve

    for n in (5, 6, 8, 12, 20):
        assert existence_bound_curve(math.pi / n) == pytest.approx(rw.existence_bound(n), rel=1e-12)
        assert existence_bound_curve(math.pi / n, 1e-4) == pytest.approx(rw.existence_bound(n, 0.01), rel=1e-12)
    with pytest.raises(ValueError, match="alpha"):
        existence_bound_curve(1.0)


def test_steep_branch_at_twelve_spokes():
    # the gamma > alpha starts of the paper result 003-wheel-steep-branch: between omega_b and -sqrt(K) the wheel
    # completes a backward step (corrected map), where (3.14) as printed has it rock back (-beta omega > 0)
    w = RimlessWheel(12, math.pi / 6, gyration=0.01)
    omega_b = -math.sqrt(2.0 * w.rate2 * (1.0 - math.cos(w.slope + w.alpha)))
    for f in (0.25, 0.5, 0.75):
        om = -math.sqrt(w.K + f * (omega_b**2 - w.K))
        assert omega_b < om < rw.backward_threshold(w)
        assert rw.return_map(w, om) == pytest.approx(hy.hybrid_return_map(w, om), abs=1e-9)
        assert rw.return_map(w, om) < 0 < -w.beta * om
        assert rw.flight_free(w, om, 1)
