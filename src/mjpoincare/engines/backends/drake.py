"""Drake behind the rollout seam (:class:`mjpoincare.core.seam.Batch`): the scenario's own compiled model as a discrete
``MultibodyPlant`` (:mod:`mjpoincare.engines.backends.drake_plant`), one simulator per trajectory (Drake has no batch),
each chunk stepped natively with the plant's state logged at every step (``VectorLogSink``), no Python between steps.

What it implements of the seam: chunks, state setting, per-trajectory friction (the geometries' proximity
properties replaced in that trajectory's scene-graph context), contact release (that context's collision filters)
(its own self-test then fails on the contact's softness, docs/engines.md). Equality toggling, actuators and
fractional steps it does not: their calls raise
:class:`NotImplementedError`, so the seam's self-test of a scenario's mechanism refuses the scenario before any of its
simulation (:mod:`mjpoincare.simulation.seam_check`).
"""

from __future__ import annotations

import time

import mujoco
import numpy as np
from pydrake.geometry import CollisionFilterDeclaration, GeometrySet, ProximityProperties, RoleAssign
from pydrake.multibody.plant import CoulombFriction
from pydrake.systems.analysis import Simulator

from mjpoincare.engines.backends.arrays import ArrayBatch
from mjpoincare.engines.backends.drake_plant import build_scene, no_deformable_note, to_drake, to_mujoco


class DrakeBatch(ArrayBatch):
    """:class:`mjpoincare.core.seam.Batch` on Drake: B simulators of one plant built from ``model``, from the starts
    ``state0`` (B, nstate); ``approximation``: Drake's discrete contact approximation (sap, tamsi, lagged, similar);
    ``hydroelastic``: compliant hydroelastic contact where the geometry allows it (else point contact)."""

    def __init__(self, model: mujoco.MjModel, state0: np.ndarray, *, approximation: str = "sap",
                 hydroelastic: bool = False) -> None:
        self._model = model
        self._start(model, np.asarray(state0, float), 0)
        with no_deformable_note():
            self._scene = build_scene(model, approximation=approximation, hydroelastic=hydroelastic)
            self._contexts = [self._scene.diagram.CreateDefaultContext() for _ in range(self._real)]
        self._simulators = [Simulator(self._scene.diagram, context) for context in self._contexts]
        self._applied = np.full(self._real, self._scene.friction)

    def run_chunk(self, nstep: int, control: np.ndarray | None = None, rows: np.ndarray | None = None
                  ) -> np.ndarray:
        if control is not None and np.any(control):
            raise NotImplementedError("backend=drake: actuator controls")
        scene, model = self._scene, self._model
        nstate = self._current.shape[1]
        states = np.empty((self._real, nstep, nstate))
        start = time.perf_counter()
        skipped = 0
        for b, (context, simulator) in enumerate(zip(self._contexts, self._simulators, strict=True)):
            if (self._diverged[b] or not np.isfinite(self._current[b]).all()  # flagged: stays NaN, never stepped
                    or (rows is not None and b not in rows)):
                states[b] = np.nan
                skipped += 1
                continue
            self._apply_friction(b)
            plant_context = scene.plant.GetMyMutableContextFromRoot(context)
            t0 = float(self._current[b, 0])
            context.SetTime(0.0)  # the dynamics are time-invariant: each chunk runs from 0, its times from t0
            scene.plant.SetPositionsAndVelocities(plant_context, to_drake(scene, model, self._current[b:b + 1])[0])
            scene.logger.FindMutableLog(context).Clear()
            try:
                simulator.Initialize()
                simulator.AdvanceTo(nstep * model.opt.timestep)
            except RuntimeError as error:  # the discrete solver failed: the trajectory diverged there
                self._failure(str(error))
            samples = scene.logger.FindLog(context).data().T[1: nstep + 1]
            full = np.full((nstep, samples.shape[1] if samples.size else scene.nq + scene.nv), np.nan)
            full[: len(samples)] = samples
            times = t0 + model.opt.timestep * np.arange(1, nstep + 1)
            states[b] = to_mujoco(scene, model, times, full, nstate)
        stepped = self._finish_chunk(states, np.zeros((self._real, nstep, 0)), nstep, time.perf_counter() - start,
                                     rows)
        self.report.steps -= skipped * nstep  # a flagged or unasked trajectory was not stepped
        return stepped

    def _failure(self, message: str) -> None:
        """A failed discrete update, once per kind in the report's warnings (the trajectory is flagged diverged)."""
        line = "drake: " + message.split(" at simulation time")[0].split("\n")[0]
        if line not in self.report.warnings:
            self.report.warnings.append(line)

    def _apply_friction(self, b: int) -> None:
        """Trajectory ``b``'s friction coefficient (``geom_friction[:, 0]``, set by :meth:`set_friction`) into its
        scene-graph context's proximity properties, when it changed."""
        mu = float(self._fields["geom_friction"][b, 0, 0])
        if mu == self._applied[b]:
            return
        scene = self._scene
        sg_context = scene.scene_graph.GetMyMutableContextFromRoot(self._contexts[b])
        inspector = scene.scene_graph.model_inspector()
        for geometry in scene.geometries.values():
            props = ProximityProperties(inspector.GetProximityProperties(geometry))
            props.UpdateProperty("material", "coulomb_friction", CoulombFriction(mu, mu))
            scene.scene_graph.AssignRole(sg_context, scene.plant.get_source_id(), geometry, props, RoleAssign.kReplace)
        self._applied[b] = mu

    def set_eq_active(self, index: int, eq: int, on: bool) -> None:
        raise NotImplementedError("backend=drake: equality toggling (a held joint is welded)")

    def set_actuator(self, index: int, actuator: int, *, bias: float | None = None, gear: float | None = None
                     ) -> None:
        raise NotImplementedError("backend=drake: actuators")

    def set_contact(self, index: int, geom: int, on: bool) -> None:
        """Trajectory ``index``'s geom ``geom`` collides with nothing (off) or with what MuJoCo's filter lets it
        (on again), through that trajectory's own collision filters (``SceneGraph.collision_filter_manager(context)``);
        switching twice either way changes nothing."""
        if on == ((index, geom) not in self._released) or geom not in self._scene.geometries:
            return
        scene = self._scene
        manager = scene.scene_graph.collision_filter_manager(
            scene.scene_graph.GetMyMutableContextFromRoot(self._contexts[index]))
        pair = (GeometrySet(scene.geometries[geom]), GeometrySet(scene.partners[geom]))
        declaration = CollisionFilterDeclaration()
        manager.Apply(declaration.AllowBetween(*pair) if on else declaration.ExcludeBetween(*pair))
        if on:
            del self._released[index, geom]
        else:
            self._released[index, geom] = 0.0

    def advance(self, index: int, state: np.ndarray, seconds: float, ctrl: np.ndarray | None = None) -> np.ndarray:
        raise NotImplementedError("backend=drake: fractional steps (a discrete plant's step is fixed)")


def open_batch(model: mujoco.MjModel, state0: np.ndarray, *, precision: str, size: int = 0,
               approximation: str = "sap", hydroelastic: bool = False) -> DrakeBatch:
    """:class:`DrakeBatch` over ``model`` from ``state0`` (B, nstate) (double precision only; no padding: nothing
    compiles per shape)."""
    del precision, size
    return DrakeBatch(model, state0, approximation=approximation, hydroelastic=hydroelastic)
