"""The results of 003 (Kisa 2020) Ch. 4 that the passive compass biped covers, and how MuJoCo is run for each
(:mod:`mjpoincare.scenarios.paper_results`): the gait of Fig. 18 (its post-impact state, multipliers, period and step
length) off the scenario's validation at its defaults, which are Fig. 18's parameters; one step of the map (4.18) from
MuJoCo's section states and the stance leg's phase curve of Fig. 18 by the walks of
:mod:`mjpoincare.scenarios.compass_biped.paper_runs`.

003 states no period-doubling slope (nor any multiplier or stability statement for the biped): the theory's
``period_doubling_slope`` is the suite's own continuation, not a result of the paper, so none is declared here."""

from __future__ import annotations

from mjpoincare.scenarios.compass_biped import paper_runs as runs
from mjpoincare.scenarios.paper_results import AtValidation, Curve, Experiment, PaperResult, check_reader

_TESTS = "tests/test_theory_compass_biped.py"

PAPER_RESULTS = (
    PaperResult(
        id="003-biped-fixed-point", paper="003", location="Fig. 18 (caption), Sec. 4.4.2, App. A",
        quantity="post-impact state (theta_st, theta_sw, dtheta_st, dtheta_sw) of the passive gait, m_h = 10, m_l = 5, "
                 "a = b = 0.5, gamma = 0.04 (rad, rad/s)",
        paper_value="(-0.207, 0.287, 1.041, 0.481)",
        independent="theory.fixed_point (Newton shooting on the exact hybrid model) against the thesis' App. A state "
                    f"and the energy balance per step ({_TESTS}::test_kisa_fixed_point, test_energy_balance_per_step)",
        run=AtValidation(check_reader("fixed_point")), gate=True,
        disagreement="none at the printed precision: the suite's state (-0.20740, 0.28740, 1.04064, 0.48103) rounds to "
                     "the caption's; App. A's 16-digit state (-0.2074103, 0.2874190, 1.0409143, 0.4808181) is the "
                     "thesis' forward-simulated attractor with a first-order event location, 2.7e-4 from the exact "
                     "fixed point (its one-step residual ~1e-4); MuJoCo is checked against the exact one"),
    PaperResult(
        id="003-biped-eigenvalues", paper="003", location="eq (4.18), Fig. 18's gait",
        quantity="the 3 multipliers of the post-impact section map at the gait of Fig. 18", paper_value="",
        independent="theory.eigenvalues (central differences of the shooting map) against the legs-parallel "
                    f"section's, which must agree ({_TESTS}::test_kisa_eigenvalues, "
                    "test_legs_parallel_section_is_conjugate)",
        run=AtValidation(check_reader("eigenvalues"))),
    PaperResult(
        id="003-biped-step-period", paper="003", location="eqs (4.6), (4.19), Fig. 18's gait",
        quantity="step period of the gait of Fig. 18 (s)", paper_value="",
        independent=f"theory.step_period (DOP853 to the heel-strike event) ({_TESTS}::test_kisa_fixed_point)",
        run=AtValidation(check_reader("step_period"))),
    PaperResult(
        id="003-biped-step-length", paper="003", location="eqs (4.15)-(4.17), Fig. 18's gait",
        quantity="step length 2 l sin(alpha*) of the gait of Fig. 18 (m)", paper_value="",
        independent=f"theory.step_length from the exact fixed point ({_TESTS}::test_energy_balance_per_step)",
        run=AtValidation(check_reader("step_length"))),
    PaperResult(
        id="003-biped-one-step-map", paper="003", location="eqs (4.15)-(4.18), (4.20)",
        quantity="one step of the legs-parallel Poincare map (swing 4.19, impact 4.17, relabelling 4.7) from MuJoCo's "
                 "own section states (theta, dtheta_st, dtheta_sw): largest residual over the validation's 17 starts "
                 "(the fixed point and 16 perturbed) x 3 steps (rad, rad/s)", paper_value="",
        independent="theory.parallel_return_map (DOP853 swing, closed-form impact) conjugate to the post-impact map "
                    f"({_TESTS}::test_legs_parallel_section_is_conjugate); the impact law conserves both angular "
                    "momenta and reduces to eq (3.11) for m_l -> 0 (test_impact_conserves_both_angular_momenta, "
                    "test_massless_legs_give_rimless_wheel_impact)",
        run=Experiment(runs.one_step_map),
        why="max-abs, the scenario's fixed_point tolerance: measured 2.0e-3 fast, 4.9e-4 accurate (medians 7.9e-4 and "
            "3.1e-4: the soft impact's onset on the step grid, as in the validation's fixed point); the impact law "
            "with massless legs (theta_dot_st+ = cos 2alpha theta_dot_st-) moves the next section state by "
            "0.06-0.23"),
    PaperResult(
        id="003-biped-fig18", paper="003", location="Fig. 18 (top)",
        quantity="the stance leg's phase curve dtheta_st(theta_st) over one step of the gait of Fig. 18 (rad/s)",
        paper_value="", independent="figures.stance_phase_curve (DOP853 dense output, Brent on the angle) against "
                                    f"an RK45 integration with an event at each angle ({_TESTS}::"
                                    "test_stance_phase_curve_against_rk45_events)",
        run=Curve(x=runs.fig18_angles(10), point=runs.fig18_point, theory=runs.fig18_curve, x_label="theta_st (rad)",
                  y_label="dtheta_st (rad/s)"),
        presets=("fast",), gate=True,
        why="absolute, the scenario's fixed_point tolerance (the curve carries the post-impact state through the "
            "swing): measured at most 6.4e-4 rad/s at fast over 10 angles (spread up to 1.2e-3 over the 6-7 "
            "crossings of a 6-step walk from the fixed point); a gait off by the thesis' App. A residual (2.7e-4 in "
            "dtheta_st+) would pass, one with the rimless wheel's impact (m_l -> 0) would not; the same error under "
            "OPENBLAS_CORETYPE=Prescott; 0.4 s at fast"),
)
