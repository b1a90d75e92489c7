"""MuJoCo's soft contact written from its documentation (:mod:`mjpoincare.analysis.soft_contact`) against MuJoCo itself:
the impedance of ``solimp``, and the law of a sliding contact on a puck that slides on a plane and lifts off."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from mjpoincare.analysis.soft_contact import SoftContact, impedance, lift_ratio
from mujoco import rollout

from mjpoincare.core.mjcompat import efc_diag_inverse_inertia

SOLIMP = (0.9, 0.999, 1e-3, 0.5, 2.0)  # a wide, strongly varying impedance: every part of the sigmoid is used
#: A 2 kg puck on slide joints (no rotation: MuJoCo's diagonal inverse inertia is exactly 1/m) with a sphere foot.
XML = """<mujoco><option timestep="2e-4" integrator="implicitfast" cone="elliptic" impratio="10" tolerance="1e-10"
 iterations="100"/><default><geom solref="4e-4 3" solimp="{solimp}" friction="{mu} 0 0"/></default>
<worldbody><geom type="plane" size="5 5 .1"/><body pos="0 0 0.01"><joint name="x" type="slide" axis="1 0 0"/>
<joint name="z" type="slide" axis="0 0 1"/><geom type="sphere" size="0.01" mass="2"/></body></worldbody></mujoco>"""


def _puck(mu: float) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(XML.format(mu=mu, solimp=" ".join(map(str, SOLIMP))))


def test_impedance_is_mujocos() -> None:
    """d(r) against MuJoCo's own ``efc_KBIP`` impedance of the puck's contact at depths across the width."""
    model = _puck(0.5)
    data = mujoco.MjData(model)
    for depth in (1e-5, 2e-4, 5e-4, 8e-4, 2e-3):
        data.qpos[:] = [0.0, -depth]
        mujoco.mj_forward(model, data)
        assert impedance(-depth, SOLIMP) == pytest.approx(float(np.ravel(data.efc_KBIP)[2]), rel=1e-12)


@pytest.mark.parametrize(("mu", "speed"), [(0.1, 0.5), (0.3, 0.2), (0.6, 1.0)])
def test_a_sliding_puck_obeys_the_documented_law(mu: float, speed: float) -> None:
    """Rested on the plane and pushed along it, the puck slides and lifts off: on every row in the cone's middle
    zone the law's residual is at the solver's tolerance, and the normal velocity the step starts with is eq 2's."""
    model = _puck(mu)
    data = mujoco.MjData(model)
    state = np.empty(mujoco.mj_stateSize(model, mujoco.mjtState.mjSTATE_FULLPHYSICS))
    mujoco.mj_getState(model, data, state, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    rest, _ = rollout.rollout(model, data, state[None], nstep=3000)  # settle into the soft contact
    start = rest[0, -1].copy()
    start[3] = speed  # qvel of the slide along the plane (time, qpos x z, qvel x z)
    mujoco.mj_setState(model, data, start, mujoco.mjtState.mjSTATE_FULLPHYSICS)
    mujoco.mj_forward(model, data)
    law = SoftContact(timestep=model.opt.timestep, timeconst=4e-4, dampratio=3.0, solimp=SOLIMP, impratio=10.0, mu=mu,
                      diag_inverse_inertia=float(efc_diag_inverse_inertia(data)[0]))
    assert law.diag_inverse_inertia == pytest.approx(0.5)
    states, _ = rollout.rollout(model, data, start[None], nstep=300)
    rows = np.concatenate([start[None], states[0]])
    dist, v_t, v_n = rows[:-1, 2], rows[:-1, 3], rows[:-1, 4]
    a_t, a_n = np.diff(rows[:, 3]) / law.timestep, np.diff(rows[:, 4]) / law.timestep
    f_n = 2.0 * (a_n + 9.81)
    sliding = (dist < 0) & law.in_cone_zone(dist=dist, v_n=v_n, v_t=v_t, a_n=a_n, a_t=a_t)
    assert sliding.sum() >= 1 and np.nanmax(rows[:, 2]) > 0  # it slid, and it left the surface
    residual = law.sliding_law_residual(dist=dist, v_n=v_n, v_t=v_t, a_n=a_n, a_t=a_t, f_n=f_n)[sliding]
    assert residual.max() < 1e-9
    predicted = law.sliding_normal_velocity(dist=dist, v_t=v_t, a_n=a_n, a_t=a_t, f_n=f_n)
    np.testing.assert_allclose(predicted[sliding], v_n[sliding], rtol=0, atol=1e-9 * mu * speed)


def test_lift_ratio_is_one_at_mu_v_t() -> None:
    assert lift_ratio(np.array([0.02]), np.array([-0.1]), 0.2) == pytest.approx([1.0])
