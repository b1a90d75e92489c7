"""Compass-gait theory (003 Kiša 2020 Ch. 4; Goswami et al. 1996/98) against independent point-mass mechanics
(Lagrangian by finite differences, angular momenta by cross products, Newton's law by differentiated momentum)
and against the numbers of the derivation page (docs/theory/rimless-wheel-and-compass-gait.md, Sec. 2.6)."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np
import pytest
from mjpoincare.analysis.theory import compass_biped as cb
from mjpoincare.analysis.theory.compass_biped import CompassBiped, flight
from scipy.integrate import solve_ivp

KISA_X = np.array([-0.2073985186, 0.2873985186, 1.0406442919, 0.4810330477])
KISA_T = 0.72404762
KISA_EIG = np.array([0.013832 + 0.589692j, 0.013832 - 0.589692j, 0.150606])
#: 003 App. A: the thesis' own gait (grid search + forward simulation, first-order event location).
THESIS_X = np.array([-0.20741034501258232, 0.287418992418885, 1.0409143102934366, 0.480818114159959])
GOSWAMI_X = np.array([-0.2186688, 0.3233886, 1.0923836, 0.3773739])
GOSWAMI_T = 0.734346
GOSWAMI_EIG = np.array([-0.199726 + 0.544476j, -0.199726 - 0.544476j, 0.131573])
RNG = np.random.default_rng(3)


def u(th: float) -> np.ndarray:
    return np.array([math.sin(th), math.cos(th)])


def du(th: float) -> np.ndarray:
    return np.array([math.cos(th), -math.sin(th)])


def cross(p: np.ndarray, v: np.ndarray) -> float:
    return float(p[0] * v[1] - p[1] * v[0])


def points(bp: CompassBiped, x: np.ndarray) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(mass, position, velocity) of stance-leg mass, hip, swing-leg mass; origin at the stance foot."""
    th1, th2, w1, w2 = x
    hip, v_hip = bp.l * u(th1), bp.l * w1 * du(th1)
    return [
        (bp.m_l, bp.a * u(th1), bp.a * w1 * du(th1)),
        (bp.m_h, hip, v_hip),
        (bp.m_l, hip - bp.b * u(th2), v_hip - bp.b * w2 * du(th2)),
    ]


def kinetic(bp: CompassBiped, x: np.ndarray) -> float:
    return sum(0.5 * m * float(v @ v) for m, _, v in points(bp, x))


def potential(bp: CompassBiped, q: np.ndarray) -> float:
    return sum(m * bp.gravity * p[1] for m, p, _ in points(bp, np.array([*q, 0.0, 0.0])))


def grad(f, z: np.ndarray, h: float = 1e-6) -> np.ndarray:
    out = np.empty(z.size)
    for k in range(z.size):
        dz = np.zeros(z.size)
        dz[k] = h
        out[k] = (f(z + dz) - f(z - dz)) / (2 * h)
    return out


def random_state() -> np.ndarray:
    return np.array([*RNG.uniform(-0.6, 0.6, 2), *RNG.uniform(-2.0, 2.0, 2)])


