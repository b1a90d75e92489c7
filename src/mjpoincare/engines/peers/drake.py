"""Drake as an outside peer: the hybrid rimless wheel and compass gait of ``pydrake.examples``.

Source: Drake's ``examples/rimless_wheel`` and ``examples/compass_gait`` (classes ``RimlessWheel`` and
``CompassGait``, after R. Tedrake's *Underactuated Robotics*, "Simple models of walking"), simulated by
``pydrake.systems.analysis.Simulator``: the continuous dynamics by an error-controlled integrator, each impact by
Drake's own witness function and reset map.

* Drake's rimless wheel is the point-mass wheel of 003 Sec. 3: stance theta'' = (g/l) sin theta (003 eq 3.2) and
  impact omega+ = cos(2 alpha) omega- (003 eq 3.11), i.e. kappa = 0 in 002's terms (002 eqs 12, 14).
* Drake's compass gait is the biped of 003 Ch. 4 and Goswami et al. (1998): EoM 003 eq 4.5 (hip torque through
  B = (-1, 1)), heel-strike guard max(2 gamma - theta_st - theta_sw, theta_sw - theta_st) (003 eq 4.6, scuffing
  ignored), plastic impact at the new foot with the legs relabelled (003 eqs 4.7, 4.15-4.17; Drake writes it as a
  floating-base impulse), state (stance, swing, stancedot, swingdot) = 003's (theta_st, theta_sw, dtheta_st,
  dtheta_sw).

The step map is Drake's simulation from a post-impact state to its next impact: a monitor stops the simulator once
the guard has crossed 0 (Drake's witness has then located the impact in time to 0.01 x accuracy x 1 s) and
``Simulator.AdvancePendingEvents`` applies Drake's reset. The gait is a root of that map (MINPACK hybrd) and its
multipliers are central finite differences of it. The suite's theory supplies only the root search's starting guess.

Drake's models are given as the suite's theory parameters (:class:`~mjpoincare.analysis.theory.rimless_wheel.
RimlessWheel`, :class:`~mjpoincare.analysis.theory.compass_biped.CompassBiped`); what they cannot represent is refused
with ValueError: a hub with inertia (gyration > 0) and an ankle torque. mu enters neither model: both assume a
sticking stance foot. The scenarios map their parameters onto these models and say so in their ``peers`` field
(:class:`mjpoincare.engines.peers.Peer`).
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import fsolve

from mjpoincare.analysis.eigenvalues import sort_eigenvalues
from mjpoincare.analysis.theory import compass_biped as compass_theory
from mjpoincare.analysis.theory import rimless_wheel as rimless_theory
from mjpoincare.analysis.theory.shooting import central_jacobian
from mjpoincare.core.params import ParameterError, Values
from mjpoincare.engines.peers import Peer, PeerValues

NAME = "drake"
INSTALL = "pip install 'mjpoincare[peers]'"
SCHEME = "runge_kutta5"
#: Target accuracy of the reference run (Drake's integrator error control and witness isolation).
REFERENCE_ACCURACY = 1e-12
#: Longest a step may take, in units of sqrt(l/g), before the gait counts as lost (the theory's MAX_SWING).
MAX_STEP = 10.0
#: Largest integrator step, in units of sqrt(l/g): keeps a guard's sign change visible at loose accuracies.
MAX_STEP_SIZE = 0.1
#: The root search starts this fraction off the suite's gait (each section coordinate), so that the answer is
#: Drake's root, reached by the search, not the guess it was handed.
GUESS_OFFSET = 0.05
#: The root search fails if |P(z) - z| at its answer exceeds this many times the accuracy.
RESIDUAL_FACTOR = 100.0


def available() -> bool:
    """Whether pydrake is importable (the optional extra ``mjpoincare[peers]``)."""
    return importlib.util.find_spec("pydrake") is not None


def require() -> None:
    """ParameterError naming the extra when pydrake is missing."""
    if not available():
        raise ParameterError(f"--peer drake needs pydrake: {INSTALL}")


def version() -> str:
    """The installed ``drake`` distribution's version ("unknown" for a pydrake not installed from the wheel)."""
    try:
        return importlib.metadata.version("drake")
    except importlib.metadata.PackageNotFoundError:
        return "unknown"


