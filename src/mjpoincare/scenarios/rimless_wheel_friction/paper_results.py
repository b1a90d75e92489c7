"""The results of 002 (Gamus & Or 2015) Sec. 3 that the friction wheel covers, and how MuJoCo is run for each
(:mod:`mjpoincare.scenarios.paper_results`)."""

from __future__ import annotations

from mjpoincare.scenarios.paper_results import AtValidation, PaperResult, check_reader

PAPER_RESULTS = (
    PaperResult(
        id="002-wheel-a-fixed-point", paper="002", location="Sec. 3.2, Fig. 3.5(a)",
        quantity="Type A (sticking) gait's mid-stance pitch rate, n = 10, kappa = 1/3, alpha = 13 deg, mu = 1 "
                 "(nondimensional)",
        paper_value="", independent="theory.sticking_fixed_point (closed form, eq 17) against the event-driven "
                                    "solve_ivp step (tests/test_theory_rimless_wheel_friction.py)",
        run=AtValidation(check_reader("midstance_rate"), {"mu": "1"})),
    PaperResult(
        id="002-wheel-a-multiplier", paper="002", location="Sec. 3.2, eq (17)",
        quantity="Type A gait's multiplier lambda = beta^2 (mu = 1)", paper_value="",
        independent="beta^2 in closed form against a finite difference of the solve_ivp map",
        run=AtValidation(check_reader("eigenvalue"), {"mu": "1"})),
)