# --- validate -----------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("m_h", -1, "m_h must be > 0 kg (got -1)"),
        ("m_l", 0.0, "m_l must be > 0 kg"),
        ("a", 0.0, "a must be > 0 m"),
        ("b", -0.5, "b must be > 0 m"),
        ("slope", 0.0, "slope must be in (0, pi/2) rad"),
        ("slope", 2.0, "slope must be in (0, pi/2) rad"),
        ("gravity", 0.0, "gravity must be > 0"),
    ],
)
def test_validate_messages(field, value, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        cb.validate(CompassBiped(**{field: value}))
    with pytest.raises(ValueError, match=re.escape(message)):
        cb.step(CompassBiped(**{field: value}), KISA_X)
    cb.validate(cb.kisa())


# --- equations of motion (003 eq 4.5) -------------------------------------------------------------------------
@pytest.mark.parametrize("bp", [cb.kisa(), CompassBiped(m_h=3.0, m_l=2.0, a=0.3, b=0.8, slope=0.1, gravity=9.0)])
def test_eom_equals_lagrangian_of_point_masses(bp):
    for _ in range(5):
        x = random_state()
        q, qd = x[:2], x[2:]
        mass = cb.mass_matrix(bp, q)
        assert np.allclose(mass, mass.T)
        assert np.all(np.linalg.eigvalsh(mass) > 0)

        def momentum(qq, vv):
            return grad(lambda w: kinetic(bp, np.concatenate([qq, w])), vv, 1e-3)  # exact: T quadratic in qd

        # T is quadratic in qd: M = Hessian of T in qd
        hess = np.vstack([grad(lambda w, k=k, q=q: momentum(q, w)[k], qd, 1e-3) for k in range(2)])
        assert mass == pytest.approx(hess, abs=1e-6)
        # C qd = (dp/dq) qd - dT/dq, G = -dU/dq
        dpdq = np.vstack([grad(lambda z, k=k, qd=qd: momentum(z, qd)[k], q, 1e-5) for k in range(2)])
        c_qd = dpdq @ qd - grad(lambda z, qd=qd: kinetic(bp, np.concatenate([z, qd])), q)
        assert cb.coriolis(bp, q, qd) @ qd == pytest.approx(c_qd, abs=1e-5)
        assert cb.gravity_vector(bp, q) == pytest.approx(-grad(lambda z: potential(bp, z), q), abs=1e-6)
        assert cb.energy(bp, q, qd) == pytest.approx(kinetic(bp, x) + potential(bp, q), rel=1e-12)


def test_constant_torques_power_and_gait():
    """With the model's constant torques dE/dt = tau_ankle dtheta_st + tau_hip (dtheta_sw - dtheta_st), and the
    gait continued from the passive one is a fixed point of the actuated map, shifted the way the ankle pushes."""
    from dataclasses import replace

    bp = replace(cb.kisa(), tau_ankle=0.5, tau_hip=0.2)
    x = random_state()
    qdd = cb.swing_dynamics(bp, x[:2], x[2:])
    rate = np.concatenate([x[2:], qdd])

    def energy_along(h: float) -> float:
        y = x + h * rate
        return kinetic(bp, y) + potential(bp, y[:2])

    d_energy = (energy_along(1e-6) - energy_along(-1e-6)) / 2e-6
    assert d_energy == pytest.approx(0.5 * x[2] + 0.2 * (x[3] - x[2]), abs=1e-6)
    x_star = cb.fixed_point(bp)
    assert cb.step(bp, x_star).x_plus_next == pytest.approx(x_star, abs=1e-9)
    passive = cb.fixed_point(cb.kisa())
    assert x_star[2] > passive[2]  # the ankle torque pushes the hip downhill: a faster stance leg


def test_hip_torque_power():
    """dE/dt = tau (dtheta_sw - dtheta_st): the hip torque's power, B = (-1, 1) (003 eq 4.4)."""
    bp = cb.kisa()
    for tau in (0.0, 2.5, -4.0):
        x = random_state()
        qdd = cb.swing_dynamics(bp, x[:2], x[2:], tau)
        assert cb.mass_matrix(bp, x[:2]) @ qdd + cb.coriolis(bp, x[:2], x[2:]) @ x[2:] == pytest.approx(
            cb.gravity_vector(bp, x[:2]) + tau * np.array([-1.0, 1.0])
        )
        rate = np.concatenate([x[2:], qdd])

        def energy_along(h, x=x, rate=rate):
            y = x + h * rate
            return kinetic(bp, y) + potential(bp, y[:2])

        d_energy = (energy_along(1e-6) - energy_along(-1e-6)) / 2e-6
        assert d_energy == pytest.approx(tau * (x[3] - x[2]), abs=1e-6)


def test_energy_conserved_in_passive_swing():
    bp = cb.goswami()

    def rhs(_t, y):
        return np.concatenate([y[2:], cb.swing_dynamics(bp, y[:2], y[2:])])

    sol = solve_ivp(rhs, (0.0, 0.7), KISA_X, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=np.linspace(0, 0.7, 30))
    energies = [kinetic(bp, y) + potential(bp, y[:2]) for y in sol.y.T]
    assert np.ptp(energies) < 1e-9 * abs(energies[0])


def test_swing_foot_height_is_normal_distance():
    bp = CompassBiped(slope=0.2)
    for _ in range(5):
        q = RNG.uniform(-0.6, 0.6, 2)
        foot = bp.l * (u(q[0]) - u(q[1]))
        assert cb.swing_foot_height(bp, q) == pytest.approx(float(foot @ u(bp.slope)), abs=1e-14)
        s, d = q.sum() - 2 * bp.slope, q[0] - q[1]
        assert cb.swing_foot_height(bp, q) == pytest.approx(-2 * bp.l * math.sin(s / 2) * math.sin(d / 2), abs=1e-14)


# --- impact (003 eqs 4.7, 4.15-4.18) ------------------------------------------------------------------------
@pytest.mark.parametrize("bp", [cb.kisa(), CompassBiped(m_h=3.0, m_l=2.0, a=0.3, b=0.8, slope=0.1)])
def test_impact_conserves_both_angular_momenta(bp):
    for _ in range(5):
        half = RNG.uniform(0.05, 0.5)
        x_minus = np.array([bp.slope + half, bp.slope - half, *RNG.uniform(-2.0, 2.0, 2)])
        x_plus = cb.impact_map(bp, x_minus)
        assert x_plus[:2] == pytest.approx(x_minus[1::-1], abs=0)
        pre = points(bp, x_minus)
        contact = pre[1][1] - bp.l * u(x_minus[1])
        assert float(contact @ u(bp.slope)) == pytest.approx(0.0, abs=1e-14)  # on the slope
        # post-impact point masses, origin at the new stance foot; the old stance mass is now the swing-leg mass
        post = points(bp, x_plus)
        new_stance, hip, new_swing = post
        for (m0, p0, _), (m1, p1, _) in zip(pre, [new_swing, hip, new_stance], strict=True):
            assert m0 == m1
            assert p0 == pytest.approx(p1 + contact, abs=1e-14)
        lc_pre = sum(cross(p - contact, m * v) for m, p, v in pre)
        lc_post = sum(cross(p, m * v) for m, p, v in post)
        assert lc_post == pytest.approx(lc_pre, abs=1e-12)
        trail_pre = cross(pre[0][1] - pre[1][1], bp.m_l * pre[0][2])
        trail_post = cross(new_swing[1] - hip[1], bp.m_l * new_swing[2])
        assert trail_post == pytest.approx(trail_pre, abs=1e-12)
        assert kinetic(bp, x_plus) < kinetic(bp, x_minus)


def test_massless_legs_give_rimless_wheel_impact():
    """m_l -> 0: dtheta_st+ = cos(2 alpha) dtheta_st- (003 eq 3.11, remark after eq 4.17)."""
    bp = CompassBiped(m_l=1e-10)
    for half in (0.1, 0.3, 0.7):
        x_minus = np.array([bp.slope + half, bp.slope - half, 1.3, -0.4])
        assert cb.impact_map(bp, x_minus)[2] == pytest.approx(math.cos(2 * half) * 1.3, rel=1e-8)


# --- passive gait (003 Fig. 18, Sec. 4.4; Goswami et al.) -------------------------------------------------------
@pytest.fixture(scope="module")
def kisa_gait():
    bp = cb.kisa()
    x = cb.fixed_point(bp)
    return bp, x, cb.step(bp, x)


@pytest.fixture(scope="module")
def goswami_gait():
    bp = cb.goswami()
    x = cb.fixed_point(bp)
    return bp, x, cb.step(bp, x)


def test_kisa_fixed_point(kisa_gait):
    bp, x, res = kisa_gait
    assert x == pytest.approx(KISA_X, abs=2e-10)
    assert res.x_plus_next == pytest.approx(x, abs=1e-11)
    assert res.period == pytest.approx(KISA_T, abs=1e-8)
    assert cb.step_period(bp, x) == pytest.approx(res.period, abs=1e-12)
    loose = cb.step(bp, x, rtol=1e-8, atol=1e-10)
    assert 0 < np.max(np.abs(loose.x_plus_next - x)) < 1e-6
    assert cb.step_length(bp, x) == pytest.approx(0.489765, abs=1e-6)
    assert res.x_minus == pytest.approx([0.2873985186, -0.2073985186, 1.3506364092, 1.5820806928], abs=2e-10)
    assert cb.swing_foot_height(bp, res.x_minus[:2]) == pytest.approx(0.0, abs=1e-11)
    assert np.max(np.abs(x - THESIS_X)) < 4e-4  # 003 Fig. 18 / App. A
    z = THESIS_X[[0, 2, 3]]
    assert np.max(np.abs(cb.return_map(bp, z) - z)) < 4e-4  # the thesis' state nearly repeats itself


def test_kisa_eigenvalues(kisa_gait):
    bp, x, _ = kisa_gait
    lam = cb.eigenvalues(bp, x)
    assert lam == pytest.approx(KISA_EIG, abs=2e-6)
    assert np.all(np.abs(lam) < 1)


def test_goswami_fixed_point_and_eigenvalues(goswami_gait):
    bp, x, res = goswami_gait
    assert x == pytest.approx(GOSWAMI_X, abs=2e-7)
    assert res.period == pytest.approx(GOSWAMI_T, abs=1e-6)
    assert cb.eigenvalues(bp, x) == pytest.approx(GOSWAMI_EIG, abs=2e-6)


def test_goswami_literature_state_at_g_9_8():
    """Goswami's [theta_ns, theta_s, dtheta_ns, dtheta_s] = [-0.3234, 0.2187, -0.3772, -1.0918] (counter-clockwise
    positive, g = 9.8; derivation page Sec. 2.6, values as commonly quoted), mapped to the thesis' order and sign."""
    x = cb.fixed_point(cb.goswami(g=9.8))
    assert x == pytest.approx([-0.2187, 0.3234, 1.0918, 0.3772], abs=1e-4)
    assert cb.step_period(cb.goswami(g=9.8), x) == pytest.approx(0.73472, abs=1e-5)


@pytest.mark.parametrize("gait", ["kisa_gait", "goswami_gait"])
def test_energy_balance_per_step(gait, request):
    """Impact loss = potential drop per step = (m_h + 2 m_l) g 2 l sin(alpha*) sin(gamma)."""
    bp, x, res = request.getfixturevalue(gait)
    half = 0.5 * (x[1] - x[0])
    loss = kinetic(bp, res.x_minus) - kinetic(bp, res.x_plus_next)
    assert loss == pytest.approx(bp.total_mass * bp.gravity * 2 * bp.l * math.sin(half) * math.sin(bp.slope), rel=1e-9)
    if gait == "kisa_gait":
        assert loss == pytest.approx(3.842651, abs=1e-6)


@pytest.mark.parametrize(
    ("gait", "n_min", "n_max", "mu"), [("kisa_gait", 145.17, 201.60, 0.2496), ("goswami_gait", 135.66, 202.96, 0.2742)]
)
def test_contact_validity(gait, n_min, n_max, mu, request):
    """Stance-foot force from the rate of change of the point masses' total momentum (central differences along
    an independent solve_ivp swing), against StepResult and the derivation page's ranges (Sec. 2.6)."""
    bp, x, res = request.getfixturevalue(gait)

    def rhs(_t, y):
        return np.concatenate([y[2:], cb.swing_dynamics(bp, y[:2], y[2:])])

    sol = solve_ivp(rhs, (0.0, res.period), x, method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True)
    h = 1e-5
    t = np.linspace(0.0, res.period, 600)  # the ends use the dense output's extrapolation over h

    def momentum(s):
        return sum(m * v for m, _, v in points(bp, sol.sol(s)))

    force = np.array([(momentum(s + h) - momentum(s - h)) / (2 * h) for s in t])
    force[:, 1] += bp.total_mass * bp.gravity
    tangent = np.array([math.cos(bp.slope), -math.sin(bp.slope)])
    normal = force @ u(bp.slope)
    assert normal.min() == pytest.approx(n_min, abs=0.01)
    assert normal.max() == pytest.approx(n_max, abs=0.01)
    assert res.min_normal_force_ratio * bp.total_mass * bp.gravity == pytest.approx(normal.min(), abs=1e-3)
    assert res.required_friction == pytest.approx(np.max(np.abs(force @ tangent) / normal), abs=1e-5)
    assert res.required_friction == pytest.approx(mu, abs=1e-4)
    if gait == "kisa_gait":
        assert res.liftoff_velocity == pytest.approx(0.3726, abs=1e-4)
    assert res.liftoff_velocity > 0
    # independent: the old stance foot's velocity after the impact, from the post-impact point masses
    _, hip, _ = points(bp, res.x_plus_next)
    foot_velocity = hip[2] - bp.l * res.x_plus_next[3] * du(res.x_plus_next[1])
    assert res.liftoff_velocity == pytest.approx(float(foot_velocity @ u(bp.slope)), abs=1e-12)


def test_legs_parallel_section_is_conjugate(kisa_gait):
    """003 eq 4.20 section: the derivation page's y* and time (Sec. 2.6); same multipliers as the post-impact
    section."""
    bp, x, _ = kisa_gait
    y, t = cb.legs_parallel_state(bp, x)
    assert y == pytest.approx([-0.0116109, 0.3953236, -1.8322910], abs=1e-7)
    assert t == pytest.approx(0.310944, abs=1e-6)
    assert cb.parallel_return_map(bp, y) == pytest.approx(y, abs=1e-10)
    eps = 1e-6
    jac = np.column_stack(
        [(cb.parallel_return_map(bp, y + d) - cb.parallel_return_map(bp, y - d)) / (2 * eps) for d in eps * np.eye(3)]
    )
    lam = np.linalg.eigvals(jac)
    lam = lam[np.lexsort((-lam.imag, -np.abs(lam)))]
    assert lam == pytest.approx(cb.eigenvalues(bp, x), abs=5e-6)


@pytest.mark.parametrize("slope", [0.005, 0.075])
def test_default_guess_reaches_slope_range(slope):
    bp = cb.goswami(slope)
    x = cb.fixed_point(bp)
    z = x[[0, 2, 3]]
    assert cb.return_map(bp, z) == pytest.approx(z, abs=1e-10)
    assert x[0] + x[1] == pytest.approx(2 * slope, abs=1e-15)
    assert np.max(np.abs(cb.eigenvalues(bp, x))) < 1
    assert np.all(cb.fixed_point(bp, guess=x) == pytest.approx(x, abs=1e-10))


def test_period_doubling_slope():
    """First flip bifurcation of the Goswami walker (derivation page Sec. 2.6: 4.3909 deg = 0.076636 rad); about 2 s."""
    slope = cb.period_doubling_slope(10.0, 5.0, 0.5, 0.5, 0.07, 0.08)
    assert slope == pytest.approx(0.076636, abs=2e-6)
    lam = cb.eigenvalues(cb.goswami(slope))
    assert np.min(np.abs(lam + 1)) < 1e-5
    with pytest.raises(ValueError, match="no multiplier crosses -1"):
        cb.period_doubling_slope(10.0, 5.0, 0.5, 0.5, 0.04, 0.045)


def test_pull_back_from_legs_parallel_inverts_the_swing() -> None:
    """post_impact_from_parallel is the inverse of legs_parallel_state (backward vs forward integration)."""
    for bp in (cb.kisa(), cb.goswami()):
        x = cb.fixed_point(bp) + np.array([0.01, -0.01, 0.02, -0.03])
        y, _ = cb.legs_parallel_state(bp, x)
        assert cb.post_impact_from_parallel(bp, y) == pytest.approx(x, abs=1e-9)


# --- the free biped at the trailing foot's release (compass_biped_flight) ----------------------------------------
def flight_points(bp: CompassBiped, s: np.ndarray) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(mass, position, velocity) of the hip and the two leg masses in the slope frame, s = (x, z, phi_0, phi_1, and
    their rates): the hip at (x, z), leg i's mass b below it along -u(phi_i)."""
    hip, v_hip = s[:2], s[4:6]
    return [(bp.m_h, hip, v_hip)] + [(bp.m_l, hip - bp.b * u(s[2 + i]), v_hip - bp.b * s[6 + i] * du(s[2 + i]))
                                     for i in (0, 1)]


def slope_gravity(bp: CompassBiped) -> np.ndarray:
    return bp.gravity * np.array([math.sin(bp.slope), -math.cos(bp.slope)])


def flight_kinetic(bp: CompassBiped, s: np.ndarray) -> float:
    return sum(0.5 * m * float(v @ v) for m, _, v in flight_points(bp, s))


def flight_potential(bp: CompassBiped, q: np.ndarray) -> float:
    return -sum(m * float(slope_gravity(bp) @ p) for m, p, _ in flight_points(bp, np.concatenate([q, np.zeros(4)])))


def flight_state() -> np.ndarray:
    return np.array([*RNG.uniform(-1.0, 1.0, 2), *RNG.uniform(-0.6, 0.6, 2), *RNG.uniform(-2.0, 2.0, 4)])


FLIGHT_BIPEDS = [replace(cb.kisa(), tau_ankle=0.5, tau_hip=0.2),
                 CompassBiped(m_h=3.0, m_l=2.0, a=0.3, b=0.8, slope=0.1, gravity=9.0, tau_ankle=-1.0, tau_hip=0.7)]


@pytest.mark.parametrize("bp", FLIGHT_BIPEDS)
def test_flight_eom_equals_lagrangian_of_point_masses(bp):
    """M = the Hessian of T in qd, h = (dp/dq) qd - dT/dq and G = -dU/dq, by finite differences of the point masses'
    T and U in MuJoCo's coordinates (x, z, phi_0, phi_1)."""
    for _ in range(5):
        s = flight_state()
        q, qd = s[:4], s[4:]
        mass = flight.mass_matrix(bp, q[2:])

        def momentum(qq, vv):
            return grad(lambda w: flight_kinetic(bp, np.concatenate([qq, w])), vv, 1e-3)  # exact: T quadratic in qd

        hess = np.vstack([grad(lambda w, k=k, q=q: momentum(q, w)[k], qd, 1e-3) for k in range(4)])
        assert mass == pytest.approx(hess, abs=1e-6)
        assert np.all(np.linalg.eigvalsh(mass) > 0)
        dpdq = np.vstack([grad(lambda z, k=k, qd=qd: momentum(z, qd)[k], q, 1e-5) for k in range(4)])
        h_qd = dpdq @ qd - grad(lambda z, qd=qd: flight_kinetic(bp, np.concatenate([z, qd])), q)
        assert flight.velocity_terms(bp, q[2:], qd[2:]) == pytest.approx(h_qd, abs=1e-5)
        assert flight.gravity_forces(bp, q[2:]) == pytest.approx(-grad(lambda z: flight_potential(bp, z), q), abs=1e-6)


@pytest.mark.parametrize("bp", FLIGHT_BIPEDS)
def test_flight_accelerations_obey_momentum_and_energy_balance(bp):
    """Along the computed accelerations, by central differences of point-mass quantities: the linear momentum
    changes by gravity only (the torques are couples), the angular momentum about the origin by gravity's moment
    plus the external torque Q_0 + Q_1 (the hip torque's pair cancels; the ankle torque reacts on the world through
    the hip's fixed orientation), and the energy T + U by the hinge torques' power: four balances, one per
    acceleration."""
    for _ in range(5):
        s = flight_state()
        torques = RNG.uniform(-2.0, 2.0, 2)
        rate = np.concatenate([s[4:], flight.accelerations(bp, s[2:4], s[6:], torques)])

        def along(f, s=s, rate=rate):
            return (f(s + 1e-6 * rate) - f(s - 1e-6 * rate)) / 2e-6

        def linear(y):
            return sum(m * v for m, _, v in flight_points(bp, y))

        def angular(y):
            return sum(cross(p, m * v) for m, p, v in flight_points(bp, y))  # cross(p, v) = -(p x v)_y

        total = bp.m_h + 2 * bp.m_l
        assert along(linear) == pytest.approx(total * slope_gravity(bp), abs=1e-6)
        moment = sum(cross(p, m * slope_gravity(bp)) for m, p, _ in flight_points(bp, s))
        assert along(angular) == pytest.approx(moment - torques.sum(), abs=1e-6)
        assert along(lambda y: flight_kinetic(bp, y) + flight_potential(bp, y[:4])) == pytest.approx(
            float(torques @ s[6:]), abs=1e-6)


@pytest.mark.parametrize("bp", FLIGHT_BIPEDS)
def test_pinned_foot_gives_the_stance_eom(bp):
    """Pinning leg 0's foot (hip at l u(phi_0) from it) projects the free biped onto 003 eq 4.5: J^T M J = M_4.5,
    J^T (M Jdot thetad + h) = C thetad and J^T G = G_4.5, J = d(x, z, phi_0, phi_1)/d(theta_st, theta_sw)."""
    for _ in range(5):
        x = random_state()
        phi, (w0, _) = x[:2] - bp.slope, x[2:]
        c, s = math.cos(phi[0]), math.sin(phi[0])
        jac = np.array([[bp.l * c, 0.0], [-bp.l * s, 0.0], [1.0, 0.0], [0.0, 1.0]])
        mass = flight.mass_matrix(bp, phi)
        assert jac.T @ mass @ jac == pytest.approx(cb.mass_matrix(bp, x[:2]), abs=1e-12)
        jdot_qd = np.array([-bp.l * s * w0**2, -bp.l * c * w0**2, 0.0, 0.0])
        assert jac.T @ (mass @ jdot_qd + flight.velocity_terms(bp, phi, x[2:])) == pytest.approx(
            cb.coriolis(bp, x[:2], x[2:]) @ x[2:], abs=1e-12)
        assert jac.T @ flight.gravity_forces(bp, phi) == pytest.approx(cb.gravity_vector(bp, x[:2]), abs=1e-12)


@pytest.mark.parametrize("bp", [cb.kisa(), *FLIGHT_BIPEDS])
def test_release_acceleration_is_the_released_foots_second_derivative(bp):
    """release_acceleration at the gait's pre-impact state is the second central difference of the trailing foot
    sphere's slope-normal height z - (l - r) cos phi_0 along the free biped's flow (DOP853, +-1e-3 s), with the
    torques moved to the leading leg (Q_0 + Q_1 = tau_ankle, Q_0 = tau_hip); at rest without torques it is free
    fall, -g cos gamma."""
    radius = 2.5e-4
    x_minus = cb.step(bp, cb.fixed_point(bp)).x_minus
    phi = x_minus[:2] - bp.slope
    start = np.array([0.0, 0.0, *phi, bp.l * x_minus[2] * math.cos(phi[0]), -bp.l * x_minus[2] * math.sin(phi[0]),
                      *x_minus[2:]])
    torques = flight.release_torques(bp)
    assert sum(torques) == pytest.approx(bp.tau_ankle, abs=1e-15) and torques[0] == bp.tau_hip

    def rhs(_t, y):
        return np.concatenate([y[4:], flight.accelerations(bp, y[2:4], y[6:], torques)])

    def height(t: float) -> float:
        y = start if t == 0 else solve_ivp(rhs, (0.0, t), start, method="DOP853", rtol=1e-13, atol=1e-14).y[:, -1]
        return float(y[1] - (bp.l - radius) * math.cos(y[2]))

    step = 1e-3
    second = (height(step) - 2 * height(0.0) + height(-step)) / step**2
    accel = flight.release_acceleration(bp, x_minus, radius)
    assert accel == pytest.approx(second, rel=1e-5)
    rest = np.array([*x_minus[:2], 0.0, 0.0])
    assert flight.release_acceleration(replace(bp, tau_ankle=0.0, tau_hip=0.0), rest, radius) == pytest.approx(
        -bp.gravity * math.cos(bp.slope), rel=1e-14)


def test_stance_phase_curve_against_rk45_events(kisa_gait):
    # 003 Fig. 18 (top): dtheta_st where theta_st crosses a level, by an independent RK45 integration of the passive
    # swing with an event at that level; the curve starts at the post-impact rate and ends at the pre-impact one
    from mjpoincare.analysis.theory.compass_biped.dynamics import swing_dynamics
    from mjpoincare.analysis.theory.compass_biped.figures import stance_phase_curve

    bp, x_star, step = kisa_gait
    x_minus = step.x_minus
    levels = np.linspace(x_star[0], x_minus[0], 9)[1:-1]

    def rhs(_t, y):
        return [y[2], y[3], *swing_dynamics(bp, y[:2], y[2:])]

    expected = []
    for level in levels:
        def cross(_t, y, lv=level):
            return y[0] - lv
        cross.terminal, cross.direction = True, 1.0
        sol = solve_ivp(rhs, (0.0, 2.0), x_star, method="RK45", events=cross, rtol=1e-11, atol=1e-12)
        expected.append(sol.y_events[0][0][2])
    np.testing.assert_allclose(stance_phase_curve(bp, x_star, levels), expected, atol=1e-8)
    ends = stance_phase_curve(bp, x_star, [x_star[0], x_minus[0]])
    np.testing.assert_allclose(ends, [x_star[2], x_minus[2]], atol=1e-10)
    with pytest.raises(ValueError, match="outside"):
        stance_phase_curve(bp, x_star, [0.5])