@dataclass(frozen=True)
class RimlessWheelGait:
    """Drake's rolling gait (003 eq 3.13 fixed point): post-impact speed ``omega_post_impact`` (rad/s), the return
    map's ``multiplier`` d omega+_{k+1}/d omega+_k there (central difference), ``impact_coefficient`` omega+/omega-
    across Drake's reset, ``step_period`` (s); the integrator ``accuracy`` and the search's ``wall_s`` (s)."""

    omega_post_impact: float
    multiplier: float
    impact_coefficient: float
    step_period: float
    accuracy: float
    wall_s: float


@dataclass(frozen=True)
class CompassGaitCycle:
    """Drake's period-1 gait (003 eq 4.18 fixed point): post-impact ``fixed_point`` (theta_st, theta_sw, dtheta_st,
    dtheta_sw), the 3 ``eigenvalues`` of the post-impact section map (central differences; sorted as the theory's),
    ``step_period`` (s), ``step_length`` (m, Drake's stance-toe advance); the integrator ``accuracy`` and the
    search's ``wall_s`` (s)."""

    fixed_point: tuple[float, ...]
    eigenvalues: tuple[complex, ...]
    step_period: float
    step_length: float
    accuracy: float
    wall_s: float


@dataclass(frozen=True)
class _Impact:
    """One simulated step: continuous state just before and just after Drake's reset, the step's duration (s) and
    the stance toe's advance along the slope (m)."""

    x_minus: NDArray[np.float64]
    x_plus: NDArray[np.float64]
    period: float
    advance: float


class _StepMap:
    """Drake's simulation of one step from a post-impact state: run until ``guard`` (Drake's witness, evaluated on
    the continuous state) has crossed 0, then apply Drake's pending reset. One Simulator serves every call."""

    def __init__(self, simulator: Any, guard: Callable[[NDArray[np.float64]], float], horizon: float) -> None:
        from pydrake.systems.framework import EventStatus

        self.simulator, self.guard, self.horizon = simulator, guard, horizon
        self._status = EventStatus
        self._struck = False
        simulator.set_monitor(self._monitor)

    def _monitor(self, context: Any) -> Any:
        if self.guard(context.get_continuous_state_vector().CopyToVector()) > 0.0:
            return self._status.DidNothing()
        self._struck = True
        return self._status.ReachedTermination(self.simulator.get_system(), "impact")

    def __call__(self, x_plus: ArrayLike) -> _Impact:
        context = self.simulator.get_mutable_context()
        context.SetTime(0.0)
        context.SetContinuousState(np.asarray(x_plus, dtype=float))
        context.SetDiscreteState([0.0])  # the stance toe at the origin
        self._struck = False
        self.simulator.Initialize()
        self.simulator.AdvanceTo(self.horizon)
        if not self._struck:
            raise RuntimeError(f"no impact within {self.horizon:.3g} s from x = {np.asarray(x_plus)!r} (gait lost)")
        x_minus = context.get_continuous_state_vector().CopyToVector()
        period = context.get_time()
        self.simulator.AdvancePendingEvents()
        advance = abs(float(context.get_discrete_state_vector().GetAtIndex(0)))
        if advance == 0.0:
            raise RuntimeError(f"Drake's impact witness did not fire at t = {period!r} s")
        return _Impact(x_minus, context.get_continuous_state_vector().CopyToVector(), period, advance)


def _import_drake() -> None:
    """Import pydrake's modules up front, so that the wall times exclude the one-time import (about a second)."""
    import pydrake.examples
    import pydrake.systems.analysis  # noqa: F401


def _simulator(system: Any, accuracy: float, scheme: str, time_scale: float) -> Any:
    """A Simulator with Drake's integrator ``scheme`` at target ``accuracy``."""
    from pydrake.systems.analysis import ResetIntegratorFromFlags, Simulator

    simulator = Simulator(system)
    integrator = ResetIntegratorFromFlags(simulator, scheme, MAX_STEP_SIZE * time_scale)
    integrator.set_target_accuracy(accuracy)  # Context.SetAccuracy alone leaves the integrator at its default
    simulator.get_mutable_context().SetAccuracy(accuracy)  # witness isolation window 0.01 x accuracy x 1 s
    return simulator


