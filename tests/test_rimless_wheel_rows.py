"""analysis.theory.rimless_wheel_friction.rows: the planar rimless wheel's stick-slip variables of recorded rows
(002 = Gamus & Or 2015, Sec. 3) and the soft contact's impact window."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mjpoincare.analysis.stick_slip_phases import STICK, Classifier
from mjpoincare.analysis.theory.rimless_wheel_friction.rows import impact_window, wheel_rows


def test_impact_window_is_the_longest_of_its_three_bounds() -> None:
    assert impact_window(2e-4, 4e-4, 3.0, 5.0) == pytest.approx(8 * 4e-4 * 9)  # the slow time constants
    assert impact_window(2e-4, 4e-4, 0.5, 5.0) == pytest.approx(5 * 4e-4)  # at least min_timeconsts tc
    assert impact_window(2e-4, 1e-5, 0.5, 5.0) == pytest.approx(5 * 4e-4)  # tc at least 2 steps
    assert impact_window(1e-2, 1e-3, 0.1, 0.1) == pytest.approx(3e-2)  # at least 3 steps


def test_wheel_rows_of_a_wheel_rolling_without_slip() -> None:
    """A wheel rolling at a constant rate on a fixed foot: the foot does not slip, the lowest foot touches, and the
    contact force per unit mass is the hub's acceleration minus gravity."""
    l, r, dt, unit, spokes = 1.0, 5e-4, 1e-4, 2.0, 10
    phi = math.pi / spokes
    t = np.arange(200) * dt
    pitch = -0.5 * phi + unit * t  # rate 1 nondimensional
    theta = pitch
    rate = np.full(t.size, unit)
    x_dot = rate * ((l - r) * np.cos(theta) + r)
    z = (l - r) * np.cos(theta) + r
    z_dot = -rate * (l - r) * np.sin(theta)
    gravity = np.array([1.5, 0.0, -9.0])
    cls = Classifier(mu=np.array([0.5]), v_thr=1e-3, impact_window=0.0)
    rows = wheel_rows(time=t[None], pitch=pitch[None], pitch_rate=rate[None], hub_x_dot=x_dot[None], hub_z=z[None],
                      hub_z_dot=z_dot[None], gravity=gravity, spokes=spokes, leg_length=l, foot_radius=r,
                      rate_unit=unit, timestep=dt, cls=cls)
    np.testing.assert_allclose(rows.theta[0], theta)
    np.testing.assert_allclose(rows.rate[0], 1.0)
    np.testing.assert_allclose(rows.slip[0], 0.0, atol=1e-12)
    np.testing.assert_allclose(rows.clearance[0], 0.0, atol=1e-12)
    np.testing.assert_allclose(rows.force_t[0, :-1], np.diff(x_dot) / dt - 1.5)
    np.testing.assert_allclose(rows.force_n[0, :-1], np.diff(z_dot) / dt + 9.0)
    assert rows.force_t[0, -1] == rows.force_n[0, -1] == 0.0
    assert (rows.stance[0] == 0).all() and (rows.vmode[0, :-1] == STICK).all()
