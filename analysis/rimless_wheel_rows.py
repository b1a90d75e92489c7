"""The planar rimless wheel's stick-slip variables of recorded rows (002 = Gamus & Or 2015, Sec. 3 and eq 35):
theta wrapped to one step, theta_dot, the stance foot's slip speed x_dot, the lowest foot's clearance, and the
contact force per unit mass a_hub - g (the spokes are massless), classified by
:func:`mjpoincare.analysis.stick_slip_phases.stance_rows`; and the impact window of a soft contact (numpy only)."""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.sections import wrap_phase
from mjpoincare.analysis.stick_slip_phases import Classifier, Rows, stance_rows


def impact_window(timestep: float, timeconst: float, dampratio: float, min_timeconsts: float) -> float:
    """Time after a support transfer that belongs to the impact, s: four of the contact's slow time constants
    2 tc dampratio^2 (tc at least 2 steps, as MuJoCo clamps it), at least ``min_timeconsts`` tc and 3 steps."""
    tc = max(timeconst, 2 * timestep)
    return max(min_timeconsts * tc, 8 * tc * dampratio**2, 3 * timestep)


def wheel_rows(*, time: np.ndarray, pitch: np.ndarray, pitch_rate: np.ndarray, hub_x_dot: np.ndarray,
               hub_z: np.ndarray, hub_z_dot: np.ndarray, gravity: np.ndarray, spokes: int, leg_length: float,
               foot_radius: float, rate_unit: float, timestep: float, cls: Classifier) -> Rows:
    """002's variables of every row from the hub's recorded pitch, pitch rate, x_dot, z and z_dot (all (B, T), SI,
    in the slope frame) and the slope-frame ``gravity`` (3,): rates divided by ``rate_unit`` (omega_c, 1/s) and
    speeds by leg_length omega_c; the force from the recorded velocities, a_k = (v_k+1 - v_k) / dt (exact for
    Euler/implicitfast), zero in the last row."""
    phi = math.pi / spokes
    l, r = leg_length, foot_radius
    theta = wrap_phase(pitch, phi)
    slip = (hub_x_dot - pitch_rate * ((l - r) * np.cos(theta) + r)) / (l * rate_unit)
    clearance = (hub_z - (l - r) * np.cos(theta) - r) / l
    tail = np.zeros((time.shape[0], 1))
    f_t = np.concatenate([np.diff(hub_x_dot, axis=1) / timestep - gravity[0], tail], axis=1)
    f_n = np.concatenate([np.diff(hub_z_dot, axis=1) / timestep - gravity[2], tail], axis=1)
    return stance_rows(time=time, theta=theta, rate=pitch_rate / rate_unit, slip=slip, clearance=clearance,
                       force_t=f_t, force_n=f_n, half_step=phi, timestep=timestep, weight=abs(float(gravity[2])),
                       cls=cls)