def _rimless_step_map(w: rimless_theory.RimlessWheel, accuracy: float, scheme: str) -> tuple[_StepMap, float, float]:
    """Drake's RimlessWheel with the parameters of ``w``: its step map, its slope and alpha."""
    from pydrake.examples import RimlessWheel

    wheel = RimlessWheel()
    length, gravity = w.leg_length, w.gravity
    simulator = _simulator(wheel, accuracy, scheme, math.sqrt(length / gravity))
    params = simulator.get_mutable_context().get_mutable_numeric_parameter(0)
    params.set_mass(w.mass)
    params.set_length(length)
    params.set_gravity(gravity)
    params.set_number_of_spokes(float(w.spokes))
    params.set_slope(w.slope)
    slope, alpha = params.slope(), wheel.calc_alpha(params)

    def step_forward(x: NDArray[np.float64]) -> float:  # Drake's "step forward" witness
        return slope + alpha - float(x[0])

    return _StepMap(simulator, step_forward, MAX_STEP * math.sqrt(length / gravity)), slope, alpha


def _compass_step_map(bp: compass_theory.CompassBiped, accuracy: float, scheme: str) -> tuple[_StepMap, float]:
    """Drake's CompassGait with the parameters of ``bp`` (hip torque as a fixed input): its step map and slope."""
    from pydrake.examples import CompassGait

    gait = CompassGait()
    length, gravity = bp.a + bp.b, bp.gravity
    simulator = _simulator(gait, accuracy, scheme, math.sqrt(length / gravity))
    context = simulator.get_mutable_context()
    params = context.get_mutable_numeric_parameter(0)
    params.set_mass_hip(bp.m_h)
    params.set_mass_leg(bp.m_l)
    params.set_length_leg(length)
    params.set_center_of_mass_leg(bp.b)  # Drake measures the leg's mass from the hip: 003's b
    params.set_gravity(gravity)
    params.set_slope(bp.slope)
    gait.get_input_port(0).FixValue(context, [bp.tau_hip])
    slope = params.slope()

    def foot_collision(x: NDArray[np.float64]) -> float:  # Drake's "foot collision" witness
        return max(2.0 * slope - float(x[0]) - float(x[1]), float(x[1]) - float(x[0]))

    return _StepMap(simulator, foot_collision, MAX_STEP * math.sqrt(length / gravity)), slope


