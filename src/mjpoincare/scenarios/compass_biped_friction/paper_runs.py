"""The MuJoCo runs behind the compass biped's results of 002 (Gamus & Or 2015, Secs. 4-5) that its checks do not read
directly: readers of the validation's fitted map and actuator work, the figures' points over mu (Figs 4.2(b), 5.2(a-c))
with the theory's curves from the suite's continuation, the stability-loss brackets, the heel strike's impulse ratio
(002 Sec. 4.1, Fig. 4.1(c)) measured from the momentum jump of the recorded rows, and Gait II's energy split (002 Sec.
5) from their mechanical energy and actuator work.

Every MuJoCo value comes from the scenario's own validation (:func:`validated`, through the command's
:class:`~mjpoincare.scenarios.paper_results.Runner`: its batched ``event_rollout`` runs and fit) or, for the impulse
ratio and Gait II's energy split, from the scenario's gait run from the fixed point (:func:`impulse_ratio`,
:func:`energy_split`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np

from mjpoincare.analysis.theory import compass_biped_friction as theory
from mjpoincare.analysis.theory.compass_biped_friction.stance_measurements import stance_rows
from mjpoincare.scenarios.compass_biped_friction.gait_choice import gait
from mjpoincare.scenarios.compass_biped_friction.start_design import SETTLE
from mjpoincare.scenarios.compass_biped_friction.walk import run_gait
from mjpoincare.scenarios.paper_results import Reading, Runner, check_reader, largest_multiplier_reader

if TYPE_CHECKING:
    from mjpoincare.core.result import Result

#: The theory's curves are continued on this mu grid and interpolated between (002 Figs 4.2(b), 5.2).
THEORY_STEP = 0.0025
#: The theory's name of each of the scenario's gaits (its curve continues from the highest-mu seed of
#: :data:`theory.GAIT_SEEDS`).
_CURVE_GAIT = {"a": "A", "b": "B", "c": "C", "i": "I", "ii": "II", "iii": "III"}
#: The momentum is fitted this long on each side of the heel strike (s), skipping this long around it: the soft
#: impact's window (a few contact time constants) and, after it, the settling of the new stance foot.
IMPULSE_FIT = 0.03
IMPULSE_SKIP = 0.004
#: Heel strikes of trajectory 0 read for the impulse ratio and the energy split: those after the start design's settling
#: steps.
IMPULSE_FIRST = SETTLE
#: Heel strikes walked from the fixed point for the impulse ratio and the energy split.
IMPULSE_STEPS = 8


def _tolerance(result: Result, check: str) -> float:
    """The tolerance the run's check ``check`` holds at the run's preset (NaN where it does not report it)."""
    return next((float(c.tolerance) for c in result.checks if c.name == check), math.nan)


@dataclass(frozen=True)
class ActuatorWork:
    """Reads the actuator work per step W (002 eq 29, J) regressed at the fitted fixed point against the exact step's,
    relative, held to the run's cost-of-transport tolerance (W is its numerator, measured the same way)."""

    def __call__(self, result: Result) -> Reading:
        work = result.extras.get("actuator_work")
        tol = _tolerance(result, "cost_of_transport")
        if not work:
            return Reading(analytic=None, mujoco=None, error=math.nan, tolerance=tol, kind="rel",
                           detail="the run reports no actuator work")
        exact, sim = float(work["analytic"]), float(work["simulated"])
        return Reading(analytic=exact, mujoco=sim, error=abs(sim - exact) / abs(exact), tolerance=tol, kind="rel",
                       detail="actuator force x hinge rate x dt over a step, regressed at the fitted fixed point")


#: What a figure's point reads off the validation at its mu: the multiplier with its bootstrap spread, or a check.
_QUANTITY_READERS = {"multiplier": largest_multiplier_reader("eigenvalues"), "speed": check_reader("speed"),
                     "cost_of_transport": check_reader("cost_of_transport")}


@dataclass(frozen=True)
class GaitPoint:
    """A figure's MuJoCo point (002 Figs 4.2(b), 5.2(a-c)): ``quantity`` of Gait ``gait`` at friction ``x``, read off
    the scenario's validation there (:func:`validated`)."""

    gait: str
    quantity: str

    def __call__(self, x: float, runner: Runner) -> Reading:
        return _QUANTITY_READERS[self.quantity](runner.validate({"gait": self.gait, "mu": repr(float(x))}))


