"""The results of 003 (Kisa 2020) Sec. 3 that the planar rimless wheel covers, and how MuJoCo is run for each
(:mod:`mjpoincare.scenarios.paper_results`): the rolling gait's fixed point, multiplier, impact law, period and basins
off the scenario's validation; the regions of Table 1, the existence bound (3.16) and Fig. 14's curve of it, the
gamma > alpha branch of (3.14), the standing multiplier and the phase plots of Figs. 5, 6, 12 and 13 by the dedicated
runs of :mod:`mjpoincare.scenarios.rimless_wheel.paper_runs`."""

from __future__ import annotations

import math

from mjpoincare.analysis.theory import rimless_wheel as theory
from mjpoincare.scenarios.paper_results import AtValidation, Bracket, Curve, Experiment, PaperResult, check_reader
from mjpoincare.scenarios.rimless_wheel import paper_runs as runs

_TESTS = "tests/test_theory_rimless_wheel.py"
_FLIGHT = ("the map assumes the stance spoke can pull (bilateral contact); its normal force N/(mg) = cos theta - "
           "l omega^2/g is negative at the end of every step of a rolling gait above the no-flight bound "
           "gamma_fly(pi/8) = 0.2621 rad (theory.no_flight_bound, test_no_flight_bound_table), which lies below "
           "alpha = 0.3927: ")

