"""The scenario's compiled MuJoCo model as a discrete Drake ``MultibodyPlant``: the same bodies, inertias, joints,
collision geometry, friction and gravity, and a compliant contact equivalent to MuJoCo's soft contact.

What is translated (anything else is refused with one line naming it, before any simulation):

- bodies: mass, centre of mass and rotational inertia (MuJoCo's principal axes ``body_iquat``/``body_inertia``);
- joints: hinge and slide (several in one body become a chain through massless bodies, composed in MuJoCo's order,
  each about its anchor ``jnt_pos`` along its ``jnt_axis``), free (Drake's quaternion floating joint), none (welded);
- geoms that collide (``contype``/``conaffinity`` not both 0): plane (a half space), sphere, capsule, cylinder, box,
  ellipsoid; MuJoCo's collision filter (a pair collides when the type bits of one meet the affinity bits of the other,
  never within one body or between a body and its parent) becomes Drake's collision filter declarations;
- friction: one coefficient, as every scenario gives all its colliding geoms (MuJoCo takes the larger of two geoms'
  coefficients, Drake their harmonic mean: the two agree only for equal ones, so unequal ones are refused);
- contact: MuJoCo's solref (time constant tc, damping ratio zeta) makes the penetration a spring-damper of natural
  frequency omega = 1/(tc zeta) and damping ratio zeta (MuJoCo docs, "Solver parameters"). Drake's compliant point
  contact gets the stiffness k = M omega^2 (M: the moving mass) and the dissipation of the same damping at the
  static penetration g/omega^2: SAP's linear Kelvin-Voigt relaxation time 2 zeta/omega, Hunt-Crossley's (TAMSI,
  Lagged, Similar) 2 zeta omega/g. Hydroelastic contact takes the modulus k / (the foot's area scale) on compliant
  spheres against a rigid half space. (MuJoCo's impedance ``solimp`` has no counterpart: at MuJoCo's rest its
  penetration is (1 - d)/d of the spring's, so a resting body sinks deeper on Drake where d is far below 1.)
- equality constraints: a joint held at its reference, alone in its body, is welded there (:func:`held_joints`);
- actuators: none; a model with a nonzero one is refused, a zero-force one (the seam's self-test model has one) is
  left out.

The state maps by joint: MuJoCo's ``qpos``/``qvel`` of each joint to Drake's q/v of the same joint (a free joint's
quaternion and its body-frame angular velocity to Drake's (quaternion, position) and world-frame velocities).
"""

from __future__ import annotations

import contextlib
import logging
from collections.abc import Iterator
from dataclasses import dataclass

import mujoco
import numpy as np
from pydrake.common.eigen_geometry import Quaternion
from pydrake.geometry import (
    AddCompliantHydroelasticProperties,
    AddContactMaterial,
    AddRigidHydroelasticProperties,
    Box,
    Capsule,
    CollisionFilterDeclaration,
    Cylinder,
    Ellipsoid,
    GeometryId,
    GeometrySet,
    HalfSpace,
    ProximityProperties,
    SceneGraph,
    Shape,
    Sphere,
)
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import (
    AddMultibodyPlantSceneGraph,
    ContactModel,
    CoulombFriction,
    DiscreteContactApproximation,
    MultibodyPlant,
)
from pydrake.multibody.tree import (
    FixedOffsetFrame,
    PrismaticJoint,
    QuaternionFloatingJoint,
    RevoluteJoint,
    RigidBody,
    RotationalInertia,
    SpatialInertia,
)
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.primitives import LogVectorOutput, VectorLogSink

from mjpoincare.core.params import ParameterError

#: The discrete contact approximations a run may ask for (the ``drake_approximation`` setting).
APPROXIMATIONS = {"sap": DiscreteContactApproximation.kSap, "tamsi": DiscreteContactApproximation.kTamsi,
                  "lagged": DiscreteContactApproximation.kLagged, "similar": DiscreteContactApproximation.kSimilar}
#: Hydroelastic resolution hint of a compliant sphere, as a fraction of its radius.
RESOLUTION = 0.5


