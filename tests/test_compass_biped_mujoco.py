"""Regression: MuJoCo's passive compass biped against the exact hybrid model (Kisa 2020 Ch. 4; Goswami et al.).

The gait runs with the contact switching the analytic model assumes (swing foot's contact off until it is ahead
and clear, trailing foot released at heel strike); tolerances are the scenario's own.
"""

from __future__ import annotations

import copy
import math

import mujoco
import numpy as np
import pytest
from mjpoincare.analysis.theory import compass_biped as theory
from mjpoincare.analysis.theory.compass_biped import flight
from mjpoincare.analysis.theory.compass_biped.step_measurements import swing_foot_detail

from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_values
from mjpoincare.core.seam import STATE_SPEC
from mjpoincare.engines.backends.mujoco_c import MujocoBatch
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios import compass_biped as cb
from mjpoincare.scenarios.base import JointIndex
from mjpoincare.scenarios.compass_biped.controller import GaitController
from mjpoincare.scenarios.compass_biped.runs import RELEASE_FALL_STEPS, post_impact_states, release_tolerance

pytestmark = pytest.mark.mujoco


def test_switched_off_swing_foot_dips_as_the_exact_swing() -> None:
    """The swing foot passes through the slope mid-swing, as the exact model's does (003 Sec. 4.1 ignores it). On
    every swing of the trajectory from the fixed point, its depth below the stance foot is the exact swing's (from
    the post-impact state its legs-parallel sample pulls back to, legs l - r to the slope) within (r/l) x the exact
    gait's depth: MuJoCo's foot spheres (radius r) are point feet only to O(r/l). A foot whose contact stayed on
    would stop at the slope. The run's deepest dip below the slope is reported without a verdict, in the table and
    the JSON (the run's verdicts are the gate's: tests/test_gate.py)."""
    result = gate.run_case(gate.case("compass-biped[fast]"))
    swing = result.extras["swing_foot"]
    r_over_l = result.settings["foot_radius"] / (result.params["a"] + result.params["b"])
    below, exact = swing["depth_below_stance_foot"], swing["exact_depth_same_swing"]
    # every swing the run walked (the batch stops once its fit settles), the last one after the last heel strike
    assert len(below) == len(exact) and cb.STOPPING.min_samples <= len(below) <= cb.STEPS + 1
    assert max(abs(m - e) for m, e in zip(below, exact, strict=True)) <= r_over_l * swing["exact_depth"]
    reported = result.reported["swing_foot_depth"]
    assert reported.unit == "m" and reported.value >= max(swing["depth"])  # perturbed starts included
    assert "swing_foot_depth" not in {c.name for c in result.checks}
    assert "reported swing_foot_depth: " in result.table()
    assert result.to_dict()["reported"]["swing_foot_depth"]["value"] == reported.value


def test_constant_torques_move_the_gait_as_the_theory_says() -> None:
    """Ankle and hip torques are MuJoCo actuators switched to the stance leg at each heel strike: the gait they
    give matches the exact actuated model (fast preset tolerances)."""
    result = gate.run_case(gate.case("compass-biped[fast,tau_ankle=0.5,tau_hip=0.2]"))
    passive = theory.fixed_point(theory.CompassBiped())
    assert abs(result.analytic.values["fixed_point"][2] - passive[2]) > 0.01  # the torques matter


@pytest.mark.parametrize(
    ("assignment", "needle"),
    [("m_h=-1", "m_h must be in (0, 1e+06]"), ("a=0", "a must be in (0, 100]"),
     ("slope=0.09", "unstable passive gait"), ("mu=0.1", "mu must be >= 0.2496")],
)
def test_bad_input(assignment: str, needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "compass-biped", "--set", assignment]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_a_mass_ratio_the_heel_strike_contact_cannot_hold_is_refused(capsys: pytest.CaptureFixture[str]) -> None:
    """m_h / m_l past 1e4: the heel-strike contact, as soft as the light leg makes it, cannot stop the hip."""
    assert main(["validate", "compass-biped", "--set", "m_h=1e6", "--set", "m_l=1e-6"]) == 2
    err = capsys.readouterr().err
    assert "m_h / m_l must be <= 10000 (got 1e+12)" in err and err.count("\n") == 1


def test_a_sample_the_exact_biped_falls_from_gives_nan_not_a_traceback() -> None:
    """A simulated gait far from the exact one (a fallen run's legs-parallel sample, from a run at m_h / m_l = 1e4
    with solimp 0.5-0.6) is measured as nan in the swing-foot record."""
    bp = theory.CompassBiped()
    fallen = np.array([-0.30897218, -0.31002485, -3.17537188])
    detail = swing_foot_detail(bp, [(-0.1, 0.0)], [fallen], 5e-4, 0.002)
    assert math.isnan(detail["exact_depth_same_swing"][0])


