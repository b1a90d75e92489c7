"""The rollout seam (:class:`mjpoincare.core.seam.Batch`) on MJX (x64) and MuJoCo Warp (float32): the semantics of
``test_rollout_seam.py`` on its small model (plus a sled for friction), and agreement with MuJoCo C.

Skipped when a backend's packages are missing, except under ``CI=true`` on Python 3.11+ (``make test`` installs the
extras ``mjx`` and ``warp`` there, so a missing backend is a broken install and fails). Each backend compiles once
per model, batch size and chunk length; the tests share those."""

from __future__ import annotations

import copy
import itertools
import json

import mujoco
import numpy as np
import pytest
from conftest import BACKEND_DISTRIBUTIONS, failed_gated_checks, skip_unless_required
from mujoco import rollout as mj_rollout
from test_rollout_seam import XML, fractional_step_of

from mjpoincare.core.params import ParameterError
from mjpoincare.core.seam import Batch
from mjpoincare.core.settings import DEFAULTS
from mjpoincare.engines.backends import check_installed, check_settings, open_batch
from mjpoincare.simulation.simulate import initial_states

#: The seam's model with a 1 kg sled on the floor, sliding along x and free to settle along z (box-plane contact):
#: friction decelerates it.
SLED_XML = XML.replace("  </worldbody>", """    <body name="sled" pos="0 -2 0.05">
      <joint name="slide" type="slide" axis="1 0 0"/>
      <joint name="settle" type="slide" axis="0 0 1"/>
      <geom name="sled" type="box" size="0.05 0.05 0.05" mass="1"/>
    </body>
  </worldbody>""")
#: (backend, precision) pairs under test, and the largest state difference from MuJoCo C each may show over
#: STEPS steps of the plain rollout, a fractional step and the friction test. Measured on this model: MJX x64 1.4e-15
#: (a fractional step 1.7e-18), Warp 5.6e-6 (2.0e-6 with contacts, a fractional step 1.7e-8); bounds with margin.
BACKENDS = {("mjx", "float64"): 1e-13, ("warp", "float32"): 2e-5}
CHUNK, STEPS = 50, 150
SLED_SPEED = 1.0


def _require(backend: str) -> None:
    try:
        check_installed(backend)
    except ParameterError as missing:
        skip_unless_required(str(missing), BACKEND_DISTRIBUTIONS[backend])


@pytest.fixture(scope="module", params=list(BACKENDS), ids=lambda p: f"{p[0]}-{p[1]}")
def backend(request: pytest.FixtureRequest) -> tuple[str, str]:
    _require(request.param[0])
    return request.param


@pytest.fixture(scope="module")
def model() -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(SLED_XML)


@pytest.fixture(scope="module")
def free(model: mujoco.MjModel) -> mujoco.MjModel:
    """The model without constraints (a restart from a recorded state repeats the step exactly)."""
    out = copy.copy(model)
    out.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
    return out


def _states(model: mujoco.MjModel, batch: int = 2, swing: float = 0.3) -> np.ndarray:
    """``batch`` states, the ball resting on the floor, the pendulum at ``swing`` (rad), the sled sliding."""
    qpos = np.tile(model.qpos0, (batch, 1))
    qpos[:, model.joint("swing").qposadr[0]] = swing
    qvel = np.zeros((batch, model.nv))
    qvel[:, model.joint("slide").dofadr[0]] = SLED_SPEED
    return initial_states(model, qpos, qvel)


def _column(model: mujoco.MjModel, joint: str, velocity: bool = False) -> int:
    return 1 + (model.nq + model.joint(joint).dofadr[0] if velocity else model.joint(joint).qposadr[0])


def _open(backend: tuple[str, str], model: mujoco.MjModel, start: np.ndarray) -> Batch:
    return open_batch(model, start, threads=1, backend=backend[0], precision=backend[1])