@dataclass(frozen=True)
class JointMap:
    """Where one MuJoCo joint's coordinates sit in MuJoCo's state and in Drake's: ``kind`` (a ``mjtJoint``),
    MuJoCo's ``qpos``/``dof`` addresses and Drake's q/v starts."""

    kind: int
    qpos: int
    dof: int
    q: int
    v: int


@dataclass(frozen=True)
class DrakeScene:
    """The plant, its diagram and logger, and the maps between MuJoCo's state and Drake's.

    Attributes:
        diagram: plant + scene graph + a state logger at every step.
        plant: the discrete ``MultibodyPlant`` (time step = MuJoCo's).
        scene_graph: its ``SceneGraph`` (collision geometry and filters).
        logger: the ``VectorLogSink`` of the plant's state (q, v), one sample per step.
        joints: each MuJoCo joint's map.
        nq, nv: Drake's position and velocity counts.
        geometries: MuJoCo geom index -> Drake geometry id (the colliding ones).
        friction: the friction coefficient every colliding geom has.
        partners: MuJoCo geom index -> the Drake geometries it may collide with (MuJoCo's filter).
    """

    diagram: Diagram
    plant: MultibodyPlant
    scene_graph: SceneGraph
    logger: VectorLogSink
    joints: tuple[JointMap, ...]
    nq: int
    nv: int
    geometries: dict[int, GeometryId]
    friction: float
    partners: dict[int, list[GeometryId]]


def _pose(pos: np.ndarray, quat: np.ndarray) -> RigidTransform:
    """MuJoCo's (pos, quat w x y z) as a Drake transform."""
    return RigidTransform(RotationMatrix(Quaternion(np.asarray(quat, float) / np.linalg.norm(quat))),
                          np.asarray(pos, float))


def _inertia(model: mujoco.MjModel, body: int) -> SpatialInertia:
    """Body ``body``'s spatial inertia about its origin, in its frame."""
    rotation = RotationMatrix(Quaternion(model.body_iquat[body] / np.linalg.norm(model.body_iquat[body]))).matrix()
    central = rotation @ np.diag(model.body_inertia[body]) @ rotation.T
    return SpatialInertia.MakeFromCentralInertia(
        float(model.body_mass[body]), np.asarray(model.body_ipos[body], float),
        RotationalInertia(central[0, 0], central[1, 1], central[2, 2], central[0, 1], central[0, 2], central[1, 2]))


def _shape(model: mujoco.MjModel, geom: int) -> Shape:
    """Geom ``geom``'s shape in Drake's terms (ParameterError for a type with no counterpart)."""
    kind, size = int(model.geom_type[geom]), model.geom_size[geom]
    shapes = {int(mujoco.mjtGeom.mjGEOM_PLANE): lambda: HalfSpace(),
              int(mujoco.mjtGeom.mjGEOM_SPHERE): lambda: Sphere(size[0]),
              int(mujoco.mjtGeom.mjGEOM_CAPSULE): lambda: Capsule(size[0], 2 * size[1]),
              int(mujoco.mjtGeom.mjGEOM_CYLINDER): lambda: Cylinder(size[0], 2 * size[1]),
              int(mujoco.mjtGeom.mjGEOM_BOX): lambda: Box(*(2 * size)),
              int(mujoco.mjtGeom.mjGEOM_ELLIPSOID): lambda: Ellipsoid(*size)}
    if kind not in shapes:
        raise ParameterError(f"backend=drake cannot represent geom {model.geom(geom).name!r} of type "
                             f"{mujoco.mjtGeom(kind).name}")
    return shapes[kind]()