def mujoco_release(model: mujoco.MjModel, bp: theory.CompassBiped, x_minus: np.ndarray, foot_radius: float,
                   switched: bool) -> tuple[float, np.ndarray]:
    """MuJoCo's own slope-normal acceleration of the released trailing foot (leg 0) at the pre-impact state
    ``x_minus``, with no contact (mj_forward), and its qacc in (x, z, leg0, leg1): release_tolerance's computation
    before it took the exact model. Torques: the gait's before the release (the ankle torque on the trailing leg, as
    that computation had them), or ``switched`` as the controller sets them with the release (on the leading leg)."""
    m = copy.copy(model)
    controller = GaitController(m, bp, 1, foot_radius)
    state = post_impact_states(m, bp, x_minus[None, :], foot_radius)
    with MujocoBatch([m], state, threads=0) as batch:
        controller.configure(batch)
        batch.set_contact(0, controller.feet[0], False)
        if switched:
            controller._actuate(batch, 0, 1)  # the controller's own switch at the release
    data = mujoco.MjData(m)
    mujoco.mj_setState(m, data, state[0], STATE_SPEC)
    mujoco.mj_forward(m, data)
    z, leg = JointIndex.of(m, "z"), JointIndex.of(m, "leg0")
    q, w = float(data.qpos[leg.qpos]), float(data.qvel[leg.dof])
    accel = float(data.qacc[z.dof]) + (bp.l - foot_radius) * (math.sin(q) * float(data.qacc[leg.dof])
                                                               + math.cos(q) * w * w)
    dofs = [JointIndex.of(m, name).dof for name in ("x", "z", "leg0", "leg1")]
    return accel, data.qacc[dofs].copy()


@pytest.mark.parametrize("assignments", [{}, {"tau_ankle": 0.5, "tau_hip": 0.2}])
def test_release_acceleration_agrees_with_mujoco(assignments: dict[str, float]) -> None:
    """The exact free biped's accelerations at the gait's pre-impact state (analysis.theory.compass_biped_flight,
    which trailing_foot_release's tolerance now takes) against MuJoCo's qacc there, with either torque assignment:
    within 1e-6 relative, the size of the legs' 1e-6 kg m^2 rotational inertia in the MJCF against m_l b^2 = 1.25 kg
    m^2 (measured at the fast preset, foot acceleration / qacc: 8.0e-9 / 3.2e-8 passive, 2.0e-8 / 7.2e-8 actuated).
    That inertia, where the exact model has point masses, is the whole difference: with it zeroed they agree to
    roundoff. The switch of the torques to the leading leg
    moves the actuated point's acceleration by 1.85e-3 relative (-8.2932 -> -8.3086 m/s^2)."""
    _, _, params, settings = resolve_values("compass-biped", assignments, "fast")
    bp, model = cb.biped(params), cb.build(params, settings)
    radius = float(settings["foot_radius"])
    x_minus = theory.step(bp, theory.fixed_point(bp)).x_minus
    angles, rates = x_minus[:2] - bp.slope, x_minus[2:]
    point_masses = cb.build(params, settings)
    point_masses.body_inertia[:] = 0.0
    for switched, torques in ((False, (bp.tau_ankle - bp.tau_hip, bp.tau_hip)), (True, flight.release_torques(bp))):
        qdd = flight.accelerations(bp, angles, rates, torques)
        phi, w = float(angles[0]), float(rates[0])
        accel = float(qdd[1]) + (bp.l - radius) * (math.sin(phi) * float(qdd[2]) + math.cos(phi) * w * w)
        mj_accel, qacc = mujoco_release(model, bp, x_minus, radius, switched)
        assert accel == pytest.approx(mj_accel, rel=1e-6)
        assert qacc == pytest.approx(qdd, rel=1e-6, abs=1e-6 * float(np.max(np.abs(qdd))))
        mj_point, qacc_point = mujoco_release(point_masses, bp, x_minus, radius, switched)
        assert accel == pytest.approx(mj_point, rel=1e-13)
        assert qacc_point == pytest.approx(qdd, rel=1e-12, abs=1e-12 * float(np.max(np.abs(qdd))))
    exact, tolerance = release_tolerance(model, bp, theory.fixed_point(bp), radius)
    assert exact == flight.release_acceleration(bp, x_minus, radius) == pytest.approx(mj_accel, rel=1e-6)
    n = RELEASE_FALL_STEPS
    assert tolerance == pytest.approx(-exact * model.opt.timestep**2 * n * (n + 1) / 2, rel=1e-15)
