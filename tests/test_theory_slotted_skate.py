"""Slotted-skate theory (000, Coleman & Holmes 1999) against an independent rigid-body reference
(stance ODE + Cartesian impulse at the new peg, ``simulate_exact``), impulse algebra done here from momentum
balance, and the numbers of the derivation page (docs/theory/slotted-skate.md, Sec. 3)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from mjpoincare.analysis.theory import slotted_skate as ss
from mjpoincare.analysis.theory.slotted_skate import SlottedSkate

R1000 = math.sqrt(1000.0)
#: Derivation page Sec. 3.1 parameter sets.
P = {
    "P1": SlottedSkate(1.0, 1.0 / 3.0),
    "P2": SlottedSkate(-1.0, 1.0 / 3.0),
    "P3": SlottedSkate(-2.0 / 3.0 * math.sqrt(12.5), math.sqrt(12.5)),  # L0/Delta = -2/3, 1/Delta^2 = 0.08
    "P4": SlottedSkate(-math.sqrt(2.0), math.sqrt(2.0) / 2.0),
    "P5": SlottedSkate(-0.55 * R1000, R1000),  # L0/Delta = -0.55, 1/Delta^2 = 0.001
    "P6": SlottedSkate(-0.5, 1.0),
    "P7": SlottedSkate(1.0, 0.01),
}
#: Derivation page Sec. 3.1: sigma4 for V* > 0 and V* < 0 (exact fractions where the page gives them).
SIGMA4 = {
    "P1": (21 / 25, 7 / 6),
    "P2": (15 / 13, 5 / 6),
    "P3": (-32 / 43, -16 / 59),
    "P4": (4 / 3, 2 / 3),
    "P5": (-493 / 407, -493 / 607),
    "P6": (3 / 5, 3 / 5),
    "P7": (0.995000247512, 1.005),
}
STAB = {
    "P1": ("stable", "unstable"),
    "P2": ("unstable", "stable"),
    "P3": ("stable", "stable"),
    "P4": ("unstable", "stable"),
    "P5": ("unstable", "stable"),
    "P6": ("stable", "stable"),
    "P7": ("stable", "unstable"),
}
#: Derivation page Sec. 3.1, last column: d theta+/d H at |V*| = 1.
DTHETA_DH = {
    "P1": 0.1418971,
    "P2": 0.1973956,
    "P3": 2.0367066,
    "P4": 0.3398369,
    "P5": 3.0140024,
    "P6": 0.9272952,
    "P7": 0.0049751,
}
#: Derivation page Sec. 3.3 (V0 = 1, theta0 = 0): Omega0, E1, H1, theta1, tau1, reversals, V_f, theta_f.
TRAJ = {
    "P1": (0.1, 0.509856, 0.168, 0.02833952298, 0.3328393669, 0, 1.009466066, 0.1762614878),
    "P2": (0.1, 0.509467455621, 0.230769230769, 0.03955633471, 0.3339502421, 1, -0.8868760894, 4.687297688),
    "P3": (0.1, 0.460982212607, -0.487855297158, 1.541553706, 3.941237804, 0, 0.8624020952, 0.8840292792),
    "P4": (0.1, 0.511666666667, 0.4, 0.1027274417, 0.7118606856, 1, -0.8830719016, 4.17805409),
    "P5": (0.001, 0.500148085625, -0.36763022113, 0.9377701313, 31.7620308, 1, -0.9999390929, 2.515249109),
    "P6": (0.1, 0.50225, 0.075, 0.1160310809, 1.000996327, 0, 1.0, 0.2899317267),
}


def cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


# --------------------------------------------------------------------------------------------- parameters


@pytest.mark.parametrize(
    ("L0", "Delta", "msg"),
    [
        (0.0, 0.0, r"Delta must be > 0 \(got 0.0\)"),
        (0.0, -1.0, r"Delta must be > 0 \(got -1.0\)"),
        (0.0, math.nan, r"Delta must be > 0 \(got nan\)"),
        (math.inf, 1.0, r"L0 must be finite \(got inf\)"),
    ],
)
def test_validate_messages(L0: float, Delta: float, msg: str) -> None:
    with pytest.raises(ValueError, match=msg):
        ss.validate(SlottedSkate(L0, Delta))
    with pytest.raises(ValueError, match=msg):
        ss.sigma4(SlottedSkate(L0, Delta), True)


def test_validate_accepts_any_finite_L0() -> None:
    """L0 is signed (000 Sec. 3): a skate with any finite L0 passes the check and has a map, in both
    directions."""
    for l0 in (-50.0, -1.0, 0.0, 2.5):
        sk = SlottedSkate(l0, 0.7)
        ss.validate(sk)
        assert all(0 < ss.sigma4(sk, forward) < math.inf for forward in (True, False)), l0


def test_section_and_feasibility_errors() -> None:
    sk = P["P1"]
    with pytest.raises(ValueError, match="D must be 0 or Delta"):
        ss.return_map(sk, 0.1, 0.5, 0.0, 0.1)
    with pytest.raises(ValueError, match="direction must be"):
        ss.return_map(sk, 0.0, 0.5, 0.0, 0.1, direction=-1)
    with pytest.raises(ValueError, match="infeasible"):
        ss.stance(sk, 0.0, 0.5, 2.0)  # 2E/H^2 = 0.25 < 1/(1 + L0^2) = 0.5 (3.15)
    with pytest.raises(ValueError, match="V0 must be"):
        ss.iterate(sk, 0.0, 0.1, 0.0, 1)


# --------------------------------------------------------------------------------------------- impact law


@pytest.mark.parametrize("name", ["P1", "P3", "P5"])
@pytest.mark.parametrize("old_rear", [True, False])
def test_impact_law_against_cartesian_impulse(name: str, old_rear: bool) -> None:
    """Solve the plastic impulse at the new peg from m dv = Pi e_n, I dw = (P' - G) x Pi e_n and a zero normal
    velocity of the body point at P' (3x3 linear system, m = I = 1); compare (3.6), (3.7) and the H jump."""
    sk = P[name]
    th, V, om = 0.37, -0.8 if not old_rear else 0.9, 0.23
    l_old, l_new = (sk.L_rear, sk.L_front) if old_rear else (sk.L_front, sk.L_rear)
    el, en = np.array([math.cos(th), math.sin(th)]), np.array([-math.sin(th), math.cos(th)])
    old_peg = np.array([0.3, -1.1])
    g = old_peg + l_old * el
    vg = V * el + l_old * om * en
    new_peg = g - l_new * el
    arm = new_peg - g
    # unknowns (vx, vy, w): vx - Pi enx = vgx, vy - Pi eny = vgy, w - arm x en Pi = om, and en.(v + w z x arm) = 0
    zxa = np.array([-arm[1], arm[0]])
    a = np.array(
        [
            [1.0, 0.0, 0.0, -en[0]],
            [0.0, 1.0, 0.0, -en[1]],
            [0.0, 0.0, 1.0, -cross(arm, en)],
            [en[0], en[1], float(en @ zxa), 0.0],
        ]
    )
    sol = np.linalg.solve(a, np.array([vg[0], vg[1], om, 0.0]))
    vp, wp = sol[:2], sol[2]
    e_minus = 0.5 * float(vg @ vg) + 0.5 * om**2
    e_plus = 0.5 * float(vp @ vp) + 0.5 * wp**2
    h_old = om + cross(g - old_peg, vg)
    h_plus = wp + cross(g - new_peg, vp)
    assert float(vp @ el) == pytest.approx(V, abs=1e-14)  # no impulse along the slot
    assert wp / om == pytest.approx(ss.impact_ratio(sk, l_new), rel=1e-13)
    assert e_plus - e_minus == pytest.approx(ss.energy_loss(sk, h_old, l_old, l_new), rel=1e-10, abs=1e-15)
    assert e_plus - e_minus == pytest.approx(-0.5 * sk.Delta**2 * om**2 / (1 + l_new**2), rel=1e-10)
    _, c2 = ss.impact_coefficients(sk, l_old, l_new)
    assert h_plus == pytest.approx(c2 * h_old, rel=1e-13)
    assert ss.stance_invariants(sk, l_old - sk.L0, V, om) == pytest.approx((e_minus, h_old), rel=1e-14)
    with pytest.raises(ValueError, match="two slot ends"):
        ss.energy_loss(sk, 1.0, l_old, l_old)


# --------------------------------------------------------------------------------------------- map vs exact


CASES = [
    ("P1", 1.0, 0.1, 8),
    ("P1", -1.0, 0.1, 14),  # backward, unstable: reversal in the 12th stance (B.6: n = 11)
    ("P2", 1.0, 0.1, 16),  # reversal in the 14th stance
    ("P2", -1.0, 0.3, 6),
    ("P3", 1.0, 0.1, 6),  # wobble
    ("P3", -1.0, 0.1, 6),
    ("P4", 1.0, 0.1, 9),  # reversal in the 6th stance
    ("P5", 1.0, 0.001, 10),  # wobble growth, reversal in the 8th stance
    ("P6", 0.35, 0.8, 6),  # Fig. 3: one reversal
    ("P6", 0.2, 0.8, 6),  # two reversals
    ("P7", 1.0, 0.1, 5),
]


@pytest.mark.parametrize(("name", "V0", "Om0", "n"), CASES)
def test_return_map_matches_exact_reference(name: str, V0: float, Om0: float, n: int) -> None:
    sk = P[name]
    a = ss.iterate(sk, V0, Om0, 0.2, n)
    b = ss.simulate_exact(sk, V0, Om0, 0.2, n)
    assert [s.reversed for s in a] == [s.reversed for s in b]
    assert [s.D_plus for s in a] == [s.D_plus for s in b]
    scale = max(1.0, max(abs(s.theta_plus) for s in a))
    for x, y in zip(a, b, strict=True):
        assert x.E_plus == pytest.approx(y.E_plus, abs=1e-9)
        assert x.H_plus == pytest.approx(y.H_plus, abs=1e-9)
        assert x.theta_plus == pytest.approx(y.theta_plus, abs=1e-9 * scale)
        assert x.duration == pytest.approx(y.duration, rel=1e-9)
    if (name in ("P1", "P2", "P4", "P5") and n > 8) or name == "P6":
        assert any(s.reversed for s in a)


def test_stance_closed_forms_against_exact() -> None:
    """B.1: end speed and angular rate of one reversing and one non-reversing stance."""
    sk = P["P6"]
    e, h = ss.stance_invariants(sk, 0.0, 0.35, 0.8)
    st = ss.stance(sk, 0.0, e, h)
    ref = ss.simulate_exact(sk, 0.35, 0.8, 0.0, 1)[0]
    assert st.reversed and ref.reversed and st.D_end == 0.0
    assert st.V_end == pytest.approx(-0.35, rel=1e-12)
    assert st.Omega_end == pytest.approx(0.8, rel=1e-12)
    assert st.duration == pytest.approx(ref.duration, rel=1e-10)
    st2 = ss.stance(sk, 0.0, *ss.stance_invariants(sk, 0.0, 0.6, 0.8))
    assert not st2.reversed and st2.D_end == sk.Delta
    assert st2.Omega_end == pytest.approx(0.8 * 1.25 / 1.25, rel=1e-12)  # L = +-1/2 at both ends
    lc = math.sqrt(h * h / (2 * e) - 1)
    assert ss.turning_points(sk, e, h) == pytest.approx((0.5 - lc, 0.5 + lc), rel=1e-14)  # both roots in the slot
    ref2 = ss.simulate_exact(sk, 0.6, 0.8, 0.0, 1)[0]
    assert st2.V_end == pytest.approx(ref2.velocities(sk)[0], rel=1e-11)  # V is continuous through the impact
    assert st2.dtheta == pytest.approx(ref2.theta_plus, rel=1e-11)


# --------------------------------------------------------------------------------------------- sigma4 and C1


@pytest.mark.parametrize("name", list(P))
@pytest.mark.parametrize("forward", [True, False])
def test_sigma4_and_C1_from_exact_reference(name: str, forward: bool) -> None:
    """H_{k+1}/H_k of the exact reference = (3.10) = the page's fractions, at finite amplitude;
    E_{k+1} - E_k = C1 H_k^2."""
    sk = P[name]
    s4 = ss.sigma4(sk, forward)
    assert s4 == pytest.approx(SIGMA4[name][0 if forward else 1], rel=1e-11)
    v0 = 1.0 if forward else -1.0
    om0 = 1e-3 if name == "P5" else 0.02
    q0 = ss.initial_state(sk, v0, om0, 0.0)
    steps = [q0, *ss.simulate_exact(sk, v0, om0, 0.0, 3)]
    assert not any(s.reversed for s in steps)
    c1 = ss.C1(sk, forward)
    for a, b in itertools.pairwise(steps):
        assert b.H_plus / a.H_plus == pytest.approx(s4, rel=1e-9)
        assert b.E_plus - a.E_plus == pytest.approx(c1 * a.H_plus**2, rel=1e-7, abs=1e-14)


@pytest.mark.parametrize("name", list(P))
def test_dtheta_dH_by_finite_differences(name: str) -> None:
    sk = P[name]
    h = 1e-5
    for v0 in (1.0, -1.0):
        la = sk.L_front if v0 > 0 else sk.L_rear
        th = []
        for sgn in (1.0, -1.0):
            om = sgn * h / (1 + la * la)
            vv = math.copysign(math.sqrt(1.0 - h * h / (1 + la * la)), v0)  # E = 1/2
            th.append(ss.simulate_exact(sk, vv, om, 0.0, 1)[0].theta_plus)
        fd = (th[0] - th[1]) / (2 * h)
        assert fd == pytest.approx(ss.dtheta_dH(sk, 1.0), rel=1e-6)
        assert ss.dtheta_dH(sk, 1.0) == pytest.approx(DTHETA_DH[name], abs=6e-8)


# --------------------------------------------------------------------------------------------- stability


@pytest.mark.parametrize("name", list(P))
def test_stability_classification(name: str) -> None:
    st = ss.stability(P[name])
    assert (st["forward"], st["backward"]) == STAB[name]
    assert st["wobble_forward"] == (name in ("P3", "P5"))
    assert st["coexistence"] == (name in ("P3", "P6"))


def test_stability_criteria_match_sigma4_on_grid() -> None:
    """(3.11)/(3.12) (exact reading) against |sigma4| < 1 over a grid, incl. slots longer than 4 rho."""
    for delta in (0.3, 1.0, 3.9, 5.0, 12.0, 40.0):
        for x in np.linspace(-2.0, 1.0, 301):
            sk = SlottedSkate(float(x) * delta + 1e-9, delta)
            st = ss.stability(sk)
            for key, fwd in (("forward", True), ("backward", False)):
                assert (st[key] == "stable") == (abs(ss.sigma4(sk, fwd)) < 1.0), (delta, x, key)


def test_long_slot_unstable_bands() -> None:
    """Derivation page Sec. 2: for Delta > 4 the forward motion is unstable for x in ((-3-s)/4, (-3+s)/4) and the
    backward one for x in ((-1-s)/4, (-1+s)/4), s = sqrt(1 - 16/Delta^2)."""
    delta = 10.0
    s = math.sqrt(1 - 16 / delta**2)
    for x, fwd_stable in [((-3 - s) / 4 - 1e-3, True), (-0.75, False), ((-3 + s) / 4 + 1e-3, True)]:
        assert (ss.stability(SlottedSkate(x * delta, delta))["forward"] == "stable") == fwd_stable
    for x, bwd_stable in [((-1 - s) / 4 - 1e-3, True), (-0.25, False), ((-1 + s) / 4 + 1e-3, True)]:
        assert (ss.stability(SlottedSkate(x * delta, delta))["backward"] == "stable") == bwd_stable
    assert ss.stability(SlottedSkate(-1.0, 1.0))["forward"] == "neutral"
    assert ss.stability(SlottedSkate(0.0, 1.0))["backward"] == "neutral"


# --------------------------------------------------------------------------------------------- the page's oracles


@pytest.mark.parametrize("name", list(TRAJ))
def test_trajectory_oracles(name: str) -> None:
    om0, e1, h1, th1, tau1, nrev, vf, thf = TRAJ[name]
    sk = P[name]
    s1 = ss.iterate(sk, 1.0, om0, 0.0, 1)[0]
    assert s1.E_plus == pytest.approx(e1, abs=2e-12)
    assert s1.H_plus == pytest.approx(h1, abs=2e-12)
    assert s1.theta_plus == pytest.approx(th1, abs=2e-9)
    assert s1.duration == pytest.approx(tau1, abs=2e-8)
    fin = ss.final_state(sk, 1.0, om0, 0.0)
    assert fin.reversals == nrev
    assert fin.V_f == pytest.approx(vf, abs=2e-9)
    assert fin.theta_f == pytest.approx(thf, abs=2e-8)


def test_final_energy_b10_b12() -> None:
    """Derivation page Sec. 3.3 E_f (B.10) and V_f (B.12), both directions; B.12 mirrored form against B.10."""
    for name, ef in (("P1", 0.509510869565), ("P3", 0.371868686869), ("P7", 0.509975432396)):
        sk = P[name]
        q = ss.initial_state(sk, 1.0, 0.1)
        assert ss.final_energy(sk, q.E_plus, q.H_plus, True) == pytest.approx(ef, abs=1e-12)
    assert ss.final_speed_b12(P["P1"], 1.0, 0.1) == pytest.approx(1.009466066359, abs=1e-12)
    assert ss.final_speed_b12(P["P3"], 1.0, 0.1) == pytest.approx(0.862402095161, abs=1e-12)
    for name in ("P2", "P3", "P4", "P6"):  # V < 0 stable
        sk = P[name]
        q = ss.initial_state(sk, -0.9, 0.07)
        vf = -math.sqrt(2 * ss.final_energy(sk, q.E_plus, q.H_plus, False))
        assert ss.final_speed_b12(sk, -0.9, 0.07) == pytest.approx(vf, rel=1e-13)
        assert ss.final_state(sk, -0.9, 0.07).V_f == pytest.approx(vf, rel=1e-12)


def test_symmetric_basins_b13() -> None:
    """Derivation page Sec. 3.4: P6, H = 1 (Omega0 = 0.8): spin boundaries V_n = 0.6^n/sqrt(5); V0 in
    (V_{k+1}, V_k) reverses k + 1 times and |V_f| = V0 (B.12)."""
    sk = P["P6"]
    c1, c2 = ss.C1(sk, True), ss.sigma4(sk, True)
    cp = 1 + sk.Delta**2 / 4
    for n in range(4):
        vn = 0.6**n / math.sqrt(5)
        b13 = math.sqrt(cp**2 * (c2 ** (2 * n) - 2 * c1 * (1 - c2 ** (2 * n)) / (1 - c2**2)) - cp) * 0.8
        assert b13 == pytest.approx(vn, rel=1e-12)
        for f, k in ((1.001, n), (0.999, n + 1)):
            fin = ss.final_state(sk, vn * f, 0.8)
            assert fin.reversals == k
            assert fin.V_f == pytest.approx((-1) ** k * vn * f, rel=1e-12)


def test_collisions_before_reversal_b6() -> None:
    sk = P["P1"]
    for (v0, om0), n in zip([(-1, 0.1), (-1, 0.3), (-0.5, 0.4), (-2, 0.2)], [11, 5, 1, 11], strict=True):
        q = ss.initial_state(sk, v0, om0)
        assert ss.collisions_before_reversal(sk, q.D_plus, q.E_plus, q.H_plus) == n
        flags = [s.reversed for s in ss.iterate(sk, v0, om0, 0.0, n + 1)]
        assert flags == [False] * n + [True]


def test_two_turning_points_needs_max_not_min() -> None:
    """(B.8) prints min; L0 = -0.3, Delta = 1, r = 0.8 lies in the printed range but has one root in the slot."""
    sk = SlottedSkate(-0.3, 1.0)
    r = 0.8
    assert min(1 / (1 + 0.09), 1 / (1 + 0.49)) < r < 1
    assert len(ss.turning_points(sk, 0.5 * r, 1.0)) == 1
    assert len(ss.turning_points(sk, 0.5 * 0.95, 1.0)) == 2  # r > max{...}


def test_smooth_limit() -> None:
    """(4.1): exact (1/Delta) ln sigma4 at L0 = 1 (derivation page Sec. 3.4), corrected series O(Delta^3), printed
    O(Delta^2)."""
    exact = {0.1: -0.5105517080, 0.05: -0.5057463943, 0.01: -0.5012293067}
    for dl, val in exact.items():
        sk = SlottedSkate(1.0, dl)
        assert ss.smooth_limit_rate(sk) == pytest.approx(val, abs=1e-10)
        assert abs(ss.smooth_limit_series(sk, order=3) - val) < 2 * dl**3
        printed = -0.5 + 0.5 * (1 - 2) / 4 * dl - (1 - 2) / (3 * 8) * dl**2  # paper's (L0^2 - 2) in the last term
        assert abs(printed - val) > 0.1 * dl**2
    assert ss.sleigh_rate(1.0) == -0.5
    # (1/Delta) ln sigma4 for other L0 tends to the sleigh value; series to 4 terms is O(Delta^4)
    for l0 in (-2.0, -0.4, 0.3, 3.0):
        sk = SlottedSkate(l0, 1e-3)
        assert ss.smooth_limit_rate(sk) == pytest.approx(ss.sleigh_rate(l0), abs=2e-3)
        assert ss.smooth_limit_series(sk, order=4) == pytest.approx(ss.smooth_limit_rate(sk), abs=1e-11)
    with pytest.raises(ValueError, match="sigma4 must be > 0"):
        ss.smooth_limit_rate(P["P3"])


# ------------------------------------------------------------- figures.py: Fig 2(b) bands, Fig 3, (3.8), (B.8), Fig 10


def test_band_edges_against_exact_reference() -> None:
    """Fig. 2(b): sigma4 = -1 at band_edge_delta and at the ends of unstable_band; just past the edge the solve_ivp
    reference's H ratio leaves the unit circle, just before it stays inside."""
    from mjpoincare.analysis.theory.slotted_skate.figures import band_edge_delta, unstable_band

    assert band_edge_delta(-0.75, True) == pytest.approx(4.0, rel=1e-14)
    assert band_edge_delta(-0.25, False) == pytest.approx(4.0, rel=1e-14)
    for x, fwd in ((-0.75, True), (-0.6, True), (-0.9, True), (-0.25, False), (-0.4, False)):
        edge = band_edge_delta(x, fwd)
        assert ss.sigma4(SlottedSkate(x * edge, edge), fwd) == pytest.approx(-1.0, abs=1e-12)
        for factor, outside in ((0.99, False), (1.01, True)):
            d = edge * factor
            steps = ss.simulate_exact(SlottedSkate(x * d, d), 1.0 if fwd else -1.0, 1e-4, 0.0, 2)
            assert (abs(steps[1].H_plus / steps[0].H_plus) > 1.0) == outside, (x, fwd, factor)
    for fwd in (True, False):
        lo, hi = unstable_band(10.0, fwd)
        for x in (lo, hi):
            assert ss.sigma4(SlottedSkate(x * 10.0, 10.0), fwd) == pytest.approx(-1.0, abs=1e-12)
        assert unstable_band(4.0, fwd) is None
    with pytest.raises(ValueError, match="no unstable band"):
        band_edge_delta(-0.25, True)


def test_symmetric_basins_against_exact_reference() -> None:
    """Fig. 3 (B.13): V_n = 0.6^n/sqrt 5 at L0 = -1/2, Delta = 1, Omega0 = 0.8 (the caption's 1/sqrt 5 is V_0); in
    each interval the solve_ivp reference ends in symmetric_final_speed's direction, with |V_f| = V0 (B.12)."""
    from mjpoincare.analysis.theory.slotted_skate.figures import spin_boundary_speeds, symmetric_final_speed

    sk = P["P6"]
    speeds = spin_boundary_speeds(sk, 0.8, 6)
    assert speeds == pytest.approx([0.6**n / math.sqrt(5.0) for n in range(6)], rel=1e-12)
    for v0 in (0.6, *(v * math.sqrt(0.6) for v in speeds[:4])):
        vf = symmetric_final_speed(sk, v0, 0.8)
        last = ss.simulate_exact(sk, v0, 0.8, 0.0, 45)[-1]
        v_exact = math.copysign(math.sqrt(2.0 * last.E_plus), 1.0 if last.D_plus == 0.0 else -1.0)
        assert v_exact == pytest.approx(vf, rel=1e-6), v0
    with pytest.raises(ValueError, match="symmetric"):
        spin_boundary_speeds(P["P1"], 0.8, 2)
    with pytest.raises(ValueError, match="V0 must be"):
        symmetric_final_speed(sk, 0.0, 0.8)


def test_two_turning_points_against_stance_ode() -> None:
    """(B.8) read with max: for r in two_turning_point_range both directions turn (the stance ODE 3.1 by solve_ivp
    stops at V = 0 inside the slot), at -+sqrt(1/r - 1); in (min, max) only the backward start is feasible (3.15)."""
    from mjpoincare.analysis.theory.slotted_skate.figures import two_turning_point_range
    from scipy.integrate import solve_ivp

    sk = SlottedSkate(-0.3, 1.0)
    low, high = two_turning_point_range(sk)
    assert (low, high) == (pytest.approx(1.0 / 1.09), 1.0)
    assert two_turning_point_range(P["P1"]) == (1.0, 1.0)

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        L = sk.L0 + y[0]
        return [y[1], L * y[3] ** 2, y[3], -2.0 * L * y[1] * y[3] / (1.0 + L * L)]

    def turn(_t: float, y: np.ndarray) -> float:
        return float(y[1])

    turn.terminal = True  # type: ignore[attr-defined]
    H = 0.5
    for r in (0.8, 0.95, 0.99, 1.02):
        for d0, sign in ((0.0, 1.0), (sk.Delta, -1.0)):
            la = sk.L0 + d0
            v2 = r * H * H - H * H / (1.0 + la * la)
            if v2 <= 0.0:
                assert r < low and sign > 0  # the forward start is infeasible below the max (3.15)
                continue
            sol = solve_ivp(rhs, (0.0, 50.0), [d0, sign * math.sqrt(v2), 0.0, H / (1.0 + la * la)],
                            method="DOP853", rtol=1e-12, atol=1e-14, events=turn)
            d_turn = sol.y_events[0][0][0] if sol.t_events[0].size else math.nan
            inside = 0.0 < d_turn < sk.Delta
            assert inside == (r < 1.0), (r, d0)
            if inside:
                assert sk.L0 + d_turn == pytest.approx(-sign * math.sqrt(1.0 / r - 1.0), abs=1e-9)
                assert (r > low) or sign < 0


def test_spin_saddle_against_stance_ode() -> None:
    """(3.8) and Sec. 3.1.2: the spinning equilibrium's eigenvalues 0, 0, -+Omega_eq; a peg 1e-7 off the mass centre
    (solve_ivp of 3.1) moves away as cosh(Omega_eq tau)."""
    from mjpoincare.analysis.theory.slotted_skate.figures import spin_saddle_eigenvalues
    from scipy.integrate import solve_ivp

    assert spin_saddle_eigenvalues(1.5) == pytest.approx([-1.5, 0.0, 0.0, 1.5], abs=1e-14)
    sk, om, eps = P["P6"], 1.5, 1e-7

    def rhs(_t: float, y: np.ndarray) -> list[float]:
        L = sk.L0 + y[0]
        return [y[1], L * y[3] ** 2, y[3], -2.0 * L * y[1] * y[3] / (1.0 + L * L)]

    t = 6.0
    sol = solve_ivp(rhs, (0.0, t), [-sk.L0 + eps, 0.0, 0.0, om / (1.0 + eps * eps)], method="DOP853", rtol=1e-12,
                    atol=1e-16)
    assert math.acosh((sol.y[0, -1] + sk.L0) / eps) / t == pytest.approx(om, rel=1e-6)


def test_period2_flip_flop_against_exact_reference() -> None:
    """Fig. 10 (B.15-B.16): at l0/delta = -2/3 the solve_ivp reference reverses every stance and H returns after two
    impacts multiplied by period2_multiplier, which tends to 1 as rho/delta -> 0, each impact's C2 to L0/(L0 + 1)."""
    from mjpoincare.analysis.theory.slotted_skate.figures import period2_multiplier, period2_rho0_ratios

    x = -2.0 / 3.0
    for rho in (0.05, 0.01):
        sk = SlottedSkate(x / rho, 1.0 / rho)
        steps = ss.simulate_exact(sk, 1.0, 0.5 * rho, 0.0, 6)
        assert all(s.reversed for s in steps)
        for a, b in itertools.pairwise(steps[::2]):
            assert b.H_plus / a.H_plus == pytest.approx(period2_multiplier(sk), rel=1e-9)
    for rho in (1e-3, 1e-4):  # 1 - multiplier = rho^2 (1/x - 1/(1 + x))^2 + O(rho^4): neutral at rho = 0
        gap = 1.0 - period2_multiplier(SlottedSkate(x / rho, 1.0 / rho))
        assert gap == pytest.approx(rho**2 * (1.0 / x - 1.0 / (1.0 + x)) ** 2, rel=1e-4)
    ratios = period2_rho0_ratios(x)
    assert ratios == pytest.approx((-2.0, -0.5), rel=1e-14)
    sk = SlottedSkate(x / 1e-4, 1e4)
    assert sk.c / (1.0 + sk.L_front**2) == pytest.approx(ratios[1], rel=1e-6)
    assert sk.c / (1.0 + sk.L_rear**2) == pytest.approx(ratios[0], rel=1e-6)