def held_joints(model: mujoco.MjModel) -> dict[int, int]:
    """Equality index -> joint for each equality that holds one joint at its reference, alone in its body: the
    translation welds that body at its reference pose where the hold is on from the start (MuJoCo's soft hold made
    rigid; it cannot be switched: drake 1.51.1 crashes with a weld constraint on a one-degree-of-freedom body, and with
    a locked joint once a contact is active, docs/engines.md). Any other equality is refused (one line)."""
    held = {}
    for eq in range(model.neq):
        joint = int(model.eq_obj1id[eq])
        alone = int(model.body_jntnum[model.jnt_bodyid[joint]]) == 1
        if not (int(model.eq_type[eq]) == int(mujoco.mjtEq.mjEQ_JOINT) and int(model.eq_obj2id[eq]) < 0
                and model.eq_data[eq, 0] == 0.0 and alone):
            raise ParameterError(f"backend=drake has no counterpart of equality constraint "
                                 f"{model.equality(eq).name or eq!r} (only a joint held at its reference, alone in "
                                 "its body)")
        held[eq] = joint
    return held


def _refuse_unsupported(model: mujoco.MjModel) -> None:
    """One line naming the first model feature the translation has no counterpart for."""
    held_joints(model)
    moving = [i for i in range(model.nu) if np.any(model.actuator_gainprm[i]) or np.any(model.actuator_biasprm[i])]
    if moving:
        raise ParameterError(f"backend=drake has no counterpart of MuJoCo's actuators (actuator "
                             f"{model.actuator(moving[0]).name!r}); a zero-force one is left out")
    for joint in range(model.njnt):
        if int(model.jnt_type[joint]) == int(mujoco.mjtJoint.mjJNT_BALL):
            raise ParameterError(f"backend=drake has no counterpart of ball joint {model.joint(joint).name!r}")
        if int(model.jnt_type[joint]) in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE)) \
                and model.qpos0[model.jnt_qposadr[joint]] != 0.0:
            raise ParameterError(f"backend=drake needs joint {model.joint(joint).name!r} at its reference at 0")


def _collides(model: mujoco.MjModel, geom: int) -> bool:
    return bool(model.geom_contype[geom] or model.geom_conaffinity[geom])


def _pair_collides(model: mujoco.MjModel, a: int, b: int) -> bool:
    """MuJoCo's filter: the type bits of one geom meet the affinity bits of the other, and the geoms are neither in
    one body nor in a body and its parent (MuJoCo docs, "Collision detection")."""
    body_a, body_b = int(model.geom_bodyid[a]), int(model.geom_bodyid[b])
    bits = (model.geom_contype[a] & model.geom_conaffinity[b]) or (model.geom_contype[b] & model.geom_conaffinity[a])
    related = body_a == body_b or model.body_parentid[body_a] == body_b or model.body_parentid[body_b] == body_a
    return bool(bits) and not (related and body_a != 0 and body_b != 0)


def _filters(geometries: dict[int, GeometryId], partners: dict[int, list[GeometryId]]) -> CollisionFilterDeclaration:
    """Exclude every pair of ``geometries`` that is not among each other's ``partners`` (MuJoCo's filter)."""
    declaration = CollisionFilterDeclaration()
    ids = list(geometries)
    for i, a in enumerate(ids):
        for b in ids[i + 1:]:
            if geometries[b] not in partners[a]:
                declaration.ExcludeBetween(GeometrySet(geometries[a]), GeometrySet(geometries[b]))
    return declaration


def contact_properties(model: mujoco.MjModel, geom: int, friction: float, approximation: str, hydroelastic: bool,
                       mass: float, gravity: float) -> ProximityProperties:
    """Geom ``geom``'s compliant contact (module docstring) with Coulomb coefficient ``friction``."""
    timeconst, dampratio = (float(v) for v in model.geom_solref[geom])
    if timeconst <= 0:
        raise ParameterError("backend=drake needs solref as (time constant, damping ratio)")
    omega = 1.0 / (timeconst * dampratio)
    stiffness = mass * omega**2
    props = ProximityProperties()
    coulomb = CoulombFriction(friction, friction)
    if approximation == "sap":
        AddContactMaterial(point_stiffness=stiffness, friction=coulomb, properties=props)
        props.AddProperty("material", "relaxation_time", 2.0 * dampratio / omega)
    else:
        AddContactMaterial(dissipation=2.0 * dampratio * omega / gravity, point_stiffness=stiffness, friction=coulomb,
                           properties=props)
    if hydroelastic:
        if int(model.geom_type[geom]) == int(mujoco.mjtGeom.mjGEOM_PLANE):
            AddRigidHydroelasticProperties(properties=props)
        else:
            radius = float(model.geom_size[geom][0])
            AddCompliantHydroelasticProperties(resolution_hint=RESOLUTION * radius,
                                               hydroelastic_modulus=stiffness / radius, properties=props)
    return props