def _gait_value(g: theory.Gait, quantity: str) -> float:
    if quantity == "multiplier":
        return g.spectral_radius
    if quantity == "speed":
        return theory.average_speed(g.record)
    return theory.cost_of_transport(g.biped, g.record)


@lru_cache(maxsize=8)
def theory_branch(gait: str, low: float, high: float) -> tuple[tuple[float, theory.Gait], ...]:
    """The named gait continued in mu (:func:`theory.continuation`, 002 Figs 4.2(b), 5.2) from its highest-mu seed
    down to ``low`` and up to ``high`` on a grid of :data:`THEORY_STEP`; a branch that ends stops there."""
    name = _CURVE_GAIT[gait]
    seed_mu, seed_z = max(theory.GAIT_SEEDS[name])
    bp, act = theory.paper_setup(name, seed_mu)
    down = np.arange(seed_mu, low - THEORY_STEP, -THEORY_STEP)
    up = np.arange(seed_mu + THEORY_STEP, high + THEORY_STEP, THEORY_STEP)
    out = [(g.biped.mu, g) for g in theory.continuation(bp, [float(m) for m in down], seed_z, act, mu_start=seed_mu)]
    if up.size:
        out += [(g.biped.mu, g) for g in theory.continuation(replace(bp, mu=seed_mu), [float(m) for m in up], seed_z,
                                                             act, mu_start=seed_mu)]
    return tuple(sorted(out, key=lambda pair: pair[0]))


def sticking_curve(x: np.ndarray, quantity: str) -> np.ndarray:
    """Gait A's ``quantity`` over mu: the sticking gait does not depend on mu at or above its friction demand
    max(mu_c, abs(sigma~)) (002 Sec. 4.1), below which it is Gait B (NaN)."""
    g = theory.paper_gait("A", math.inf)
    demand = theory.critical_friction(g.biped, g.z)
    return np.where(x >= max(demand.stance, demand.impulse), _gait_value(g, quantity), np.nan)


@dataclass(frozen=True)
class TheoryCurve:
    """The theory's curve of ``quantity`` of Gait ``gait`` over mu: :func:`theory_branch` interpolated linearly
    (NaN beyond the continued branch); Gait A's is flat (:func:`sticking_curve`)."""

    gait: str
    quantity: str

    def __call__(self, xs: np.ndarray, runner: Runner) -> np.ndarray:
        x = np.asarray(xs, float)
        if self.gait == "a":
            return sticking_curve(x, self.quantity)
        branch = theory_branch(self.gait, round(float(x.min()), 4), round(float(x.max()), 4))
        mus = np.array([m for m, _ in branch])
        ys = np.array([_gait_value(g, self.quantity) for _, g in branch])
        return np.where((x >= mus.min()) & (x <= mus.max()), np.interp(x, mus, ys), np.nan)


@dataclass(frozen=True)
class FittedStable:
    """Whether MuJoCo's fitted map of Gait ``gait`` at friction ``value`` is stable, abs(lambda)max < 1 (002 Sec. 4.2:
    a gait is stable while every multiplier lies inside the unit circle); a run that fits no map is not."""

    gait: str

    def __call__(self, value: float, runner: Runner) -> bool:
        result = runner.validate({"gait": self.gait, "mu": repr(float(value))})
        return result.fit is not None and float(np.max(np.abs(np.asarray(result.fit.eigenvalues, complex)))) < 1.0


#: (mu of the start, mu beyond the loss) of each gait's stability-loss search: 002's "~0.11" lies between.
_LOSS_SEARCH = {"b": (0.12, 0.10), "i": (0.12, 0.09)}


@dataclass(frozen=True)
class StabilityLoss:
    """The theory's mu at which Gait ``gait`` loses stability (:func:`theory.stability_loss_mu`: continuation, then
    regula falsi on abs(lambda)max - 1; 002 Sec. 4.2 for Gait B, Sec. 5 for Gait I)."""

    gait: str

    def __call__(self, runner: Runner) -> float:
        start, stop = _LOSS_SEARCH[self.gait]
        g = theory.paper_gait(_CURVE_GAIT[self.gait], start)
        return theory.stability_loss_mu(g.biped, g.z[:3], start, stop, g.actuation, mu_step=0.005)


