"""The compass biped's runs: post-impact starts on the 3-D section around the fixed point (003 eq 4.18), the walk of a
batch of them with the gait controller switching the feet's contacts at the events, and the released trailing foot's
fall the ``trailing_foot_release`` check is judged against."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjpoincare.analysis.adaptive_stopping import FitSettling
from mjpoincare.analysis.start_designs import design_size, sphere_offsets
from mjpoincare.analysis.theory import compass_biped as theory
from mjpoincare.analysis.theory.compass_biped import flight
from mjpoincare.core.params import Values
from mjpoincare.core.seam import RolloutReport
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.base import Foot, ReturnMapPlot, SectionConvergence
from mjpoincare.scenarios.compass_biped.controller import GaitController
from mjpoincare.simulation.simulate import event_rollout, initial_states


def biped(params: Values) -> theory.CompassBiped:
    """The analytic model for the scenario parameters (003 Ch. 4)."""
    return theory.CompassBiped(m_h=float(params["m_h"]), m_l=float(params["m_l"]), a=float(params["a"]),
                               b=float(params["b"]), slope=float(params["slope"]), gravity=float(params["gravity"]),
                               tau_ankle=float(params["tau_ankle"]), tau_hip=float(params["tau_hip"]))

#: ``foot_radius`` in the bipeds' models (passive, actuated, with friction).
BIPED_FOOT = Foot(meaning="spheres at the leg tips, standing for the point feet (lowest point at the leg's length); "
                          "the controller switches their contacts at each heel strike")
#: The feet's contact impedance in the bipeds' presets (MuJoCo's default solimp d0, d_width): a loaded foot then sits
#: about 1e-7 m deep and its contact stays in every step's constraint set; at 0.99-0.999 it sat within 1e-9 m of the
#: slope and dropped out on 1.7 % of the steps (accurate preset; 0.95-0.99: 0.1 %), each a step of free fall that made
#: the map jump with the step (tests/test_biped_step_grid.py).
BIPED_IMPEDANCE: dict[str, float] = {"solimp_dmin": 0.9, "solimp_dmax": 0.95}
STEPS = 10  # heel strikes per trajectory, at most (adaptive stopping ends the batch earlier: STOPPING)
#: Initial offsets from the fixed point on the 3-D post-impact section: STARTS random directions (fixed seed), of
#: size PERTURBATION, x (timestep / 20 us)^(1/3) below 20 us, shrunk to a third as |lambda|max -> 1 (how the size
#: and the count were chosen: docs/scenarios/compass-biped.md, "Presets and start design").
STARTS = 16
PERTURBATION = 0.03
#: Steps of free fall the released trailing foot is allowed before its dip fails ``trailing_foot_release``: twice the
#: controller's release lead (the new foot is predicted at the slope 2 steps ahead; see :func:`release_tolerance`).
RELEASE_FALL_STEPS = 4
CHUNK_SECONDS = 0.05  # native steps between controller looks: 5x fewer Python calls than 10 ms, same results
#: m: how deep the stance foot starts in the slope. With the foot exactly on it, the foot's contact distance is
#: roundoff (about +-2e-16 m), so whether the contact exists in the first step is decided by the last bit of the start,
#: which the analytic fixed point's Newton solve (and so the BLAS kernel) sets; that step with or without its contact
#: moved the fitted multipliers by up to 1e-3 between kernels. 1e-9 m decides it for every start and is 1e-4 of the
#: foot's steady penetration under the biped's weight at the fast presets (tests/test_compass_biped_starts.py).
STANCE_DEPTH = 1e-9


def post_impact_states(model: mujoco.MjModel, bp: theory.CompassBiped, x_plus: np.ndarray,
                       foot_radius: float) -> np.ndarray:
    """MuJoCo states for post-impact states x = (theta_st, theta_sw, dtheta_st, dtheta_sw) (thesis frame).

    Leg 0 is the stance leg with its foot at the origin; the hip moves as rotation about it.
    """
    q_st, q_sw = x_plus[:, 0] - bp.slope, x_plus[:, 1] - bp.slope
    w_st, w_sw = x_plus[:, 2], x_plus[:, 3]
    qpos = standing_qpos(bp.l, foot_radius, q_st, q_sw)
    qvel = np.stack([bp.l * w_st * np.cos(q_st), -bp.l * w_st * np.sin(q_st), w_st, w_sw], axis=1)
    return initial_states(model, qpos, qvel)


def standing_qpos(leg_length: float, foot_radius: float, q_st: np.ndarray, q_sw: np.ndarray) -> np.ndarray:
    """qpos (B, 4) = (hip x, hip z, stance hinge, swing hinge) of a biped standing on the slope: its stance foot's
    sphere centred over the origin (the hip by rotation about it), STANCE_DEPTH into the slope."""
    lever = leg_length - foot_radius
    return np.stack([lever * np.sin(q_st), lever * np.cos(q_st) + foot_radius - STANCE_DEPTH, q_st, q_sw], axis=1)


def initial_section_states(bp: theory.CompassBiped, timestep: float) -> np.ndarray:
    """The fixed point and STARTS offsets from it on the 3-D post-impact section (theta_st by a tenth of the
    size, keeping both feet on the slope; each rate by the size, rad/s), in random directions (seed 0); the size
    rounded by :func:`~mjpoincare.analysis.start_designs.design_size` (the multipliers carry the kernel's roundoff)."""
    x_star = theory.fixed_point(bp)
    margin = 1.0 - float(np.max(np.abs(theory.eigenvalues(bp, x_star))))
    size = design_size(PERTURBATION * min(1.0, (timestep / 2e-5) ** (1.0 / 3.0))
                       * min(1.0, max(1.0 / 3.0, margin / 0.4)))
    out = sphere_offsets(x_star, np.array([0.1 * size, 0.0, size, size]), STARTS)
    out[:, 1] = 2.0 * bp.slope - out[:, 0]
    return out


def walk(model: mujoco.MjModel, bp: theory.CompassBiped, starts: np.ndarray, steps: int, settings: Values,
         settling: FitSettling | None = None) -> tuple[GaitController, RolloutReport]:
    """Walk from the post-impact states ``starts`` for ``steps`` heel strikes, switching contacts at the events;
    with ``settling``, stop once it says the legs-parallel samples so far are enough."""
    controller = GaitController(model, bp, len(starts), float(settings["foot_radius"]))
    period = theory.step_period(bp, theory.fixed_point(bp))
    nstep = math.ceil((steps + 0.5) * period / model.opt.timestep)
    stop = None if settling is None else lambda: settling(controller.samples)
    report = event_rollout(model, post_impact_states(model, bp, starts, float(settings["foot_radius"])), nstep,
                           controller,
                           **rollout_options(settings), chunk_steps=max(10, round(CHUNK_SECONDS / model.opt.timestep)),
                           setup=controller.configure, stop=stop)
    return controller, report


def release_tolerance(model: mujoco.MjModel, bp: theory.CompassBiped, x_star: np.ndarray, foot_radius: float
                      ) -> tuple[float, float]:
    """(a, depth): the released trailing foot's slope-normal acceleration a (m/s^2, < 0 downward) at the exact
    pre-impact state of the gait from ``x_star``, from the exact free biped with the torques switched to the new
    stance leg, as the controller switches them with the release
    (:func:`mjpoincare.analysis.theory.compass_biped.flight.release_acceleration`; not from MuJoCo, so that a dynamics
    regression cannot move the tolerance with the error), and the depth it falls from rest in RELEASE_FALL_STEPS
    semi-implicit Euler steps of ``model``'s timestep, |a| dt^2 n (n + 1)/2."""
    accel = flight.release_acceleration(bp, theory.step(bp, x_star).x_minus, foot_radius)
    n = RELEASE_FALL_STEPS
    return accel, max(0.0, -accel) * model.opt.timestep**2 * n * (n + 1) / 2


def legs_parallel_figures(plot_label: str, labels: list[str], x: np.ndarray, x_next: np.ndarray,
                          eigenvalues: np.ndarray, fixed_point: np.ndarray, sequences: list[np.ndarray]
                          ) -> tuple[ReturnMapPlot, SectionConvergence]:
    """The report's figures of a biped's legs-parallel section map, which has no 1-D analytic form: the first
    coordinate's x_k -> x_k+1 (no analytic curve) and each coordinate's approach to the analytic fixed point.

    Args:
        plot_label: the plotted (first) coordinate's axis label.
        labels: ``(3,)`` the section coordinates' names with units.
        x, x_next: ``(m, 3)`` the sample pairs.
        eigenvalues: ``(3,)`` the analytic multipliers.
        fixed_point: ``(3,)`` the analytic fixed point on the section.
        sequences: per trajectory, its consecutive section samples ``(k, 3)``.
    """
    grid = np.linspace(float(x[:, 0].min()), float(x[:, 0].max()), 2)
    plot = ReturnMapPlot(label=plot_label, x=x[:, 0], x_next=x_next[:, 0], analytic_x=grid,
                         analytic_y=np.full_like(grid, np.nan), analytic_eigenvalues=eigenvalues)
    return plot, SectionConvergence(labels=labels, fixed_point=fixed_point, sequences=sequences)