class _NotDeformable(logging.Filter):
    """Drops Drake's note that a rigid half space takes no part in deformable contact (there is none here)."""

    def filter(self, record: logging.LogRecord) -> bool:
        return "deformable contact" not in record.getMessage()


@contextlib.contextmanager
def no_deformable_note() -> Iterator[None]:
    """Drop Drake's note on half spaces and deformable contact (logged when a plant's first context is made) inside
    the block; the filter is removed afterwards."""
    quiet = _NotDeformable()
    logging.getLogger("drake").addFilter(quiet)
    try:
        yield
    finally:
        logging.getLogger("drake").removeFilter(quiet)


def build_scene(model: mujoco.MjModel, *, approximation: str = "sap", hydroelastic: bool = False) -> DrakeScene:
    """The model as a discrete Drake plant (module docstring); ParameterError for what it cannot represent."""
    _refuse_unsupported(model)
    colliding = [g for g in range(model.ngeom) if _collides(model, g)]
    frictions = {float(model.geom_friction[g, 0]) for g in colliding}
    if len(frictions) > 1:
        raise ParameterError(f"backend=drake needs one friction coefficient on every colliding geom (got "
                             f"{sorted(frictions)}): Drake combines two as their harmonic mean, MuJoCo takes the "
                             "larger")
    friction = frictions.pop() if frictions else 1.0
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=float(model.opt.timestep))
    plant.set_discrete_contact_approximation(APPROXIMATIONS[approximation])
    plant.set_contact_model(ContactModel.kHydroelasticWithFallback if hydroelastic else ContactModel.kPoint)
    bodies: dict[int, RigidBody] = {0: plant.world_body()}
    chain: list[tuple[int, object]] = []
    held = held_joints(model)
    welded = {int(model.jnt_bodyid[j]) for eq, j in held.items() if model.eq_active0[eq]}
    for body in range(1, model.nbody):
        parent = bodies[int(model.body_parentid[body])]
        x_parent_body = _pose(model.body_pos[body], model.body_quat[body])
        name = model.body(body).name or f"body{body}"
        first, count = int(model.body_jntadr[body]), int(model.body_jntnum[body])
        links = [plant.AddRigidBody(f"{name}__joint{k}", SpatialInertia.Zero()) for k in range(max(0, count - 1))]
        rigid = plant.AddRigidBody(name, _inertia(model, body))
        bodies[body] = rigid
        if count == 0 or body in welded:
            plant.WeldFrames(parent.body_frame(), rigid.body_frame(), x_parent_body)
            continue
        outboard = [*links, rigid]
        inboard = parent
        for k in range(count):
            joint = first + k
            kind = int(model.jnt_type[joint])
            frame_parent = x_parent_body if k == 0 else RigidTransform()
            child = outboard[k]
            jname = model.joint(joint).name or f"joint{joint}"
            if kind == int(mujoco.mjtJoint.mjJNT_FREE):
                added = plant.AddJoint(QuaternionFloatingJoint(jname, inboard.body_frame(), child.body_frame()))
            else:
                anchor = RigidTransform(np.asarray(model.jnt_pos[joint], float))
                f_parent = plant.AddFrame(FixedOffsetFrame(f"{jname}__F", inboard.body_frame(),
                                                           frame_parent.multiply(anchor)))
                f_child = plant.AddFrame(FixedOffsetFrame(f"{jname}__M", child.body_frame(), anchor))
                cls = RevoluteJoint if kind == int(mujoco.mjtJoint.mjJNT_HINGE) else PrismaticJoint
                added = plant.AddJoint(cls(jname, f_parent, f_child, np.asarray(model.jnt_axis[joint], float)))
            chain.append((joint, added))
            inboard = child
    gravity = float(np.linalg.norm(model.opt.gravity))
    moving = float(np.sum(model.body_mass[1:]))
    geometries: dict[int, GeometryId] = {}
    for geom in colliding:
        body = bodies[int(model.geom_bodyid[geom])]
        props = contact_properties(model, geom, friction, approximation, hydroelastic, moving, gravity)
        geometries[geom] = plant.RegisterCollisionGeometry(
            body, _pose(model.geom_pos[geom], model.geom_quat[geom]), _shape(model, geom),
            model.geom(geom).name or f"geom{geom}", props)
    plant.mutable_gravity_field().set_gravity_vector(np.asarray(model.opt.gravity, float))
    plant.Finalize()
    partners = {g: [geometries[h] for h in geometries if h != g and _pair_collides(model, g, h)] for g in geometries}
    scene_graph.collision_filter_manager().Apply(_filters(geometries, partners))
    logger = LogVectorOutput(plant.get_state_output_port(), builder, publish_period=float(model.opt.timestep))
    diagram = builder.Build()
    joints = tuple(JointMap(kind=int(model.jnt_type[j]), qpos=int(model.jnt_qposadr[j]),
                            dof=int(model.jnt_dofadr[j]), q=int(added.position_start()),
                            v=int(added.velocity_start())) for j, added in chain)
    return DrakeScene(diagram=diagram, plant=plant, scene_graph=scene_graph, logger=logger, joints=joints,
                      nq=plant.num_positions(), nv=plant.num_velocities(), geometries=geometries, friction=friction,
                      partners=partners)


