"""Dedicated MuJoCo experiments for the results of 000 (Coleman & Holmes 1999) the scenario's validation does not run:
sigma4 of a long slot (Fig. 2) and of a short one (4.1), the symmetric skate's basins (Fig. 3, B.13), the spinning
saddle (3.8), the turning points (B.5, B.8) and the flip-flop of a vanishing radius of gyration (Fig. 10, B.15-B.16)
(:mod:`mjpoincare.scenarios.paper_results`).

Every run builds the scenario's model (:func:`mjpoincare.scenarios.slotted_skate.pegs.build`) at the preset's settings,
m = rho = 1 unless stated, so that SI numbers are the paper's; the peg protocol runs through the scenario's
:class:`~mjpoincare.scenarios.slotted_skate.pegs.PegController` in one batched event rollout
(:func:`mjpoincare.simulation.simulate.event_rollout`), and the runs without a peg switch (a single stance) through
:func:`mjpoincare.simulation.simulate.rollout_batch`. A Fig. 3 start is run at a rate of FIG3_RATE and a sigma4 run's
long slot faster than 1 m/s: the velocity scaling of 000 Sec. 2.1 maps them to the paper's (V0, Omega0) exactly.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from mjpoincare.analysis.theory import slotted_skate as theory
from mjpoincare.analysis.theory.slotted_skate import figures
from mjpoincare.core.params import Values
from mjpoincare.core.seam import Chunk
from mjpoincare.core.settings import rollout_options
from mjpoincare.scenarios.paper_results import Reading, Runner
from mjpoincare.scenarios.slotted_skate.design import slot_speed
from mjpoincare.scenarios.slotted_skate.pegs import PegController, build
from mjpoincare.simulation.simulate import event_rollout, initial_states, rollout_batch

#: Angular momenta about the entry peg of a sigma4 run's starts (paper units): small enough that r = 2E/H^2 stays far
#: above 1 over the run (no reversal, 3.13-3.15) on the longest slot of Fig. 2, three of them for the spread.
SIGMA4_H0 = (0.5e-3, 1e-3, 2e-3)
#: Impacts of a sigma4 run: three ratios H_k+1/H_k per start.
SIGMA4_IMPACTS = 4
#: A ratio H_k+1/H_k is judged while abs(H_k) is at least this fraction of the start's largest abs(H) (the scenario's
#: RATIO_FLOOR, docs/scenarios/slotted-skate.md).
SIGMA4_FLOOR = 1e-4
#: Longest stance of a sigma4 run (s): a slot longer than this many metres is run faster than 1 m/s (velocity scaling,
#: 000 Sec. 2.1), ~1000 steps of the fast preset per stance.
SIGMA4_STANCE = 0.5
#: Fig. 2: the slot length of the sigma4 curve over L0/Delta, 1/Delta^2 = 0.01 (a slot longer than 4 rho: the bands).
FIG2_DELTA = 10.0
#: Fig. 3: L0, Delta and the initial rate of the symmetric skate (H = 1 about the entry peg: Omega0 = 4/5).
FIG3_SKATE = theory.SlottedSkate(L0=-0.5, Delta=1.0)
FIG3_OMEGA0 = 0.8
#: Fig. 3: the initial rate of a run (rad/s, rho = 1 m); the slot speed is scaled with it (velocity scaling, 000 Sec.
#: 2.1). The final speed's error grows with the rate (the rotation's energy passes through the impacts): 1 rad/s holds
#: it to a few 1e-4 of V0 at the fast preset.
FIG3_RATE = 1.0
#: Fig. 3: a run is read at the first impact where the map's slot speed is within this of its final one (units of the
#: initial slot speed): a hundredth of the tolerance.
FIG3_RESOLUTION = 1e-5
#: Fig. 3: the starts of a point, Omega0 x these (|V_f| = V0 whatever Omega0, B.12; the basins move by 1 %).
FIG3_SPREAD = (0.99, 1.0, 1.01)
#: (3.8): rates of the spinning starts (rad/s, rho = 1: the paper's Omega_eq), the peg's offset from the mass centre
#: at the start (m) and the offset at which the growth rate is read (its O(offset^2) nonlinearity is 1e-6).
SPIN_RATES = (0.5, 1.0, 2.0)
SPIN_OFFSET = 1e-6
SPIN_READ = 1e-3
#: (B.8): the skate of the derivation page's example (G inside the slot), H about the entry peg, and the ratios
#: r = 2E/H^2 of the starts: 0.8 in (min, max) of (B.8), 0.95 and 0.99 in (max, 1), 1.02 above 1 (no turning point).
TURN_SKATE = theory.SlottedSkate(L0=-0.3, Delta=1.0)
TURN_H = 0.5
TURN_RATIOS = (0.8, 0.95, 0.99, 1.02)
#: Fig. 10: l0/delta of the figure, the radius of gyration of the run (rho/delta; 0 does not compile, see the
#: result), the starts' initial rates (rad/s at v0 = 1 m/s, delta = 1 m) and the impacts.
FIG10_X = -2.0 / 3.0
FIG10_RHO = 0.01
FIG10_RATES = (0.5, 1.0, 2.0)
FIG10_IMPACTS = 8


def _inputs(runner: Runner, **values: float) -> tuple[Values, Values]:
    """The scenario's parameters (its defaults, ``values`` on top) and the runner's preset settings."""
    return runner.inputs({name: repr(float(value)) for name, value in values.items()})


def _peg_runs(params: Values, settings: Values, V: np.ndarray, Om: np.ndarray, seconds: float) -> PegController:
    """Starts (V, Om) (SI; the peg at the slot end each enters, front for V > 0) run ``seconds`` through the peg
    protocol; the controller holds each start's stances (:class:`PegController`)."""
    model = build(params, settings)
    l0, delta = float(params["l0"]), float(params["delta"])
    entry = np.where(V > 0, l0, l0 + delta)
    controller = PegController(model, params, entry)
    start = initial_states(model, np.stack([np.zeros_like(V), entry, np.zeros_like(V)], 1),
                           np.stack([Om, V, np.zeros_like(V)], 1))
    nstep = math.ceil(seconds / model.opt.timestep)
    event_rollout(model, start, nstep, controller, **rollout_options(settings),
                  chunk_steps=max(10, min(2000, nstep // 20)))
    return controller


def _plain_runs(params: Values, settings: Values, qpos: np.ndarray, qvel: np.ndarray, seconds: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Starts (qpos, qvel) in the peg chart run ``seconds`` about their first peg (no switch): time, s and sdot, each
    (B, T)."""
    model = build(params, settings)
    chunks: list[Chunk] = []
    nstep = math.ceil(seconds / model.opt.timestep)
    rollout_batch(model, initial_states(model, qpos, qvel), nstep, chunks.append, **rollout_options(settings),
                  chunk_steps=min(nstep, 20000))
    cat = [chunks[0]] + [Chunk(c.time[:, 1:], c.qpos[:, 1:], c.qvel[:, 1:]) for c in chunks[1:]]
    return (np.concatenate([c.time for c in cat], 1), np.concatenate([c.qpos[:, :, 1] for c in cat], 1),
            np.concatenate([c.qvel[:, :, 1] for c in cat], 1))


def _reversed(samples: list[tuple[float, ...]]) -> list[bool]:
    """Per stance with a successor: whether it reversed (the next stance's peg went in at the other end)."""
    return [b[0] != a[0] for a, b in itertools.pairwise(samples)]


def sigma4_ratios(l0: float, delta: float, forward: bool, runner: Runner) -> list[np.ndarray]:
    """MuJoCo's H_k+1/H_k of straight motion (3.10) at slot offset ``l0`` and length ``delta`` (rho = 1), per start of
    SIGMA4_H0 in one direction (at the slot speed of SIGMA4_STANCE), over its non-reversing stances while abs(H_k) is
    at least SIGMA4_FLOOR of the start's largest (a sigma4 near 0 leaves a ratio of MuJoCo's rounding after that)."""
    params, settings = _inputs(runner, l0=l0, delta=delta)
    sk = theory.SlottedSkate(L0=l0, Delta=delta)
    la = sk.L_front if forward else sk.L_rear
    speed = max(1.0, delta / SIGMA4_STANCE)
    h0 = np.array(SIGMA4_H0)
    V = np.full(h0.size, speed if forward else -speed)
    controller = _peg_runs(params, settings, V, speed * h0 / (1.0 + la * la),
                           1.2 * (SIGMA4_IMPACTS + 1) * delta / speed)
    out = []
    for samples in controller.samples:
        floor = SIGMA4_FLOOR * max(abs(x[3]) for x in samples)
        pairs = [(a[3], b[3]) for (a, b), flip in zip(itertools.pairwise(samples), _reversed(samples), strict=True)
                 if not flip and abs(a[3]) >= floor]
        out.append(np.array([h1 / h0 for h0, h1 in pairs[: SIGMA4_IMPACTS - 1]]))
    return out


def _sigma4_reading(l0: float, delta: float, forward: bool, runner: Runner, tolerance: float) -> Reading:
    ratios = sigma4_ratios(l0, delta, forward, runner)
    ref = theory.sigma4(theory.SlottedSkate(L0=l0, Delta=delta), forward)
    per_start = np.array([np.median(r) for r in ratios])
    every = np.concatenate(ratios)
    return Reading(analytic=ref, mujoco=float(np.median(per_start)), error=float(np.max(np.abs(every - ref))),
                   tolerance=tolerance, kind="max-abs", spread=float(np.ptp(per_start)) / 2,
                   detail=f"H_k+1/H_k of {len(ratios)} starts, {every.size} impacts, V* {'> 0' if forward else '< 0'}")


#: Fig. 2 and (4.1): the bound on a sigma4 ratio's error and on the rate's (``why`` of the results states them).
SIGMA4_TOLERANCE = 1e-5
RATE_TOLERANCE = 1e-4


def fig2_point(x: float, runner: Runner) -> Reading:
    """000 Fig. 2(a): MuJoCo's sigma4 (V* > 0) at L0/Delta = ``x`` and 1/Delta^2 = 1/FIG2_DELTA^2, against (3.10)."""
    return _sigma4_reading(x * FIG2_DELTA, FIG2_DELTA, True, runner, SIGMA4_TOLERANCE)


def fig2_theory(xs: np.ndarray, _runner: Runner) -> np.ndarray:
    """(3.10): sigma4 (V* > 0) over L0/Delta at Delta = FIG2_DELTA."""
    return np.array([theory.sigma4(theory.SlottedSkate(L0=float(x) * FIG2_DELTA, Delta=FIG2_DELTA), True)
                     for x in xs])


def stable_forward_band(delta: float, runner: Runner) -> bool:
    """Fig. 2(b): whether MuJoCo's straight motion V* > 0 at L0/Delta = -3/4 and slot length ``delta`` is stable
    (median |H_k+1/H_k| < 1)."""
    return bool(abs(np.median(np.concatenate(sigma4_ratios(-0.75 * delta, delta, True, runner)))) < 1.0)


def stable_backward_band(delta: float, runner: Runner) -> bool:
    """Fig. 2(b): whether MuJoCo's straight motion V* < 0 at L0/Delta = -1/4 and slot length ``delta`` is stable."""
    return bool(abs(np.median(np.concatenate(sigma4_ratios(-0.25 * delta, delta, False, runner)))) < 1.0)


def band_edge_forward(_runner: Runner) -> float:
    """Fig. 2(b): the slot length where the forward band's tip (L0/Delta = -3/4) turns unstable
    (:func:`figures.band_edge_delta`)."""
    return figures.band_edge_delta(-0.75, True)


def band_edge_backward(_runner: Runner) -> float:
    """Fig. 2(b): the slot length where the backward band's tip (L0/Delta = -1/4) turns unstable."""
    return figures.band_edge_delta(-0.25, False)


def smooth_limit_point(delta: float, runner: Runner) -> Reading:
    """(4.1): MuJoCo's (V*/Delta) ln sigma4 at L0 = 1 and slot length ``delta`` (V* = 1), against the exact rate; the
    smooth sleigh's -1/2 (2.1) is its Delta -> 0 limit."""
    rates = [np.log(r) / delta for r in sigma4_ratios(1.0, delta, True, runner)]
    per_start = np.array([np.median(r) for r in rates])
    every = np.concatenate(rates)
    ref = theory.smooth_limit_rate(theory.SlottedSkate(L0=1.0, Delta=delta))
    return Reading(analytic=ref, mujoco=float(np.median(per_start)), error=float(np.max(np.abs(every - ref))),
                   tolerance=RATE_TOLERANCE, kind="max-abs", spread=float(np.ptp(per_start)) / 2,
                   detail=f"ln(H_k+1/H_k)/Delta of {len(rates)} starts, {every.size} impacts")


def smooth_limit_theory(deltas: np.ndarray, _runner: Runner) -> np.ndarray:
    """(4.1): the exact (1/Delta) ln sigma4 at L0 = 1 over Delta (NaN for Delta <= 0, no slot)."""
    return np.array([theory.smooth_limit_rate(theory.SlottedSkate(L0=1.0, Delta=float(d))) if d > 0 else math.nan
                     for d in deltas])


#: Fig. 3: the bound on |V_f| error in the paper's units (``why`` of the result states it).
FIG3_TOLERANCE = 1e-3


def _fig3_impacts(rate: float) -> tuple[int, float]:
    """Fig. 3: the impacts from a start of unit slot speed and rate ``rate`` (paper units) to the first whose slot
    speed is within FIG3_RESOLUTION of the final one (B.12-B.13, :func:`figures.symmetric_final_speed`), and their
    time, by the exact map (B.3-B.5)."""
    v_final = figures.symmetric_final_speed(FIG3_SKATE, 1.0, rate)
    q, n, duration = theory.initial_state(FIG3_SKATE, 1.0, rate), 0, 0.0
    while abs(slot_speed(q) - v_final) > FIG3_RESOLUTION:
        q = theory.return_map(FIG3_SKATE, q.D_plus, q.E_plus, q.theta_plus, q.H_plus)
        n, duration = n + 1, duration + q.duration
    return n, duration + q.duration


def _fig3_final(v0: float, runner: Runner) -> np.ndarray:
    """Fig. 3: the FIG3_SPREAD starts of initial slot speed ``v0`` (paper units, Omega0 = 4/5) run to the impact of
    :func:`_fig3_impacts`; MuJoCo's slot speed there, in the paper's units."""
    speed = v0 * FIG3_RATE / FIG3_OMEGA0  # SI at a rate of FIG3_RATE (velocity scaling, Sec. 2.1; rho = 1 m)
    rates = FIG3_RATE * np.array(FIG3_SPREAD)
    params, settings = _inputs(runner, l0=FIG3_SKATE.L0, delta=FIG3_SKATE.Delta, V0=speed)
    reads = [_fig3_impacts(float(om) / speed) for om in rates]
    controller = _peg_runs(params, settings, np.full(rates.size, speed), rates, 1.1 * max(t for _, t in reads) / speed)
    mujoco = []
    for samples, (n, _) in zip(controller.samples, reads, strict=True):
        if len(samples) <= n:
            mujoco.append(math.nan)
            continue
        sign = 1.0 if samples[n][0] == FIG3_SKATE.L0 else -1.0
        mujoco.append(v0 / speed * math.copysign(math.sqrt(2.0 * samples[n][1]), sign))
    return np.array(mujoco)


def fig3_point(v0: float, runner: Runner) -> Reading:
    """000 Fig. 3: MuJoCo's final slot speed from initial slot speed ``v0`` (Omega0 = 4/5) against the basins of
    (B.13) with |V_f| = V0 (B.12, :func:`figures.symmetric_final_speed`)."""
    mujoco = _fig3_final(v0, runner)
    refs = np.array([figures.symmetric_final_speed(FIG3_SKATE, v0, FIG3_OMEGA0 * f) for f in FIG3_SPREAD])
    return Reading(analytic=float(refs[1]), mujoco=float(mujoco[1]), error=float(np.max(np.abs(mujoco - refs))),
                   tolerance=FIG3_TOLERANCE, kind="max-abs", spread=float(np.ptp(mujoco)) / 2,
                   detail=f"final V of {mujoco.size} starts, Omega0 x {FIG3_SPREAD}")


def fig3_theory(v0s: np.ndarray, _runner: Runner) -> np.ndarray:
    """(B.12)-(B.13): the final slot speed over the initial one (Omega0 = 4/5), +-V0 by basin (NaN at V0 <= 0)."""
    return np.array([figures.symmetric_final_speed(FIG3_SKATE, float(v), FIG3_OMEGA0) if v > 0 else math.nan
                     for v in v0s])


def second_stance_reverses(v0: float, runner: Runner) -> bool:
    """Fig. 3 (B.13): whether MuJoCo's symmetric skate from initial slot speed ``v0`` (Omega0 = 4/5) reverses in its
    second stance too (V0 below V_1: two reversals), run at FIG3_RATE for the map's first four stances."""
    speed = v0 * FIG3_RATE / FIG3_OMEGA0  # SI (velocity scaling, Sec. 2.1; rho = 1 m)
    params, settings = _inputs(runner, l0=FIG3_SKATE.L0, delta=FIG3_SKATE.Delta, V0=speed)
    seconds = 1.2 * sum(q.duration for q in theory.iterate(FIG3_SKATE, 1.0, FIG3_RATE / speed, 0.0, 4)) / speed
    samples = _peg_runs(params, settings, np.array([speed]), np.array([FIG3_RATE]), seconds).samples[0]
    flips = _reversed(samples)
    if len(flips) < 2:
        raise RuntimeError(f"V0 = {v0!r}: {len(samples)} stances in {seconds:.3g} s")
    return flips[1]


def spin_boundary_v1(_runner: Runner) -> float:
    """(B.13): V_1 of Fig. 3 (Omega0 = 4/5), where a second reversal starts."""
    return figures.spin_boundary_speeds(FIG3_SKATE, FIG3_OMEGA0, 2)[1]


#: (3.8) and (B.5): the bounds on the rate's relative error and on a turning point's (``why`` of the results).
SPIN_TOLERANCE = 1e-4
TURN_TOLERANCE = 1e-4


def spin_saddle(runner: Runner) -> Reading:
    """(3.8), Sec. 3.1.2: MuJoCo's skate spinning at SPIN_RATES with its peg SPIN_OFFSET off the mass centre (G inside
    the slot, Fig. 3's skate): the offset grows as cosh(lambda t); lambda/Omega_eq against the saddle's eigenvalue
    +Omega_eq (:func:`figures.spin_saddle_eigenvalues`), read where the offset reaches SPIN_READ."""
    params, settings = _inputs(runner, l0=FIG3_SKATE.L0, delta=FIG3_SKATE.Delta)
    rates = np.array(SPIN_RATES)
    ones = np.ones_like(rates)
    t, s, _ = _plain_runs(params, settings, np.stack([0 * ones, SPIN_OFFSET * ones, 0 * ones], 1),
                          np.stack([rates, 0 * ones, 0 * ones], 1), 1.2 * math.acosh(SPIN_READ / SPIN_OFFSET)
                          / rates.min())
    measured = []
    for b, om in enumerate(rates):
        k = int(np.argmax(s[b] >= SPIN_READ))
        if k == 0:
            return Reading(analytic=1.0, mujoco=None, error=math.nan, tolerance=SPIN_TOLERANCE, kind="rel",
                           detail=f"the offset never reached {SPIN_READ:g} m at Omega_eq = {om:g}")
        f = (SPIN_READ - s[b, k - 1]) / (s[b, k] - s[b, k - 1])
        t_read = t[b, k - 1] + f * (t[b, k] - t[b, k - 1])
        measured.append(math.acosh(SPIN_READ / SPIN_OFFSET) / t_read / figures.spin_saddle_eigenvalues(om)[-1])
    ratio = np.array(measured)
    return Reading(analytic=1.0, mujoco=float(ratio[1]), error=float(np.max(np.abs(ratio - 1.0))),
                   tolerance=SPIN_TOLERANCE, kind="rel", spread=float(np.ptp(ratio)) / 2,
                   detail=f"growth rate / Omega_eq at Omega_eq = {SPIN_RATES} rad/s, offset {SPIN_OFFSET:g} -> "
                   f"{SPIN_READ:g} m")


def _turn_starts() -> list[tuple[float, float, float | None, float]]:
    """(B.5): the feasible starts (3.15) of TURN_RATIOS from each end: (V, Omega, the turning point's L met or None,
    the stance's duration by B.1)."""
    out = []
    for r in TURN_RATIOS:
        for la, sign in ((TURN_SKATE.L_front, 1.0), (TURN_SKATE.L_rear, -1.0)):
            v2 = r * TURN_H**2 - TURN_H**2 / (1.0 + la * la)
            if v2 <= 0.0:
                continue
            d0 = la - TURN_SKATE.L0
            roots = theory.turning_points(TURN_SKATE, 0.5 * r * TURN_H**2, TURN_H)
            ahead = [TURN_SKATE.L0 + d for d in roots if sign * (d - d0) > 0.0]
            met = min(ahead, key=lambda lc: sign * (lc - la)) if ahead else None
            duration = theory.stance(TURN_SKATE, d0, 0.5 * r * TURN_H**2, TURN_H).duration
            out.append((sign * math.sqrt(v2), TURN_H / (1.0 + la * la), met, duration))
    return out


def turning_points(runner: Runner) -> Reading:
    """(B.5)/(B.8): MuJoCo's turning points (L where the slot speed changes sign in the first stance, inside the slot)
    from both slot ends at the TURN_RATIOS, against the root of (B.5) met; two distinct ones, one per direction, for r
    in (max{1/(1 + L0^2), 1/(1 + (L0 + Delta)^2)}, 1) (:func:`figures.two_turning_point_range`)."""
    params, settings = _inputs(runner, l0=TURN_SKATE.L0, delta=TURN_SKATE.Delta)
    starts = _turn_starts()
    V = np.array([v for v, _, _, _ in starts])
    Om = np.array([om for _, om, _, _ in starts])
    entry = np.where(V > 0, TURN_SKATE.L_front, TURN_SKATE.L_rear)
    _, s, sd = _plain_runs(params, settings, np.stack([0 * V, entry, 0 * V], 1), np.stack([Om, V, 0 * V], 1),
                           1.2 * max(d for _, _, _, d in starts))
    analytic, mujoco, error = [], [], 0.0
    for b, (_, _, met, _) in enumerate(starts):
        flips = np.nonzero(np.sign(sd[b, 1:]) != np.sign(sd[b, :1]))[0]
        seen = None
        if flips.size:
            k = int(flips[0]) + 1
            inside = TURN_SKATE.L_front < s[b, k] < TURN_SKATE.L_rear
            seen = float(s[b, k - 1] + (s[b, k] - s[b, k - 1]) * sd[b, k - 1] / (sd[b, k - 1] - sd[b, k])) \
                if inside else None
        analytic.append(met)
        mujoco.append(seen)
        error = max(error, math.inf if (met is None) != (seen is None) else abs(seen - met) if met is not None
                    else 0.0)
    low, _ = figures.two_turning_point_range(TURN_SKATE)
    return Reading(analytic=analytic, mujoco=mujoco, error=error, tolerance=TURN_TOLERANCE, kind="max-abs",
                   detail=f"{len(starts)} feasible starts at r = {TURN_RATIOS} (both ends where feasible); two "
                   f"turning points need r > {low:.6g} (B.8 with max)")


#: Fig. 10: the bound on the two-impact multiplier's error (``why`` of the result states it).
FIG10_TOLERANCE = 1e-4


def period2(runner: Runner) -> Reading:
    """000 Fig. 10 (B.15-B.16): MuJoCo's skate with rho/delta = FIG10_RHO at l0/delta = FIG10_X reverses every stance
    (the flip-flop); H_k+2/H_k against the two reversal impacts' product (:func:`figures.period2_multiplier`), which
    is 1 - O(rho^2) and 1 (neutral) at rho = 0."""
    params, settings = _inputs(runner, l0=FIG10_X, delta=1.0, rho=FIG10_RHO)
    sk = theory.SlottedSkate(L0=FIG10_X / FIG10_RHO, Delta=1.0 / FIG10_RHO)
    rates = np.array(FIG10_RATES)
    seconds = 1.2 * FIG10_RHO * max(sum(q.duration for q in theory.iterate(sk, 1.0, om * FIG10_RHO, 0.0,
                                                                          FIG10_IMPACTS + 1)) for om in rates)
    controller = _peg_runs(params, settings, np.ones(rates.size), rates, seconds)
    ratios, flips = [], 0
    for samples in controller.samples:
        kept = samples[: FIG10_IMPACTS + 1]
        flips += sum(int(not f) for f in _reversed(kept))
        ratios.append([b[3] / a[3] for a, b in zip(kept[:-2], kept[2:], strict=True)])
    ref = figures.period2_multiplier(sk)
    r = np.array(ratios)
    error = float(np.max(np.abs(r - ref))) if flips == 0 else math.inf
    return Reading(analytic=ref, mujoco=float(np.median(r)), error=error, tolerance=FIG10_TOLERANCE, kind="max-abs",
                   spread=float(np.ptp(np.median(r, axis=1))) / 2,
                   detail=f"H_k+2/H_k over {r.size} stance pairs of {rates.size} starts; {flips} stances did not "
                   f"reverse; rho = 0 value 1 (B.16: C2 = {figures.period2_rho0_ratios(FIG10_X)[0]:g} and its "
                   "inverse)")
