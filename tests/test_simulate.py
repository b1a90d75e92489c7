"""Tests of the shared MuJoCo helpers in mjpoincare.simulation.simulate: the fractional guard step and the plain render
clip."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjpoincare.core.seam import STATE_SPEC
from mjpoincare.engines.backends.mujoco_c import fractional_step
from mjpoincare.simulation.simulate import initial_states, plain_clip

BALL = """<mujoco><option timestep="0.01" gravity="0 0 -9.81"/><worldbody>
<body><freejoint/><geom type="sphere" size="0.1" mass="1"/></body></worldbody></mujoco>"""


@pytest.fixture
def model() -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(BALL)


def test_fractional_step_advances_by_the_fraction_and_restores_the_timestep(model: mujoco.MjModel) -> None:
    data = mujoco.MjData(model)
    data.qvel[2] = 1.0
    fractional_step(model, data, 0.004)
    assert model.opt.timestep == 0.01
    assert data.time == pytest.approx(0.004, abs=1e-15)
    # semi-implicit Euler over h: v = 1 - g h, z = h v
    assert data.qvel[2] == pytest.approx(1.0 - 9.81 * 0.004, abs=1e-12)
    assert data.qpos[2] == pytest.approx(0.004 * (1.0 - 9.81 * 0.004), abs=1e-12)


def test_fractional_step_restores_the_timestep_when_the_step_raises(model: mujoco.MjModel,
                                                                  monkeypatch: pytest.MonkeyPatch) -> None:
    def fail(*_: object) -> None:
        raise RuntimeError("step failed")

    monkeypatch.setattr(mujoco, "mj_step", fail)
    with pytest.raises(RuntimeError):
        fractional_step(model, mujoco.MjData(model), 0.002)
    assert model.opt.timestep == 0.01


def test_plain_clip_is_trajectory_0_stepped(model: mujoco.MjModel) -> None:
    qpos = np.array([[0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0], [5.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0]])
    qvel = np.array([[1.0, 0.0, 2.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    state0 = initial_states(model, qpos, qvel)
    states = plain_clip(model, state0, 7)
    assert states.shape == (7, state0.shape[1])
    data = mujoco.MjData(model)
    mujoco.mj_setState(model, data, state0[0], STATE_SPEC)
    expected = np.empty_like(states)
    for k in range(7):
        mujoco.mj_step(model, data)
        mujoco.mj_getState(model, data, expected[k], STATE_SPEC)
    np.testing.assert_allclose(states, expected, rtol=0, atol=1e-12)


@pytest.mark.parametrize("events", [False, True])
def test_a_rollout_ends_at_the_first_chunk_its_stop_test_accepts(model: mujoco.MjModel, events: bool) -> None:
    """Adaptive stopping: ``stop`` is asked after every chunk; the rollout ends at the first True."""
    from mjpoincare.simulation.simulate import event_rollout, rollout_batch

    start = initial_states(model, np.zeros((2, model.nq)) + np.array([0, 0, 1, 1, 0, 0, 0]), np.zeros((2, model.nv)))
    seen: list[int] = []

    def consume(chunk: object, *_: object) -> np.ndarray:
        seen.append(1)
        return np.full(2, 10)

    stop = lambda: len(seen) == 3  # noqa: E731
    if events:
        report = event_rollout(model, start, 100, consume, chunk_steps=10, threads=1, stop=stop)
    else:
        report = rollout_batch(model, start, 100, consume, chunk_steps=10, threads=1, stop=stop)
    assert len(seen) == 3
    assert report.steps == 3 * 10 * 2


def test_a_finished_trajectory_is_stepped_no_further_and_the_others_step_as_in_the_whole_batch(
        model: mujoco.MjModel) -> None:
    """``finished``: a trajectory it marks is NaN in every later chunk, never flagged diverged and never counted as
    stepped; the others' rows are those of the batch run whole, bit for bit; the rollout ends when all are done."""
    from mjpoincare.simulation.simulate import rollout_batch

    qpos = np.tile([0, 0, 1, 1, 0, 0, 0], (3, 1)).astype(float)
    qpos[:, 2] = [1.0, 2.0, 3.0]
    start = initial_states(model, qpos, np.zeros((3, model.nv)))
    chunks: dict[bool, list[np.ndarray]] = {True: [], False: []}
    done_after = np.array([1, 2, 3])  # chunks after which each trajectory is finished
    for retire in (False, True):
        def consume(chunk: object, retire: bool = retire) -> None:
            chunks[retire].append(np.array(chunk.qpos))  # type: ignore[attr-defined]

        finished = (lambda: len(chunks[True]) >= done_after) if retire else None
        report = rollout_batch(model, start, 50, consume, chunk_steps=10, threads=2, finished=finished)
        assert not report.diverged.any()
    assert len(chunks[True]) == 3 and len(chunks[False]) == 5
    for k, (kept, whole) in enumerate(zip(chunks[True], chunks[False], strict=False)):
        for b in range(3):
            if k < done_after[b]:
                np.testing.assert_array_equal(kept[b], whole[b])
            else:
                assert np.isnan(kept[b]).all()
    assert report.steps == 10 * int(done_after.sum())
