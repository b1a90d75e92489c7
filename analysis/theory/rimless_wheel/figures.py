"""The rimless wheel's runs from a mid-swing state, as in the phase plots of 003 (Kisa 2020) Figs. 5, 6, 12 and 13.

The thesis starts its figure runs at a stance state (theta(0), theta_dot(0)), not on the post-impact section: the first
impact follows from the stance energy integral (003 eqs 3.3-3.5, theta'' = rate2 sin theta) and the impact law (003 eq
3.11, beta of 002 eq 14), and every later post-impact speed from the return map (003 eqs 3.13/3.14 corrected).
"""

from __future__ import annotations

import math

import numpy as np
from mjpoincare.analysis.theory.rimless_wheel.map import return_map
from mjpoincare.analysis.theory.rimless_wheel.params import RimlessWheel
from numpy.typing import NDArray
from scipy.optimize import brentq


def first_post_impact_speed(w: RimlessWheel, theta: float, omega: float) -> float:
    """The post-impact speed of the first impact after the stance state (theta, omega) (003 Sec. 3.3, Figs. 5-13).

    The wheel moves towards the spoke ahead in its direction s = sign(omega), at theta = gamma + s alpha, if its
    energy carries it over the highest point between (003 eq 3.3: omega^2 + 2 rate2 (cos theta - cos phi) > 0 at the
    phi of that interval nearest the vertical); otherwise it rocks back and lands on the spoke behind, at
    gamma - s alpha. The speed there (energy integral, 003 eq 3.5) times beta (003 eq 3.11) is the result, signed by
    the direction of the step that ends in the impact.
    """
    if omega == 0.0:
        raise ValueError("a mid-swing start needs a nonzero speed")
    s = math.copysign(1.0, omega)
    ahead = w.slope + s * w.alpha
    peak = min(max(0.0, min(theta, ahead)), max(theta, ahead))
    if omega**2 + 2.0 * w.rate2 * (math.cos(theta) - math.cos(peak)) <= 0.0:
        s, ahead = -s, w.slope - s * w.alpha
    speed = math.sqrt(omega**2 + 2.0 * w.rate2 * (math.cos(theta) - math.cos(ahead)))
    return s * w.beta * speed


def figure_sequence(w: RimlessWheel, theta: float, omega: float, impacts: int) -> NDArray[np.float64]:
    """The first ``impacts`` post-impact speeds theta_dot_0, theta_dot_1, ... of a run from the stance state
    (theta, omega): :func:`first_post_impact_speed`, then the return map (003 eqs 3.13/3.14 corrected)."""
    out = [first_post_impact_speed(w, theta, omega)]
    while len(out) < impacts:
        out.append(float(return_map(w, out[-1])))
    return np.asarray(out)


def existence_bound_curve(alpha: float, kappa: float = 0.0) -> float:
    """gamma*(alpha), the Ω4 curve of 003 Fig. 14 for a real half spoke angle alpha in (0, pi/4): the slope where the
    generalised (3.16) holds with equality, beta^2 K/(1 - beta^2) = omega_f^2 (in units of rate2, so g, l drop out:
    beta^2 4 sin gamma sin alpha/(1 - beta^2) = 2 (1 - cos(gamma - alpha)), beta = (cos 2 alpha + kappa)/(1 + kappa),
    002 eq 14). At alpha = pi/n it is :func:`~mjpoincare.analysis.theory.rimless_wheel.existence_bound`."""
    if not 0.0 < alpha < math.pi / 4:
        raise ValueError(f"alpha must be in (0, pi/4) (got {alpha!r})")
    beta = (math.cos(2.0 * alpha) + kappa) / (1.0 + kappa)

    def gap(slope: float) -> float:
        gain = beta**2 * 4.0 * math.sin(slope) * math.sin(alpha) / (1.0 - beta**2)
        return gain - 2.0 * (1.0 - math.cos(slope - alpha))

    return float(brentq(gap, 1e-14, alpha * (1.0 - 1e-12), xtol=1e-15, rtol=1e-15))