PAPER_RESULTS = (
    PaperResult(
        id="003-wheel-roll-fixed-point", paper="003", location="Sec. 3.3.2, Thm 3.13",
        quantity="rolling fixed point omega*_roll = 2 cot 2alpha sqrt((g/l) sin gamma sin alpha), post-impact rate, "
                 "n = 8, gamma = 0.08 (rad/s)",
        paper_value="", independent="theory.rolling_fixed_point (closed form) against the event-driven solve_ivp "
                                    f"fixed point (hybrid_fixed_point; {_TESTS}::test_fixed_point_period_forces_"
                                    "against_hybrid, test_table_16)",
        run=AtValidation(check_reader("omega_post_impact"))),
    PaperResult(
        id="003-wheel-roll-multiplier", paper="003", location="Thm 3.13 (Lemmas 3.11-3.12)",
        quantity="rolling fixed point's multiplier P'(omega*_roll) = cos^2 2alpha, n = 8, gamma = 0.08", paper_value="",
        independent="beta^2 in closed form against a finite difference of the event-driven solve_ivp map "
                    f"({_TESTS}::test_multiplier_against_hybrid, test_return_map_derivative_by_finite_differences)",
        run=AtValidation(check_reader("eigenvalue"))),
    PaperResult(
        id="003-wheel-impact-coefficient", paper="003", location="eq (3.11)",
        quantity="impact law omega+ = cos(2alpha) omega-, n = 8", paper_value="",
        independent="beta against the event-driven solve_ivp map's plastic impact (hybrid.plastic_impact; "
                    f"{_TESTS}::test_return_map_matches_hybrid)",
        run=AtValidation(check_reader("impact_coefficient"))),
    PaperResult(
        id="003-wheel-step-period", paper="003", location="eqs (3.3)-(3.5)",
        quantity="forward swing time at omega*_roll, n = 8, gamma = 0.08 (s)", paper_value="",
        independent="theory.step_period (quadrature of the energy integral) against the event-driven solve_ivp "
                    f"step time ({_TESTS}::test_fixed_point_period_forces_against_hybrid)",
        run=AtValidation(check_reader("step_period"))),
    PaperResult(
        id="003-wheel-basins", paper="003", location="eqs (3.17)-(3.18), Def. 3.20, Table 1 (Ω5 column)",
        quantity="end state (rolling/standing) of a grid of post-impact speeds, n = 8, gamma = 0.08 (fraction "
                 "of judged starts that agree)", paper_value="",
        independent="theory.predicted_outcome (the band formulas) against iterating the map and the event-driven "
                    f"reference ({_TESTS}::test_basin_bands_table_and_outcomes)",
        run=AtValidation(check_reader("basins"))),
    PaperResult(
        id="003-wheel-region-1", paper="003", location="Table 1, Ω1 column; Fig. 7",
        quantity="end state of four post-impact starts (0.2, 1, -0.5, -1.5 rad/s) at gamma = pi/7 > alpha = pi/8: "
                 "R_A(omega*_roll) = R, no omega*_stop (count of starts that disagree)",
        paper_value="omega*_stop does not exist; omega*_roll as. stable, R_A = R",
        independent="theory.region and theory.predicted_outcome against 200 iterations of the map from random "
                    f"starts ({_TESTS}::test_outcomes_in_other_regions)",
        run=Experiment(runs.region_1),
        miss=_FLIGHT + "MuJoCo's wheel leaves the slope from every start and flies (highest flight 1.77 m fast, "
                       "2.69 m accurate), instead of rolling onto omega*_roll = 2.5526 rad/s",
        why="a count: every start must end as Table 1 says (rolling within the scenario's omega_post_impact "
            "tolerance of omega*_roll, or standing)"),
    PaperResult(
        id="003-wheel-region-2", paper="003", location="Table 1, Ω2 column; Fig. 8",
        quantity="end state of four post-impact starts (0.2, 1, -0.5, -1.5 rad/s) at gamma = alpha = pi/8: "
                 "R_A(omega*_roll) = R minus {0} (count of starts that disagree)",
        paper_value="omega*_stop unstable; omega*_roll as. stable, R_A = R minus {0}",
        independent="theory.region and theory.predicted_outcome against 200 iterations of the map from random "
                    f"starts ({_TESTS}::test_outcomes_in_other_regions)",
        run=Experiment(runs.region_2),
        miss=_FLIGHT + "MuJoCo's wheel leaves the slope from every start and flies (highest flight 0.80 m fast, "
                       "0.43 m accurate), instead of rolling onto omega*_roll = 2.3973 rad/s",
        why="a count: every start must end as Table 1 says"),
    PaperResult(
        id="003-wheel-region-3", paper="003", location="Table 1, Ω3 column; Figs. 5, 9",
        quantity="end state of five post-impact starts (0.5, 1.3, 2 omega_f; 0.5, 1.5 omega_b) at gamma = 0.025 "
                 "(Fig. 5's slope): R_A(omega*_stop) = R minus H, no omega*_roll (count of starts that disagree)",
        paper_value="omega*_roll does not exist; omega*_stop as. stable, R_A = R minus H",
        independent="theory.region and theory.predicted_outcome against 200 iterations of the map from random "
                    f"starts ({_TESTS}::test_outcomes_in_other_regions, test_omega3_has_no_rolling_point)",
        run=Experiment(runs.region_3),
        why="a count: every start must stand (|omega| below 2 % of its largest over the last second); measured: all "
            "five stand at fast and accurate, none flies (highest 0.14 mm fast, 0.21 mm accurate); the nearest wrong "
            "physics, a rolling gait below the existence bound, would roll on from 1.3 and 2 omega_f"),
    PaperResult(
        id="003-wheel-region-4", paper="003", location="Table 1, Ω4 column; Figs. 10, 14",
        quantity="on the curve gamma = gamma*(alpha) (n = 8, 0.068221 rad): the semistable ghost of omega*_roll at "
                 "omega_f, R_A = (omega_f, inf) minus H; MuJoCo's lowest forward post-impact speed from 1.5 omega_f "
                 "against omega_f (rad/s)",
        paper_value="omega*_roll does not exist; R_A(omega*_roll) = (omega_f, inf) minus H",
        independent="theory.existence_bound (brentq on the generalised 3.16) against the derivation page's table "
                    f"({_TESTS}::test_existence_bound_table); theory.forward_threshold (eq 3.4)",
        run=Experiment(runs.region_4),
        why="relative, the scenario's omega_post_impact tolerance: the ghost's speed is MuJoCo's speed over the top "
            "of a step; measured 3.1e-3 fast (13 forward impacts, still rolling at the end of the 21.5 s run; a 30 s "
            "run rocks back after 16, its lowest speed 4.6e-3 below omega_f) and 4.4e-4 accurate (12 forward "
            "impacts, still rolling); a wheel off the curve by the bisection's 5e-4 rad settles 0.5 % above omega_f "
            "(Ω5) or rocks back within 8 steps (Ω3)"),
    PaperResult(
        id="003-wheel-region-5", paper="003", location="Table 1, Ω5 column; eqs (3.17)-(3.18); Fig. 11",
        quantity="end state of one post-impact start in each basin band next to the origin at gamma = pi/15 (Figs. "
                 "11-13's slope): (0, omega_f), (omega_2^0, 0), above omega_f, I^0_roll, I^1_stop, I^1_roll (count of "
                 "starts that disagree)",
        paper_value="both fixed points as. stable, R_A by (3.17)-(3.18)",
        independent="theory.basin_band_edges and predicted_outcome against the derivation page's band table and "
                    f"the event-driven reference ({_TESTS}::test_basin_bands_table_and_outcomes)",
        run=Experiment(runs.region_5),
        why="a count: every start must end as (3.17)-(3.18) say, the rolling ones within the scenario's "
            "omega_post_impact tolerance of omega*_roll = 1.7670; measured: all six agree, rolling at 1.7717 fast "
            "(+2.7e-3) and 1.7680 accurate (+5.7e-4); a band edge misplaced by one band (I^1_stop read as rolling) "
            "flips a start"),
    PaperResult(
        id="003-wheel-existence-bound", paper="003", location="eq (3.16), Lemma 3.7",
        quantity="existence bound gamma*(pi/8): the slope below which no rolling cycle exists, n = 8 (rad)",
        paper_value="", independent="theory.existence_bound (brentq on the generalised 3.16) against the derivation "
                                    f"page's table ({_TESTS}::test_existence_bound_table)",
        run=Bracket(low=0.05, high=0.09, below=runs.no_rolling_cycle, theory=runs.existence_bound,
                    tolerance=runs.CURVE_TOLERANCE * theory.existence_bound(runs.SPOKES), unit="rad"),
        presets=("fast",),
        why="MuJoCo's side of the bound: a wheel started at 1.5 omega_f rolls back within twice the theory's fall time "
            "just below the bound (runs.bound_seconds); the tolerance, 3 % of gamma*, is the shift a 1 % error in the "
            "impact coefficient beta (the scenario's fast impact_coefficient tolerance) makes (2.8 %); it rejects the "
            "bound with the energy coefficient beta^2 in place of beta (0.1324 rad); measured 6e-5 rad at fast"),
    PaperResult(
        id="003-wheel-fig14", paper="003", location="Fig. 14",
        quantity="the Ω4 curve gamma*(alpha) between Ω3 and Ω5 at alpha = pi/n, n = 6, 7, 8, 9, 10, 12, 16, 20 (rad)",
        paper_value="", independent="paper_runs.fig14_curve (figures.existence_bound_curve, brentq on the generalised "
                                    "3.16 for real alpha) against theory.existence_bound at alpha = pi/n "
                                    f"({_TESTS}::test_existence_bound_curve_matches_spoke_counts)",
        run=Curve(x=tuple(math.pi / n for n in (6, 7, 8, 9, 10, 12, 16, 20)), point=runs.fig14_point,
                  theory=runs.fig14_curve, x_label="alpha (rad)", y_label="gamma (rad)"),
        presets=("fast",),
        why="relative, 3 %: the shift a 1 % error in beta makes at n = 8 (2.8 %); each point a bisection of "
            "runs.no_rolling_cycle to 0.75 % of gamma*; measured at fast: 0.74 % at n = 12, 0.66 % at n = 16, the "
            "others within 0.04 % (the bisection's resolution); the run length grows with n as the ghost's fall "
            "time (11 s at n = 6, 165 s at n = 20: shorter runs read small-alpha slopes as rolling, 9 % low at "
            "n = 20 with 30 s)"),
    PaperResult(
        id="003-wheel-steep-branch", paper="003", location="eq (3.14), gamma > alpha",
        quantity="next post-impact speed from three starts between omega_b and -sqrt(K), n = 12, gamma = pi/6 = "
                 "2 alpha (rad/s)",
        paper_value="", independent="theory.return_map (corrected branch) against the event-driven solve_ivp map "
                                    f"({_TESTS}::test_steep_branch_at_twelve_spokes, "
                                    "test_corrected_backward_branch_for_steep_slope)",
        run=Experiment(runs.steep_branch),
        disagreement="(3.14) as printed puts the backward threshold at omega_b (eq 3.7), so these starts rock back "
                     "and return with -cos(2alpha) omega = +1.98, +2.01, +2.05 rad/s; the suite's corrected branch "
                     "(threshold -sqrt(K): a backward step from gamma + alpha to gamma - alpha > 0 never passes the "
                     "vertical) has them complete a backward step, -0.354, -0.501, -0.613 rad/s; the event-driven "
                     "solve_ivp agrees with the corrected branch to 1e-9, and MuJoCo is checked against it",
        why="max-abs, the scenario's omega_post_impact tolerance times the speed scale sqrt(K) = 2.253 rad/s: measured "
            "0.010 fast, 6.1e-4 accurate; the printed branch is 2.3-2.7 rad/s away; the starts keep the spoke "
            "loaded (highest flight 4.4 mm fast, 0.24 mm accurate)"),
    PaperResult(
        id="003-wheel-standing-multiplier", paper="003", location="Thm 3.10, eqs (3.10)-(3.11)",
        quantity="standing fixed point's multiplier P'(0) = -cos 2alpha: ratio of successive post-impact speeds of "
                 "a rocking wheel, n = 8, gamma = 0.025", paper_value="",
        independent="theory.standing_multiplier (-beta) against the event-driven reference's rocking impacts, ratio "
                    f"-cos 2alpha each ({_TESTS}::test_hybrid_zeno_standing)",
        run=Experiment(runs.standing_multiplier),
        why="absolute, the scenario's tolerance on the rolling multiplier: measured 2.2e-3 fast (spread 0.010 over "
            "12 impacts), 9.2e-5 accurate (spread 2.1e-4); rejects the rolling multiplier's form beta^2 = 0.5 and "
            "an elastic impact's -1"),
    PaperResult(
        id="003-wheel-four-spokes", paper="003", location="Sec. 3.1 (the restriction to n >= 5), eq (3.11)",
        quantity="kinetic energy kept by a 4-spoked wheel's impact, as a fraction of the pre-impact energy, "
                 "gamma = 0.01, mu = 2 (its sticking impact needs tan alpha = 1), post-impact start 2.45 rad/s",
        paper_value="wheels with 3 or 4 legs lose all of their energy upon collision",
        independent="beta^2 = (kappa/(1 + kappa))^2 (cos 2alpha = 0) against the event-driven solve_ivp reference, "
                    f"which stops dead at the first impact ({_TESTS}::test_hybrid_four_spokes_stop_dead)",
        run=Experiment(runs.four_spokes),
        why="absolute, the square of the scenario's impact_coefficient tolerance (the energy a speed ratio that "
            "large keeps): measured 5e-16 fast, 4e-22 accurate once the soft contact's ringing on the two feet has "
            "died (0.1 s after the impact; within it |omega| reaches 2.8 % (fast) and 3.6 % (accurate) of the "
            "pre-impact speed, without a step); a wheel keeping the n = 5 ratio cos(2 pi/5) = 0.31 would keep 9.5 %"),
    PaperResult(
        id="003-wheel-fig5", paper="003", location="Fig. 5",
        quantity="post-impact speeds theta_dot_0..5 and the limit of the run from theta(0) = -0.132, theta_dot(0) = "
                 "2 at gamma = 0.025 (rad/s)",
        paper_value="theta_dot_n -> omega*_stop",
        independent="figures.figure_sequence against the derivation page's table (Sec. 1.8) and its first impact "
                    f"against an event-driven solve_ivp ({_TESTS}::test_figure_sequence_from_mid_swing_state, "
                    "test_first_post_impact_speed_against_ode)",
        run=Experiment(runs.fig5),
        why="the largest gap over the largest speed 1.66 rad/s, the scenario's omega_post_impact tolerance: "
            "measured 2.9e-3 fast, 3.6e-4 accurate (per speed, relative: at most 3.8e-3 fast and 1.2e-3 accurate, at "
            "the small rocking speed theta_dot_5 = -0.348); no flight (0.33 mm); the nearest wrong physics, an "
            "impact coefficient cos^2 2alpha, stops the wheel at the first impact"),
    PaperResult(
        id="003-wheel-fig6", paper="003", location="Fig. 6",
        quantity="post-impact speeds theta_dot_0..5 and the limit of the run from theta(0) = 0.292, theta_dot(0) = 5 "
                 "at gamma = pi/7 (rad/s)",
        paper_value="theta_dot_n -> omega*_roll from above",
        independent="figures.figure_sequence against the derivation page's table (Sec. 1.8) and its first impact "
                    f"against an event-driven solve_ivp ({_TESTS}::test_figure_sequence_from_mid_swing_state, "
                    "test_first_post_impact_speed_against_ode)",
        run=Experiment(runs.fig6),
        miss=_FLIGHT + "at the start N/(mg) = cos 0.292 - 25/9.81 = -1.59, so MuJoCo's wheel leaves the slope at once "
                       "and runs away (first post-impact speed 5.18 against 3.92; highest flight 2.4 m fast, 3.6 m "
                       "accurate; |omega| up to 27 rad/s) instead of converging to omega*_roll = 2.5526",
        why="as Fig. 5's"),
    PaperResult(
        id="003-wheel-fig12", paper="003", location="Fig. 12",
        quantity="limit of the run from theta(0) = -0.105, theta_dot(0) = -5 at gamma = pi/15: omega*_roll, "
                 "approached from below (rad/s)",
        paper_value="theta_dot_n -> omega*_roll from below",
        independent="figures.figure_sequence (theta_dot_0 = -3.5511 in I^2_roll, then the map) against the "
                    f"derivation page's table ({_TESTS}::test_figure_sequence_from_mid_swing_state); "
                    "theory.rolling_fixed_point",
        run=Experiment(runs.fig12),
        why="relative, the scenario's omega_post_impact tolerance: measured 2.7e-3 fast, 5.7e-4 accurate; the start's "
            "spoke force is negative (N/(mg) = cos 0.105 - 25/9.81 = -1.55), so MuJoCo's wheel flies off its first "
            "step (0.13 m) and lands at -4.02 (fast) against the map's -3.55, but in the same band I^2_roll, so the "
            "limit is the map's"),
    PaperResult(
        id="003-wheel-fig13", paper="003", location="Fig. 13",
        quantity="limit of the run from theta(0) = -0.105, theta_dot(0) = -4.85 at gamma = pi/15: omega*_stop "
                 "(largest |omega| over the last second, rad/s)",
        paper_value="theta_dot_n -> omega*_stop",
        independent="figures.figure_sequence (theta_dot_0 = -3.4455 in I^1_stop, then the map) against the "
                    f"derivation page's table ({_TESTS}::test_figure_sequence_from_mid_swing_state)",
        run=Experiment(runs.fig13),
        miss="the start's spoke force is negative (N/(mg) = cos 0.105 - 4.85^2/9.81 = -1.40: the map's stance would "
             "pull the wheel down), so MuJoCo's wheel flies off (0.08 m fast, 0.10 m accurate) and lands at -3.97 "
             "(fast) / -3.94 (accurate) rad/s instead of the map's -3.4455: in I^2_roll = (-4.813, -3.463), not "
             "I^1_stop = (-3.463, -3.166), so it rolls on to omega*_roll (|omega| 2.5 rad/s at the end)",
        why="standing: below 2 % of omega*_roll"),
)