def _rotation(quat: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of unit quaternions (..., 4) (w, x, y, z)."""
    w, x, y, z = (quat[..., i] for i in range(4))
    return np.stack([np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
                     np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
                     np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)], -2)


def to_drake(scene: DrakeScene, model: mujoco.MjModel, states: np.ndarray) -> np.ndarray:
    """Drake states (B, nq + nv) of MuJoCo full-physics states (B, nstate)."""
    qpos, qvel = states[:, 1: 1 + model.nq], states[:, 1 + model.nq: 1 + model.nq + model.nv]
    out = np.zeros((states.shape[0], scene.nq + scene.nv))
    for j in scene.joints:
        v = scene.nq + j.v
        if j.kind == int(mujoco.mjtJoint.mjJNT_FREE):
            quat = qpos[:, j.qpos + 3: j.qpos + 7]
            out[:, j.q: j.q + 4] = quat
            out[:, j.q + 4: j.q + 7] = qpos[:, j.qpos: j.qpos + 3]
            out[:, v: v + 3] = np.einsum("bij,bj->bi", _rotation(quat), qvel[:, j.dof + 3: j.dof + 6])
            out[:, v + 3: v + 6] = qvel[:, j.dof: j.dof + 3]
        else:
            out[:, j.q] = qpos[:, j.qpos]
            out[:, v] = qvel[:, j.dof]
    return out


def to_mujoco(scene: DrakeScene, model: mujoco.MjModel, times: np.ndarray, x: np.ndarray, nstate: int) -> np.ndarray:
    """MuJoCo full-physics states (..., nstate) of Drake states ``x`` (..., nq + nv) at ``times`` (...)."""
    out = np.zeros((*x.shape[:-1], nstate))
    out[..., 0] = times
    qpos, qvel = out[..., 1: 1 + model.nq], out[..., 1 + model.nq: 1 + model.nq + model.nv]
    for j in scene.joints:
        v = scene.nq + j.v
        if j.kind == int(mujoco.mjtJoint.mjJNT_FREE):
            quat = x[..., j.q: j.q + 4]
            qpos[..., j.qpos + 3: j.qpos + 7] = quat
            qpos[..., j.qpos: j.qpos + 3] = x[..., j.q + 4: j.q + 7]
            qvel[..., j.dof + 3: j.dof + 6] = np.einsum("...ji,...j->...i", _rotation(quat), x[..., v: v + 3])
            qvel[..., j.dof: j.dof + 3] = x[..., v + 3: v + 6]
        else:
            qpos[..., j.qpos] = x[..., j.q]
            qvel[..., j.dof] = x[..., v]
    return out
