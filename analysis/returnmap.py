"""Empirical Poincaré return maps fitted from section samples.

A batch of simulated trajectories gives, on a Poincaré section, consecutive samples
``x_k -> x_{k+1}``.  The modules listed below fit a low-degree polynomial map ``x_next = F(x)``
to those pairs by least squares, locate its fixed point, linearise it there and estimate the
uncertainty of all of it by a bootstrap over the pairs.  The resulting multipliers
(eigenvalues of the Jacobian) are what the analytic results are compared against.

A map with a one-parameter family of fixed points (a neutral direction, multiplier 1) has no
isolated fixed point; :func:`fit_drifting_cycle` reads such a map at one member of the family
instead, together with the drift along the family that a biased map shows there.

Only numpy and scipy are used.

Modules (each imports only those above it); this module re-exports their public API:

* :mod:`.returnmap_polynomial`: the monomial basis, its gradients and the per-step regression
* :mod:`.returnmap_samples`: the pairs of consecutive crossings and the fit-free multiplier
* :mod:`.returnmap_fixed_point`: the fitted map at its isolated fixed point, with a bootstrap
* :mod:`.returnmap_drifting`: the fitted map on a family of cycles, with the drift along it
"""

from __future__ import annotations

from mjpoincare.analysis.returnmap_drifting import DriftingCycleFit, fit_drifting_cycle
from mjpoincare.analysis.returnmap_fixed_point import ReturnMapFit, fit_return_map, replicate_list
from mjpoincare.analysis.returnmap_polynomial import regress_at
from mjpoincare.analysis.returnmap_samples import convergence_ratio, sample_pairs

__all__ = ["DriftingCycleFit", "ReturnMapFit", "convergence_ratio", "fit_drifting_cycle", "fit_return_map",
           "regress_at", "replicate_list", "sample_pairs"]