def momentum(rows: np.ndarray, bp: theory.FrictionBiped) -> tuple[np.ndarray, np.ndarray]:
    """The biped's total linear momentum (P_x along the slope, P_z along its normal; N s) on the recorded rows
    (time, stance, qpos (x, z, hinge 0, hinge 1), qvel): hip mass and the two leg masses (002 eq 27)."""
    qpos, qvel = rows[:, 2:6], rows[:, 6:10]
    total = bp.total_mass
    px = total * qvel[:, 0] - bp.m * bp.b * (qvel[:, 2] * np.cos(qpos[:, 2]) + qvel[:, 3] * np.cos(qpos[:, 3]))
    pz = total * qvel[:, 1] + bp.m * bp.b * (qvel[:, 2] * np.sin(qpos[:, 2]) + qvel[:, 3] * np.sin(qpos[:, 3]))
    return px, pz


def momentum_jump(t: np.ndarray, p: np.ndarray, t_on: float) -> float:
    """The jump of ``p`` at ``t_on``: quadratics fitted over IMPULSE_FIT on each side (IMPULSE_SKIP around ``t_on``
    left out), evaluated at ``t_on``; the smooth stance forces and gravity drop out, the heel strike's impulse
    remains."""
    before = (t > t_on - IMPULSE_SKIP - IMPULSE_FIT) & (t < t_on - IMPULSE_SKIP)
    after = (t > t_on + IMPULSE_SKIP) & (t < t_on + IMPULSE_SKIP + IMPULSE_FIT)
    pre = np.polyval(np.polyfit(t[before] - t_on, p[before], 2), 0.0)
    post = np.polyval(np.polyfit(t[after] - t_on, p[after], 2), 0.0)
    return float(post - pre)


def touchdowns(rows: np.ndarray, strikes: list[float], bp: theory.FrictionBiped, radius: float) -> list[float]:
    """The instants the new stance foot meets the slope after each heel strike the controller saw: where its height
    crosses 0, interpolated between rows (as the impact-slip check reads it)."""
    out = []
    for t0, stance in zip([0.0, *strikes], stance_rows(rows, strikes, bp, radius), strict=False):
        t, h = stance["t"], stance["height"]
        i = int(np.argmax(h <= 0.0))
        out.append(t0 + (t[i - 1] + h[i - 1] / (h[i - 1] - h[i]) * (t[i] - t[i - 1]) if i > 0 else t[0]))
    return out[1:]


def gait_run(runner: Runner, name: str) -> tuple[theory.Gait, Any, np.ndarray, float]:
    """The scenario's gait ``name`` run from its analytic fixed point for :data:`IMPULSE_STEPS` heel strikes at the
    runner's preset (its model, contact switching and actuation): the gait, the controller, trajectory 0's recorded
    rows and the foot radius."""
    params, settings = runner.inputs({"gait": name})
    g = gait(params)
    model = runner.build(params, settings)
    c, _, _ = run_gait(params, settings, model, g.z[None, :], IMPULSE_STEPS)
    return g, c, np.concatenate(c.rows0), float(settings["foot_radius"])


def impulse_ratio(runner: Runner) -> Reading:
    """002 Sec. 4.1, Fig. 4.1(c): the ratio sigma~ = F~_t/F~_n of Gait A's heel-strike impulse (|sigma~| = 0.145 in
    002), from MuJoCo's momentum jump at each settled heel strike of the scenario's gait run from the fixed point,
    against the exact sticking impulse (002 eqs 37-38). Spread: half the range over the heel strikes."""
    g, c, rows, radius = gait_run(runner, "a")
    strikes = [t for t, _ in c.strikes[0]]
    px, pz = momentum(rows, g.biped)
    ratios = []
    for t_on in touchdowns(rows, strikes, g.biped, radius)[IMPULSE_FIRST:]:
        if t_on + IMPULSE_SKIP + IMPULSE_FIT < rows[-1, 0]:
            ratios.append(momentum_jump(rows[:, 0], px, t_on) / momentum_jump(rows[:, 0], pz, t_on))
    exact = float(g.record.impulse_ratio)
    tol = runner.tolerance("friction_ratio")  # a force ratio read from momentum, as sigma~ is
    if not ratios:
        return Reading(analytic=exact, mujoco=None, error=math.nan, tolerance=tol, detail="no settled heel strike")
    sim = float(np.mean(ratios))
    return Reading(analytic=exact, mujoco=sim, error=abs(sim - exact), tolerance=tol,
                   spread=(max(ratios) - min(ratios)) / 2,
                   detail=f"momentum jump (quadratics over {IMPULSE_FIT * 1e3:g} ms each side, "
                   f"{IMPULSE_SKIP * 1e3:g} ms skipped) at {len(ratios)} settled heel strikes of trajectory 0")


