"""The compass biped with friction's experiment design: post-impact starts on 002's section around a gait's fixed
point (002 Sec. 4.2), their size kept inside a type-B gait's impact border (002 eqs 37-40), and the steps, starts and
fit degree each kind of gait is fitted with."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjpoincare.analysis.start_designs import design_size, sphere_offsets
from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.scenarios.compass_biped.runs import standing_qpos
from mjpoincare.simulation.simulate import initial_states

STEPS = 8  # heel strikes per trajectory, at most (a stable gait's batch stops earlier once its fit settles: STOPPING)
STARTS = 16  # perturbed starts around the fixed point (plus the fixed point itself)
PERTURBATION = 0.03  # as compass-biped: size x (timestep / 20 us)^(1/3), shrunk as |lambda|max -> 1
SETTLE = 3  # steps of the unperturbed trajectory skipped before per-step averages
#: Periods a run lasts past its last heel strike: a start on the post-impact section crosses legs-parallel about half
#: a period after each strike, so a run of (steps + 0.5) periods ended at a crossing, and which trajectories had their
#: last sample depended on the fraction of a step their gait gained or lost; 0.75 ends between the crossing and the
#: next strike.
HORIZON_TAIL = 0.75
#: Unstable gaits (|lambda|max > 1): the map is fitted from the first UNSTABLE_STEPS steps only, from more starts
#: and a quadratic fit (why: docs/scenarios/compass-biped-friction.md, "Tolerances and start design")
UNSTABLE_STEPS = 2
UNSTABLE_STARTS = 32
UNSTABLE_DEGREE = 2
FIT_DEGREE = 3
#: Type-B gaits: starts inside the impact border, fitted linearly (why: the same docs section)
BORDER_DEGREE = 1


def post_impact_states(model: mujoco.MjModel, bp: theory.FrictionBiped, z: np.ndarray, foot_radius: float
                       ) -> np.ndarray:
    """MuJoCo states for 002 section states z = (theta*, theta1_dot+, theta2_dot+, x_dot+) (002 Sec. 4.2): leg 0
    stands with its foot at the origin (sliding at x_dot+ after a slipping impact); leg 1, the swing leg, has its
    foot on the ground behind it (theta1 = theta2 = -theta*; swing hinge = -theta2, rate -theta2_dot); placed as
    compass-biped's (:func:`mjpoincare.scenarios.compass_biped.runs.standing_qpos`)."""
    th, w1, w2, xd = z[:, 0], z[:, 1], z[:, 2], z[:, 3]
    q_st, q_sw = -th, th  # theta1 = theta2 = -theta*; swing hinge = -theta2
    qpos = standing_qpos(bp.l, foot_radius, q_st, q_sw)
    qvel = np.stack([xd + bp.l * w1 * np.cos(q_st), -bp.l * w1 * np.sin(q_st), w1, -w2], axis=1)
    return initial_states(model, qpos, qvel)


def horizon(g: theory.Gait, steps: int, timestep: float) -> int:
    """Physics steps of a run of ``steps`` heel strikes and its :data:`HORIZON_TAIL`."""
    return math.ceil((steps + HORIZON_TAIL) * g.record.period / timestep)


def unstable(g: theory.Gait) -> bool:
    """|lambda|max >= 1: fitted over UNSTABLE_STEPS steps only."""
    return g.spectral_radius >= 1.0


def design(g: theory.Gait) -> tuple[int, int, int]:
    """(heel strikes per trajectory, fit degree, settled steps skipped) for the gait: STEPS, FIT_DEGREE, SETTLE, or
    for an unstable gait UNSTABLE_STEPS, UNSTABLE_DEGREE and 1 (the first stance starts from the injected state);
    a stable type-B gait, whose starts stay inside its :func:`impact_border`, is fitted linearly (BORDER_DEGREE)."""
    if unstable(g):
        return UNSTABLE_STEPS, UNSTABLE_DEGREE, 1
    return STEPS, BORDER_DEGREE if g.kind == "B" else FIT_DEGREE, SETTLE


def impact_border(g: theory.Gait) -> float:
    """Perturbation size (rate offsets; theta* by a tenth) at which a start can reach the border of a sticking
    impact, |F~_t/F~_n| = mu (002 eqs 37-40): (mu - |sigma~|)/|grad sigma~ . diag(0.1, 1, 1)|, the gradient by
    central differences of the exact step; inf for a slipping impact. Across it the map switches to the slipping-
    impact branch (a kink, 002 Sec. 4.2), which no polynomial fit spans: Gait B at mu = 0.14 has |sigma~| = 0.126,
    grad (16.0, -3.35, -0.44), so the border is 0.0037 away (0.0139/3.74) while the compass-biped size is 0.023."""
    if g.record.impact != "sticking" or math.isinf(g.biped.mu):
        return math.inf
    grad = np.zeros(3)
    for i in range(3):
        dz = np.zeros(4)
        dz[i] = 1e-6
        up, down = (theory.step(g.biped, g.z + sign * dz, g.actuation).impulse_ratio for sign in (1.0, -1.0))
        grad[i] = (up - down) / 2e-6
    return float((g.biped.mu - abs(g.record.impulse_ratio)) / np.linalg.norm(grad * np.array([0.1, 1.0, 1.0])))


def initial_section_states(g: theory.Gait, timestep: float) -> np.ndarray:
    """z* and offsets (seed 0) on (theta*, theta1_dot+, theta2_dot+) as compass-biped: theta* by a tenth of
    the size, the rates by the size (x_dot+ kept at z*); for a type-B gait (sticking impact, slip in the stance) the
    size no larger than :func:`impact_border` (all starts on the fixed point's impact branch), rounded by
    :func:`~mjpoincare.analysis.start_designs.design_size`; STARTS of them,
    UNSTABLE_STARTS for an unstable gait."""
    margin = 1.0 - g.spectral_radius
    size = PERTURBATION * (timestep / 2e-5) ** (1.0 / 3.0) * min(1.0, max(1.0 / 3.0, margin / 0.4))
    if g.kind == "B":  # measured: half of Gait B's compass-biped-size starts left the gait
        size = min(size, impact_border(g))
    size = design_size(size)  # the multipliers and the border carry the kernel's roundoff; the starts do not
    starts = UNSTABLE_STARTS if unstable(g) else STARTS
    return sphere_offsets(g.z, np.array([0.1 * size, size, size, 0.0]), starts)