def _root(section_map: Callable[[NDArray[np.float64]], NDArray[np.float64]], guess: ArrayLike,
          accuracy: float) -> NDArray[np.float64]:
    """Fixed point of ``section_map`` by MINPACK hybrd, judged by its residual (at most RESIDUAL_FACTOR x accuracy):
    the map carries the integrator's error, so hybrd may stop at that noise floor and report slow progress."""

    def gap(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return section_map(z) - z

    z = np.asarray(fsolve(gap, np.atleast_1d(np.asarray(guess, dtype=float)), xtol=max(0.1 * accuracy, 1e-14),
                          full_output=True)[0])
    residual = float(np.max(np.abs(gap(z))))
    if residual > RESIDUAL_FACTOR * accuracy:
        raise RuntimeError(f"Drake's step map has no fixed point near {guess!r} (residual {residual:.3g})")
    return z


def difference_step(accuracy: float) -> float:
    """Central-difference step for the multipliers: 0.1 accuracy^(1/3) balances the map's noise (~accuracy/step)
    against the truncation (~step^2; its coefficient measured ~3e2 for the compass gait's map), capped at 1e-2;
    1e-5 at the reference accuracy."""
    return min(1e-2, 0.1 * accuracy ** (1.0 / 3.0))


def rimless_wheel(w: rimless_theory.RimlessWheel, guess: float | None = None, accuracy: float = REFERENCE_ACCURACY,
                  scheme: str = SCHEME) -> RimlessWheelGait:
    """Drake's rolling gait of the rimless wheel ``w``.

    Args:
        w: the wheel; its hub must be a point mass (gyration 0, Drake's model), else ValueError.
        guess: the starting post-impact speed of the root search (default: GUESS_OFFSET above the suite's theory,
            003 eq 3.13). The section is 003's post-impact one, theta = gamma - alpha, omega+ > 0.
        accuracy: the integrator's target accuracy.
        scheme: Drake's integration scheme.

    Returns:
        The gait (:class:`RimlessWheelGait`).
    """
    if w.gyration != 0.0:
        raise ValueError(f"Drake's RimlessWheel has a point-mass hub (got gyration {w.gyration})")
    if guess is None:
        guess = (1.0 + GUESS_OFFSET) * rimless_theory.rolling_fixed_point(w)
    _import_drake()
    start = time.perf_counter()
    step_map, slope, alpha = _rimless_step_map(w, accuracy, scheme)

    def section_map(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return step_map([slope - alpha, float(z[0])]).x_plus[1:]

    omega = float(_root(section_map, guess, accuracy)[0])
    multiplier = float(central_jacobian(section_map, np.array([omega]), difference_step(accuracy))[0, 0])
    impact = step_map([slope - alpha, omega])
    return RimlessWheelGait(omega_post_impact=omega, multiplier=multiplier,
                            impact_coefficient=float(impact.x_plus[1] / impact.x_minus[1]),
                            step_period=impact.period, accuracy=accuracy, wall_s=time.perf_counter() - start)


def compass_gait(bp: compass_theory.CompassBiped, guess: ArrayLike | None = None,
                 accuracy: float = REFERENCE_ACCURACY, scheme: str = SCHEME) -> CompassGaitCycle:
    """Drake's period-1 gait of the compass biped ``bp``.

    Args:
        bp: the biped; it must have no ankle torque (Drake's model), else ValueError.
        guess: the starting post-impact state x, (4,) (default: GUESS_OFFSET off the suite's theory, 003 eq 4.18 by
            Newton shooting). The section is 003's post-impact one, z = (theta_st, dtheta_st, dtheta_sw) with
            theta_sw = 2 gamma - theta_st (003 eq 4.6), as the theory's; the eigenvalues are its multipliers.
        accuracy: the integrator's target accuracy.
        scheme: Drake's integration scheme.

    Returns:
        The cycle (:class:`CompassGaitCycle`).
    """
    if bp.tau_ankle != 0.0:
        raise ValueError(f"Drake's CompassGait has no ankle torque (got tau_ankle {bp.tau_ankle})")
    x0 = (1.0 + GUESS_OFFSET) * compass_theory.fixed_point(bp) if guess is None else np.asarray(guess, float)
    _import_drake()
    start = time.perf_counter()
    step_map, slope = _compass_step_map(bp, accuracy, scheme)

    def state(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.array([z[0], 2.0 * slope - z[0], z[1], z[2]])

    def section_map(z: NDArray[np.float64]) -> NDArray[np.float64]:
        return step_map(state(z)).x_plus[[0, 2, 3]]

    z = _root(section_map, x0[[0, 2, 3]], accuracy)
    jac = central_jacobian(section_map, z, difference_step(accuracy))
    lam = sort_eigenvalues(np.linalg.eigvals(jac).astype(complex))
    impact = step_map(state(z))
    return CompassGaitCycle(fixed_point=tuple(float(v) for v in state(z)),
                            eigenvalues=tuple(complex(v) for v in lam), step_period=impact.period,
                            step_length=impact.advance, accuracy=accuracy, wall_s=time.perf_counter() - start)


def peer(*, check_params: Callable[[Values], None], values: Callable[[Values, float], PeerValues],
         model_note: Callable[[Values], str], bench_accuracies: tuple[float, ...], bench_metrics: dict[str, str],
         bench_model: str, agreement_cases: tuple[dict[str, str], ...],
         model_shift: Callable[[Values, dict[str, tuple[Any, Any]]], str] | None = None) -> Peer:
    """Drake as a scenario's :class:`~mjpoincare.engines.peers.Peer`: the scenario's mapping of its parameters onto
    Drake's model (the arguments, as the record's fields) with Drake's name, version, scheme, install line and reference
    accuracy."""
    return Peer(name=NAME, version=version, scheme=SCHEME, install=INSTALL, reference_accuracy=REFERENCE_ACCURACY,
                check_params=check_params, values=values, model_note=model_note, bench_accuracies=bench_accuracies,
                bench_metrics=bench_metrics, bench_model=bench_model, agreement_cases=agreement_cases,
                model_shift=model_shift)
