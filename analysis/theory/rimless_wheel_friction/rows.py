"""The planar rimless wheel's stick-slip variables of recorded rows (002 = Gamus & Or 2015, Sec. 3 and eq 35):
theta wrapped to one step, theta_dot, the stance foot's slip speed x_dot, the lowest foot's clearance, and the
contact force per unit mass a_hub - g (the spokes are massless), classified by
:func:`mjpoincare.analysis.stick_slip_phases.stance_rows`; and the impact window of a soft contact (numpy only)."""

from __future__ import annotations

import math
from dataclasses import dataclass

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


@dataclass(frozen=True)
class StanceContact:
    """The stance foot's contact in MuJoCo's contact frame (slope normal n, slope tangent t), every row (B, T), SI:
    distance ``dist`` (m, < 0: penetration), velocity J qvel (``v_n``, ``v_t``), the step's constrained acceleration
    J qacc (``a_n``, ``a_t``; NaN in the last row) and the normal contact force ``f_n`` (N)."""

    dist: np.ndarray
    v_n: np.ndarray
    v_t: np.ndarray
    a_n: np.ndarray
    a_t: np.ndarray
    f_n: np.ndarray


def stance_contact(*, pitch: np.ndarray, pitch_rate: np.ndarray, hub_x_dot: np.ndarray, hub_z: np.ndarray,
                   hub_z_dot: np.ndarray, gravity: np.ndarray, spokes: int, leg_length: float, foot_radius: float,
                   timestep: float, mass: float) -> StanceContact:
    """:class:`StanceContact` of the recorded rows (as :func:`wheel_rows`; ``mass`` the wheel's, kg, all at the hub).

    MuJoCo puts a sphere-plane contact midway between the surfaces, r + dist/2 below the foot's centre, so the
    tangential lever of the pitch rate is (l - r) cos theta + r + dist/2 and the normal one (l - r) sin theta; the
    accelerations are the rows' forward differences, J qacc exactly for Euler and implicitfast (no J_dot term:
    MuJoCo's solver works on J qacc). The normal force is the hub's momentum rate m (z_ddot - g_n)."""
    l, r, dt = leg_length, foot_radius, timestep
    theta = wrap_phase(pitch, math.pi / spokes)
    dist = hub_z - (l - r) * np.cos(theta) - r
    normal_lever, tangent_lever = (l - r) * np.sin(theta), (l - r) * np.cos(theta) + r + 0.5 * dist
    tail = np.full((pitch.shape[0], 1), np.nan)
    z_ddot = np.concatenate([np.diff(hub_z_dot, axis=1) / dt, tail], axis=1)
    x_ddot = np.concatenate([np.diff(hub_x_dot, axis=1) / dt, tail], axis=1)
    theta_ddot = np.concatenate([np.diff(pitch_rate, axis=1) / dt, tail], axis=1)
    return StanceContact(dist=dist, v_n=hub_z_dot + normal_lever * pitch_rate,
                         v_t=hub_x_dot - tangent_lever * pitch_rate, a_n=z_ddot + normal_lever * theta_ddot,
                         a_t=x_ddot - tangent_lever * theta_ddot, f_n=mass * (z_ddot - float(gravity[2])))