#: The heel strike's window for Gait II's energy split (s around the touchdown): the soft impact and the exact
#: post-impact slip+ (5.2 ms at mu = 0.2) both end inside it.
STRIKE_WINDOW = (-0.001, 0.010)
#: The bound on either dissipation's gap (J): 3x the fast preset's measured gap (1.5e-3 J), a twentieth of the gap of
#: the split 002 prints (impact 0.022 J, slip 0.078 J) from the exact one (0.1 J).
ENERGY_TOLERANCE = 0.005


def mechanical_energy(rows: np.ndarray, bp: theory.FrictionBiped) -> np.ndarray:
    """Kinetic plus potential energy (J) of the biped's three point masses (002 eq 27) on the recorded rows: the hip
    at the model's (x, z), each leg's mass b below it along its hinge angle."""
    qpos, qvel = rows[:, 2:6], rows[:, 6:10]
    xs, zs, vx, vz = [qpos[:, 0]], [qpos[:, 1]], [qvel[:, 0]], [qvel[:, 1]]
    for j in (2, 3):
        xs.append(qpos[:, 0] - bp.b * np.sin(qpos[:, j]))
        zs.append(qpos[:, 1] - bp.b * np.cos(qpos[:, j]))
        vx.append(qvel[:, 0] - bp.b * np.cos(qpos[:, j]) * qvel[:, j])
        vz.append(qvel[:, 1] + bp.b * np.sin(qpos[:, j]) * qvel[:, j])
    energy = np.zeros(len(rows))
    for mass, x, z, u, w in zip((bp.m_h, bp.m, bp.m), xs, zs, vx, vz, strict=True):
        energy += mass * (0.5 * (u * u + w * w) + bp.g * (z * math.cos(bp.slope) - x * math.sin(bp.slope)))
    return energy


def energy_split(runner: Runner) -> Reading:
    """002 Sec. 5, Gait II at mu = 0.2: where the actuator work goes. MuJoCo's dissipation (actuator work minus the
    change of mechanical energy) over the heel strike's window (:data:`STRIKE_WINDOW`: the impact and the post-impact
    slip) and over the rest of the step, averaged over the settled steps of the scenario's gait run from the fixed
    point, against the exact step's (impact loss plus the slip+'s friction work, and the friction work after the
    window: none, the stance sticks after its 5.2 ms slip+). Error: the larger gap, J."""
    g, c, rows, radius = gait_run(runner, "ii")
    t, st = rows[:, 0], rows[:, 1].astype(int)
    idx = np.arange(len(t))
    q1, q2 = g.actuation.generalised_force(np.zeros(4), np.zeros(4), 0.0)
    power = q1 * rows[idx, 6 + 2 + st] - q2 * rows[idx, 6 + 3 - st]
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    lost = work - mechanical_energy(rows, g.biped)  # dissipated up to each row

    def at(time: float) -> float:
        return float(np.interp(time, t, lost))

    ons = touchdowns(rows, [s for s, _ in c.strikes[0]], g.biped, radius)
    strike, stance = [], []
    for t_on, t_next in zip(ons[IMPULSE_FIRST - 1 :], ons[IMPULSE_FIRST:], strict=False):
        a, b = t_on + STRIKE_WINDOW[0], t_on + STRIKE_WINDOW[1]
        strike.append(at(b) - at(a))
        stance.append(at(t_next + STRIKE_WINDOW[0]) - at(b))
    rec = g.record
    exact = [rec.impact_loss - rec.friction_work, 0.0]
    tol = ENERGY_TOLERANCE
    if not strike:
        return Reading(analytic=exact, mujoco=None, error=math.nan, tolerance=tol, detail="no settled step")
    sim = [float(np.mean(strike)), float(np.mean(stance))]
    return Reading(analytic=exact, mujoco=sim, error=float(np.max(np.abs(np.subtract(sim, exact)))), tolerance=tol,
                   kind="max-abs", spread=float(max(np.ptp(strike), np.ptp(stance)) / 2),
                   detail=f"dissipation (J) over the heel strike's window [{STRIKE_WINDOW[0] * 1e3:g}, "
                   f"{STRIKE_WINDOW[1] * 1e3:g}] ms and over the rest of the step, mean of {len(strike)} settled steps")
