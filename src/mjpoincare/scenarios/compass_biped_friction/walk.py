"""The friction biped's model and walk (002 Secs. 4-5): the compass-biped MJCF with 002's parameters and torques, and
the event rollout that walks it with the gait controller (contact switching, constant torques, Gait III's PD servos).
The scenario's validation, its video states and validation batches and its paper runs use them."""

from __future__ import annotations

import mujoco
import numpy as np

from mjpoincare.analysis.adaptive_stopping import FitSettling
from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.core.params import Values
from mjpoincare.core.seam import RolloutReport
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios import compass_biped as cb
from mjpoincare.scenarios.compass_biped.controller import FrictionGaitController
from mjpoincare.scenarios.compass_biped_friction.gait_choice import friction, gait, gait_name
from mjpoincare.scenarios.compass_biped_friction.start_design import horizon, post_impact_states
from mjpoincare.simulation.simulate import KeptRows, event_rollout

ENABLE_AHEAD = 0.05  # swing-foot contact on once the foot is this far (x l) ahead of the stance foot ...
ENABLE_CLEAR = 2e-4  # ... and this high (x l) above the ground (Gait III's swing foot clears only ~1 mm)
CHUNK_SECONDS = 0.05


def torques(params: Values) -> tuple[float, float]:
    """(tau_ankle, tau_hip) of the compass-biped model for Gaits I and II: stance hinge = Q1 = tau_ankle - tau_hip,
    swing hinge = -Q2 = tau_hip (002 eq 28 with E_eff; II: Q = (0.57, 0.12), tau_ankle 0.45, tau_hip -0.12)."""
    act = gait(params).actuation
    if gait_name(params) not in ("I", "II") or not isinstance(act, theory.ConstantTorque):
        return 0.0, 0.0
    q1, q2 = act.generalised_force(np.zeros(4), np.zeros(4), 0.0)
    return q1 - q2, -q2


def model_params(params: Values) -> dict[str, float]:
    """compass-biped parameters for 002's biped (l = 1.6, d = 0.8, m = 4, m_h = 2, g = 9.8)."""
    bp = gait(params).biped
    tau_ankle, tau_hip = torques(params)
    return {"m_h": bp.m_h, "m_l": bp.m, "a": bp.d, "b": bp.b, "slope": bp.slope, "mu": friction(params),
            "gravity": bp.g, "tau_ankle": tau_ankle, "tau_hip": tau_hip}


def build(params: Values, settings: Values) -> mujoco.MjModel:
    """compass_biped.xml rebuilt with 002's parameters; Gait III's ankle actuators become PD servos on ctrl."""
    model = cb.build(model_params(params), settings)
    if gait_name(params) == "III":
        for i in (0, 1):
            a = model.actuator(f"ankle{i}").id
            model.actuator_gainprm[a, 0] = 1.0
            model.actuator_biasprm[a, :3] = (0.0, -float(params["kp"]), -float(params["kd"]))
    return model


def run_gait(params: Values, settings: Values, model: mujoco.MjModel, starts: np.ndarray, steps: int,
         wrap: bool = False, settling: FitSettling | None = None, first_samples: int = 0
         ) -> tuple[FrictionGaitController, RolloutReport, KeptRows | None]:
    """Walk the scenario's model from the section states ``starts`` for ``steps`` heel strikes (its gait controller:
    contact switching, the gait's torques, Gait III's PD servos), in one event rollout; ``wrap`` keeps trajectory 0's
    rows. With ``settling``, the other starts stop once the fit has settled, and trajectory 0 (the fixed point's,
    whose stances the stance checks read) once it also has ``first_samples`` legs-parallel samples."""
    g = gait(params)
    pd = (float(params["kp"]), float(params["kd"])) if gait_name(params) == "III" else None
    radius = float(settings["foot_radius"])
    controller = FrictionGaitController(model, g, len(starts), radius, torques(params), pd, (ENABLE_AHEAD,
                                                                                              ENABLE_CLEAR))
    chunk = max(10, round(CHUNK_SECONDS / model.opt.timestep))
    nstep = horizon(g, steps, model.opt.timestep)
    kept = KeptRows(controller) if wrap else None

    def finished() -> np.ndarray:
        known = np.zeros(len(starts), bool)
        if settling is not None and (settling.reason != "full design" or settling(controller.samples)):
            known[1:] = True
            known[0] = len(controller.samples[0]) >= first_samples
        return known

    report = event_rollout(model, post_impact_states(model, g.biped, starts, radius),
                           nstep, kept if kept is not None else controller, **rollout_options(settings),
                           chunk_steps=chunk,
                           control=(lambda t0: controller.control(t0, chunk)) if pd is not None else None,
                           setup=controller.configure,
                           finished=finished)
    return controller, report, kept