def _c_rollout(model: mujoco.MjModel, start: np.ndarray, nstep: int) -> np.ndarray:
    states, _ = mj_rollout.rollout(model, mujoco.MjData(model), start, nstep=nstep)
    return states


@pytest.mark.parametrize("which", ["free", "model"])
def test_chunk_restarts_continue_and_agree_with_c(backend: tuple[str, str], which: str,
                                                  request: pytest.FixtureRequest) -> None:
    """Three chunks, each from the last state of the one before, are MuJoCo C's one long rollout within the
    backend's bound (with and without contacts)."""
    m = request.getfixturevalue(which)
    start = _states(m, swing=0.7)
    start[1, _column(m, "swing", velocity=True)] = -1.0
    with _open(backend, m, start) as batch:
        rows = [batch.run_chunk(CHUNK) for _ in range(STEPS // CHUNK)]
    np.testing.assert_array_equal(rows[0][:, 0], start)
    for before, after in itertools.pairwise(rows):
        np.testing.assert_array_equal(after[:, 0], before[:, -1])
    got = np.concatenate([r[:, 1:] for r in rows], axis=1)
    assert np.abs(got - _c_rollout(m, start, STEPS)).max() <= BACKENDS[backend]
    np.testing.assert_array_equal(batch.report.final_state, got[:, -1])
    assert batch.report.steps == 2 * STEPS and not batch.report.diverged.any()


def test_padding_is_never_seen_and_shares_the_compile(backend: tuple[str, str], free: mujoco.MjModel) -> None:
    """One start padded to a batch of 2 (the ``batch`` setting): its chunk, states, flags, step count and last state
    are its own, equal to the same start's in an unpadded batch of 2; on MJX the padded batch reuses that batch's
    compiled chunk (no compile of its own)."""
    start = _states(free, swing=0.7)
    with _open(backend, free, start) as whole:
        both = whole.run_chunk(CHUNK)
    with open_batch(free, start[:1], threads=1, backend=backend[0], precision=backend[1], batch=2) as padded:
        one = padded.run_chunk(CHUNK)
        assert padded.states().shape == (1, start.shape[1])
    assert one.shape == (1, CHUNK + 1, start.shape[1])
    assert np.abs(one[0] - both[0]).max() <= BACKENDS[backend]
    report = padded.report
    assert report.steps == CHUNK and report.diverged.shape == (1,) and report.final_state.shape == (1, start.shape[1])
    if backend[0] == "mjx":
        assert report.compile_s == 0.0


def test_set_states_rewrites_the_chosen_trajectories_only(backend: tuple[str, str], model: mujoco.MjModel) -> None:
    with _open(backend, model, _states(model)) as batch:
        first = batch.run_chunk(CHUNK)
        new = _states(model, 1, swing=-0.4)
        batch.set_states(np.array([1]), new)
        second = batch.run_chunk(CHUNK)
    np.testing.assert_array_equal(second[1, 0], new[0])
    np.testing.assert_array_equal(second[0, 0], first[0, -1])


def test_a_chunk_of_chosen_rows_leaves_the_others_as_they_were(backend: tuple[str, str], model: mujoco.MjModel
                                                                ) -> None:
    """``rows``: the chosen trajectory steps as in the whole batch; the other keeps its state, is NaN in the chunk
    and is not flagged diverged (this engine steps its compiled batch whole)."""
    start = _states(model, swing=0.6)
    with _open(backend, model, start) as whole:
        both = whole.run_chunk(CHUNK)
    with _open(backend, model, start) as batch:
        one = batch.run_chunk(CHUNK, rows=np.array([1]))
        np.testing.assert_array_equal(batch.states()[0], start[0])
        np.testing.assert_array_equal(batch.states()[1], one[1, -1])
    assert np.isnan(one[0]).all() and not batch.report.diverged.any()
    np.testing.assert_array_equal(one[1], both[1])


def test_contact_released_per_trajectory(backend: tuple[str, str], model: mujoco.MjModel) -> None:
    """A released ball falls through the floor while the other rests; restored (twice), both rest alike again."""
    ball, drop = model.geom("ball").id, _column(model, "drop")
    start = _states(model)
    with _open(backend, model, start) as batch:
        batch.set_contact(1, ball, False)
        fell = np.concatenate([batch.run_chunk(CHUNK)[:, 1:] for _ in range(4)], axis=1)
        batch.set_contact(1, ball, True)
        batch.set_contact(1, ball, True)
        batch.set_states(np.arange(2), start)
        rest = batch.run_chunk(CHUNK)
    assert fell[0, -1, drop] > -0.01
    assert fell[1, -1, drop] < -0.5 * 9.81 * 0.4**2 * 0.9
    np.testing.assert_allclose(rest[1], rest[0], rtol=0, atol=BACKENDS[backend])  # each keeps its solver warmstart


@pytest.mark.parametrize("released", [0, 1])
def test_equality_switched_per_trajectory(backend: tuple[str, str], model: mujoco.MjModel, released: int) -> None:
    hang, hold = _column(model, "hang"), model.equality("hold").id
    start = _states(model)
    with _open(backend, model, start) as batch:
        batch.set_eq_active(released, hold, False)
        loose = np.concatenate([batch.run_chunk(CHUNK)[:, 1:] for _ in range(2)], axis=1)
        batch.set_eq_active(released, hold, True)
        batch.set_states(np.arange(2), start)
        held = batch.run_chunk(CHUNK)
    assert loose[released, -1, hang] < -0.15 and abs(loose[1 - released, -1, hang]) < 1e-3
    np.testing.assert_allclose(held[released], held[1 - released], rtol=0, atol=BACKENDS[backend])


def test_actuator_bias_and_gear_per_trajectory(backend: tuple[str, str], model: mujoco.MjModel) -> None:
    """A constant bias force of 3 N on the 2 kg cart of trajectory 1 (then geared -1); trajectory 0 stays."""
    motor, push = model.actuator("motor").id, _column(model, "push", velocity=True)
    with _open(backend, model, _states(model)) as batch:
        batch.set_actuator(1, motor, bias=3.0)
        pushed = batch.run_chunk(CHUNK)
        batch.set_actuator(1, motor, gear=-1.0)
        back = batch.run_chunk(CHUNK)
    assert pushed[0, -1, push] == 0.0
    assert pushed[1, -1, push] == pytest.approx(1.5 * 0.1, rel=1e-5)
    assert back[1, -1, push] == pytest.approx(0.0, abs=1e-6)


def test_friction_set_per_trajectory(backend: tuple[str, str], model: mujoco.MjModel) -> None:
    """The sled of trajectory 1 (mu 0.25) slides on after 0.1 s; trajectory 0's (mu 1) has stopped; as in C."""
    slide = _column(model, "slide", velocity=True)
    start = _states(model)
    with _open(backend, model, start) as batch:
        batch.set_friction(1, 0.25)
        rows = batch.run_chunk(CHUNK)
    low = copy.copy(model)
    low.geom_friction[:, 0] = 0.25
    expected = [_c_rollout(m, start[i : i + 1], CHUNK)[0, -1, slide] for i, m in enumerate([model, low])]
    assert rows[0, -1, slide] < 0.1 and rows[1, -1, slide] > 0.5 * SLED_SPEED
    np.testing.assert_allclose(rows[:, -1, slide], expected, atol=BACKENDS[backend])


def test_advance_steps_a_fraction_of_the_timestep(backend: tuple[str, str], model: mujoco.MjModel) -> None:
    start = _states(model, 1, swing=0.5)[0]
    with _open(backend, model, start[None, :]) as batch:
        state = batch.advance(0, start, 0.0005)
        assert batch.timestep == 0.002
    assert np.abs(state - fractional_step_of(model, start, 0.0005)).max() <= BACKENDS[backend]


def test_mjx_float32_is_mjx_in_single_precision(free: mujoco.MjModel) -> None:
    """precision=float32 runs MJX in float32 (off C by float32 rounding, not by 1e-12) and leaves JAX's global x64
    setting as it found it."""
    _require("mjx")
    import jax

    before = jax.config.jax_enable_x64
    start = _states(free, swing=0.7)
    with open_batch(free, start, threads=1, backend="mjx", precision="float32") as batch:
        got = np.concatenate([batch.run_chunk(CHUNK)[:, 1:] for _ in range(STEPS // CHUNK)], axis=1)
    error = np.abs(got - _c_rollout(free, start, STEPS)).max()
    assert 1e-9 < error < 1e-5  # measured 3.2e-6
    assert jax.config.jax_enable_x64 == before


def test_a_setting_a_backend_lacks_is_refused_in_one_line() -> None:
    """Before any simulation: MJX has no kinetic-energy sensor for diagnostics=1; Warp and MuJoCo C have one."""
    with pytest.raises(ParameterError, match=r"^backend=mjx cannot run diagnostics=1: .*mjSENS_E_KINETIC\)$"):
        check_settings({**DEFAULTS, "backend": "mjx", "diagnostics": 1})
    for backend in ("mujoco", "warp"):
        check_settings({**DEFAULTS, "backend": backend, "diagnostics": 1})


def test_rimless_wheel_on_mjx_passes_its_fast_checks(request: pytest.FixtureRequest) -> None:
    """The rimless wheel's fast-preset validation on MJX (x64), run by the findings command in a process of its own
    (``conftest.MJX_RUN``, started at collection; under pytest-xdist, here): every check MuJoCo C's gate gates on that
    run passes against MuJoCo C's tolerances (the others are the gate's to watch), and the record carries MJX's
    compile seconds."""
    _require("mjx")
    from conftest import MJX_RUN, mjx_run_key, start_mjx_run

    if mjx_run_key not in request.config.stash:  # not started at collection (a pytest-xdist worker): start it now
        request.config.stash[mjx_run_key] = start_mjx_run()
    process, out = request.config.stash[mjx_run_key]
    output, _ = process.communicate(timeout=1800)
    assert process.returncode == 0, output.decode()
    scenario, backend, precision, preset = MJX_RUN
    record = json.loads((out / "json" / f"{scenario}-{preset}-{backend}-{precision}.json").read_text())
    table = "\n".join(f"{c['name']}: {c['error']:.3g} (tolerance {c['tolerance']:.3g})" for c in record["checks"])
    assert not failed_gated_checks("rimless-wheel[fast]", record["checks"]), table  # the C gate's gated checks
    assert {c["name"] for c in record["checks"]} >= {"omega_post_impact", "eigenvalue", "basins", "stable"}
    assert record["settings"]["backend"] == "mjx" and record["settings"]["precision"] == "float64"
    assert record["compile_s"] > 0


def test_rimless_wheel_on_warp_as_measured() -> None:
    """The rimless wheel's fast-preset validation on MuJoCo Warp (float32): every check MuJoCo C's gate gates passes
    (the others are the gate's to watch), and the eigenvalue error is Warp's own: 8.9e-3 measured here at the searched
    fast preset (0.93 ms steps; 7.1e-3 with the starts' velocities scaled by 1 + 1e-6), against MuJoCo C's 2.0e-5:
    float32 arithmetic through the impact jitter. Asserted within a factor of 2.5 of the measurement, as machines
    differ at that level; the gated check above bounds it by its tolerance, 2e-2."""
    from mjpoincare.commands.validation import run_validation

    _require("warp")
    result = run_validation("rimless-wheel", {"backend": "warp"}, "fast")
    assert not failed_gated_checks("rimless-wheel[fast]", result.to_dict()["checks"]), result.table()
    eigenvalue = next(c for c in result.checks if c.name == "eigenvalue")
    assert 8.9e-3 / 2.5 <= eigenvalue.error <= 8.9e-3 * 2.5, result.table()
