"""The results of 002 (Gamus & Or 2015) Sec. 3 that the friction wheel covers, and how MuJoCo is run for each
(:mod:`mjpoincare.scenarios.paper_results`). The paper's set: n = 10, kappa = 1/3, alpha = 13 deg; rates in units of
omega_c (002 eq 11)."""

from __future__ import annotations

from mjpoincare.scenarios.paper_results import (
    AtValidation,
    Bracket,
    Curve,
    Experiment,
    PaperResult,
    Refusal,
    check_reader,
)
from mjpoincare.scenarios.rimless_wheel_friction import paper_runs as runs

#: The independent check of the gaits: the closed forms of 002 eqs 16-17 (sticking) and the Appendix-A stick/slip
#: step by event-driven solve_ivp (analysis/theory/rimless_wheel_friction), pinned against the paper's numbers.
GAITS = ("theory.find_gait (Newton shooting on the event-driven solve_ivp step of 002 Appendix A) against eqs 16-17 "
         "in closed form and the paper's printed values (tests/test_theory_rimless_wheel_friction.py)")
WINDOW = ("theory.attraction_window (bisection on the solve_ivp first step) against eq 26's closed form at mu = inf "
          "(tests/test_theory_rimless_wheel_friction.py)")

#: MuJoCo's convex contact lifts a sliding foot: the mechanism of the wheel's misses at large slip (and of the D+
#: gait's, whose slip grows every step; docs/scenarios/rimless-wheel-friction.md, Findings).
D_PLUS = ("the D+ gait's slip speed grows every step and MuJoCo's sliding foot lifts (v_n grows with mu |v_t|, "
          "analysis/soft_contact.py; the check sliding_contact_law confirms the lift is MuJoCo's contact law): at mu "
          "= 0.23 four of the five starts leave the D+ gait (gait_type error 0.8) and the map has no samples to fit; "
          "at mu = 0.2 the fitted multiplier is 0.169 against 0.344, at mu = 0.1 and 0.15 the wheel flies before the "
          "fit has samples (fast preset)")
SLIP_LIFT = ("MuJoCo's convex soft contact lifts a sliding foot (its normal velocity grows with mu |v_t|, "
             "analysis/soft_contact.py): from the Fig. 3.6 start (slip 0.7) the lowest foot rises to 0.096 l within "
             "the first step (0.041 l from slip 0.3, 0.0055 l from 0.1, 0.00085 l from 0.05; measured at the fast "
             "preset), and the wheel's step table reports a detachment at step 0, where the exact model's foot slides"
             " on the slope with f_n > 0 (002 eq 42)")

UPPER_EDGE = ("MuJoCo's stance foot starts to slide on the first step (at theta 0.16 for mu = 1) and its convex "
              "contact lifts a sliding foot, so the lowest foot's clearance grows smoothly with theta_dot0 long "
              "before the exact model's f_n reaches 0: at mu = 1, 0.0008 l at 1.08, 0.0012 l at 1.09, 0.0027 l at "
              "1.13, 0.0069 l at 1.17 (fast preset); the step table's detachment is a clearance threshold, crossed "
              "non-monotonically between 1.09 and 1.15, so MuJoCo's edge is that threshold's (1.097 to 1.152 by "
              "bisection paths), not the exact model's f_n = 0")

PAPER_RESULTS = (
    PaperResult(
        id="002-wheel-a-fixed-point", paper="002", location="Sec. 3.2, eq (16), Fig. 3.5(a)",
        quantity="Type A gait (sticking, mu = 1): fixed point, mid-stance theta_dot (the paper plots the same orbit's "
                 "post-impact theta_dot*)", paper_value="", independent=GAITS,
        run=AtValidation(check_reader("midstance_rate"), {"mu": "1"}), gate=True),
    PaperResult(
        id="002-wheel-a-multiplier", paper="002", location="Sec. 3.2, eq (17), Fig. 3.5(b)",
        quantity="Type A gait's multiplier lambda = beta^2", paper_value="", independent=GAITS,
        run=AtValidation(check_reader("eigenvalue"), {"mu": "1"}), gate=True),
    PaperResult(
        id="002-wheel-critical-friction", paper="002", location="Sec. 3.2, eq (23), Fig. 3.3(a)",
        quantity="critical friction mu_c = max |f_t/f_n| along the Type A gait", paper_value="0.91",
        independent="theory.critical_friction (eq 22 scanned over the step) against the solve_ivp stance forces",
        run=AtValidation(check_reader("critical_friction"), {"mu": "1"})),
    PaperResult(
        id="002-wheel-impulse-ratio", paper="002", location="Sec. 3.2, eq (25), Fig. 3.3(a) 'x'",
        quantity="sticking impact's impulse ratio F~_t/F~_n (the paper prints its magnitude)", paper_value="0.237",
        independent="theory.impulse_ratio (eq 25 closed form) against the impact's complementarity solution "
                    "(analysis/theory/stick_slip_impact.py)",
        run=Experiment(runs.impulse_ratio), gate=True,
        why="measured 1.1e-3 at the fast preset (spread 2.2e-4 over 25 settled impacts); 0.01 rejects a wheel without "
            "hub inertia (kappa = 0: -0.325) and a frictionless tangent (0)"),
    PaperResult(
        id="002-wheel-b-fixed-point", paper="002", location="Sec. 3.3, Fig. 3.3(b), Fig. 3.5(a)",
        quantity="Type B gait (stick > slip, mu = 0.3): fixed point, mid-stance theta_dot (the paper prints the "
                 "post-impact theta_dot* = 0.8807 of the same orbit)", paper_value="0.8807 (post-impact)",
        independent=GAITS, run=AtValidation(check_reader("midstance_rate"))),
    PaperResult(
        id="002-wheel-b-multiplier", paper="002", location="Sec. 3.3, Fig. 3.5(b)",
        quantity="Type B gait's multiplier (mu = 0.3)", paper_value="", independent=GAITS,
        run=AtValidation(check_reader("eigenvalue"))),
    PaperResult(
        id="002-wheel-b-slip-onset", paper="002", location="Sec. 3.3, eq (22), Fig. 3.3(b)",
        quantity="Type B gait's slip onset angle theta_s (rad, mu = 0.3)", paper_value="",
        independent="the solve_ivp step's stick-to-slip event against eq 22's |sigma| = mu on the sticking orbit",
        run=AtValidation(check_reader("slip_onset"))),
    PaperResult(
        id="002-wheel-b-impact-kind", paper="002", location="Sec. 3.3, eq (44)",
        quantity="Type B gait's impact kind (sticking)", paper_value="sticking",
        independent="the impact's complementarity solution (analysis/theory/stick_slip_impact.py) against eq 25",
        run=AtValidation(check_reader("impact_kind"))),
    PaperResult(
        id="002-wheel-b-phases", paper="002", location="Sec. 3.3, Fig. 3.3(b)",
        quantity="Type B gait's stance phases (stick > forward slip)", paper_value="stick > slip",
        independent=GAITS, run=AtValidation(check_reader("phase_sequence"))),
    PaperResult(
        id="002-wheel-c-gait", paper="002", location="Sec. 3.3, Fig. 3.4(a)",
        quantity="Type C gait exists at mu = 0.24 (slipping impact, slip > stick > slip): the settled type",
        paper_value="C", independent=GAITS, run=AtValidation(check_reader("gait_type"), {"mu": "0.24"})),
    PaperResult(
        id="002-wheel-c-multiplier", paper="002", location="Sec. 3.3, Fig. 3.5(b)",
        quantity="Type C gait's largest multiplier (mu = 0.24)", paper_value="", independent=GAITS,
        run=AtValidation(check_reader("eigenvalue"), {"mu": "0.24"})),
    PaperResult(
        id="002-wheel-d-gait", paper="002", location="Sec. 3.3, Fig. 3.4(b)",
        quantity="Type D+ gait exists at mu = 0.23 (slip throughout): the settled type", paper_value="D",
        independent=GAITS, run=AtValidation(check_reader("gait_type"), {"mu": "0.23"}), miss=D_PLUS),
    PaperResult(
        id="002-wheel-d-multiplier", paper="002", location="Sec. 3.3, Fig. 3.5(b)",
        quantity="Type D+ gait's multiplier (mu = 0.23)", paper_value="about 0.35", independent=GAITS,
        run=AtValidation(check_reader("eigenvalue"), {"mu": "0.23"}), miss=D_PLUS),
    PaperResult(
        id="002-wheel-d-slip-growth", paper="002", location="Sec. 3.3, Fig. 3.5",
        quantity="Type D+ gait's slip growth Delta x_dot per step (mu = 0.23)", paper_value="> 0 (D+)",
        independent=GAITS, run=AtValidation(check_reader("dx_per_step"), {"mu": "0.23"}), miss=D_PLUS),
    PaperResult(
        id="002-wheel-fig36-first-sticking-impact", paper="002", location="Sec. 3.3, Fig. 3.6",
        quantity="the D- transient from (theta_dot, x_dot) = (1.12, 0.7) at mu = 0.3: the impact at which the slip "
                 "first stops (1-based)", paper_value="15",
        independent="theory.settle (the solve_ivp steps) from the same start",
        run=Experiment(runs.first_sticking_impact),
        miss=SLIP_LIFT, why="a count: exact (tolerance 0)"),
    PaperResult(
        id="002-wheel-fig36-slip-per-step", paper="002", location="Sec. 3.3, Fig. 3.6(c)",
        quantity="the D- gait's Delta x_dot per step at mu = 0.3, over the Fig. 3.6 transient", paper_value="-0.0517",
        independent="theory.find_gait('D') at mu = 0.3 (Newton on the solve_ivp step) against the transient's steps",
        run=Experiment(runs.slip_per_step), miss=SLIP_LIFT,
        why="5 % relative: the D+ gait's dx_per_step check holds 1e-2; a sticking impact's law gives Delta x_dot = 0"),
    PaperResult(
        id="002-wheel-fig38b-slip-onset", paper="002", location="Sec. 3.4, Fig. 3.8(b)",
        quantity="first step from theta_dot0 = 1 at mu = 1: the angle where sticking turns to slip (rad)",
        paper_value="0.163", independent="the solve_ivp step's stick-to-slip event (theory.step) against eq 22",
        run=Experiment(runs.slip_onset), gate=True,
        why="measured 2.6e-3 rad at the fast preset (the soft contact's force ratio crosses the cone a few steps "
            "late); 0.01 rad rejects the sticking continuation's detachment angle 0.256 and the Type B gait's own "
            "onset"),
    PaperResult(
        id="002-wheel-fig38b-sticking-detachment", paper="002", location="Sec. 3.4, Fig. 3.8(b) (dotted curve)",
        quantity="the sticking continuation's detachment angle (f_n = 0) from theta_dot0 = 1", paper_value="0.256",
        independent="eq 22's f_n on the sticking orbit from theta_dot0 = 1 (theory.sticking_forces)",
        run=Refusal("the dotted curve is the sticking motion continued past the slip onset at 0.163 rad, a motion "
                    "friction cannot hold at mu = 1 (it needs |f_t/f_n| > 1 there): no simulator with mu = 1 follows "
                    "it, and MuJoCo's wheel slips at 0.1655 rad (002-wheel-fig38b-slip-onset) as the exact model "
                    "does; at larger mu the same continuation is 002-wheel-window-upper's limit")),
    PaperResult(
        id="002-wheel-fig38c-detachment-angle", paper="002", location="Sec. 3.4, Fig. 3.8(c)",
        quantity="from theta_dot0 = theta_dot_max at mu = 1: the angle where f_n touches 0 (rad)",
        paper_value="-0.01", independent="the solve_ivp slip phase's f_n (002 eq 42) at theta_dot_max",
        run=Refusal("at theta_dot_max f_n touches 0 tangentially (a double root; the exact model finds the touch "
                    "at -0.001 rad, the paper -0.01 with a coarse event step): the touch is the edge itself, not an "
                    "event a soft contact shows, and MuJoCo's edge sits 0.014 above the exact one "
                    "(002-wheel-window-upper), where its foot already lifts")),
    PaperResult(
        id="002-wheel-alpha-min", paper="002", location="Sec. 3.2, eq (18), Fig. 3.2",
        quantity="alpha_min: the slope below which the gait does not exist and the wheel rolls back (deg)",
        paper_value="1.4", independent="theory.slope_bounds (eq 18 with equality) against the solve_ivp map's "
                                       "fixed point vanishing (tests/test_theory_rimless_wheel_friction.py)",
        run=Bracket(low=1.0, high=3.0, below=runs.alpha_min_below, theory=runs.alpha_min_theory, tolerance=0.02,
                    unit="deg"), presets=("fast",),
        why="MuJoCo at mu = 10 (no slip) from theta_dot0 = 0.6, 40 steps: measured 0.006 deg at the fast preset "
            "(bracket half-width 0.0025); 0.02 deg rejects a wheel without hub inertia (kappa = 0: 1.92 deg)"),
    PaperResult(
        id="002-wheel-alpha-max", paper="002", location="Sec. 3.2, eq (21), Fig. 3.2",
        quantity="alpha_max: the slope above which f_n vanishes on the gait (deg, unbounded friction)",
        paper_value="14.7", independent="theory.slope_bounds (eq 21, f_n scanned over the whole step) against the "
                                        "solve_ivp stance forces",
        run=Bracket(low=14.0, high=40.0, below=runs.alpha_max_below, theory=runs.alpha_max_theory_unbounded,
                    tolerance=0.2, unit="deg"), presets=("fast",),
        miss="eq 21 is a bound for unbounded friction; at any finite mu the foot slips as f_n -> 0 (|f_t/f_n| -> inf) "
             "and the slip delays the detachment, as the paper itself finds for theta_dot_max (Fig. 3.8(a): 1.14 "
             "against eq 26's 0.9595). MuJoCo's wheel at mu = 10 keeps rolling to 17.17 deg (bracket [17.15, "
             "17.20], fast preset); the exact model cannot be run above eq 21's bound (its gait search refuses it), "
             "so the finite-mu bound has no exact value here",
        why="0.2 deg: the bisection's resolution 0.05 deg and the slope's effect on f_n; a wheel without hub inertia "
            "gives 13.75 deg"),
    PaperResult(
        id="002-wheel-window-lower", paper="002", location="Sec. 3.4, eq (26), Fig. 3.8(a)",
        quantity="theta_dot_min: the slowest post-impact start that does not roll back (mu = 1)", paper_value="0.0872",
        independent=WINDOW,
        run=Bracket(low=0.03, high=0.3, below=runs.window_lower_below, theory=runs.window_lower_theory,
                    tolerance=runs.LOWER_EDGE_TOLERANCE), presets=("fast",),
        why="measured 1.6e-4 at the fast preset (bracket half-width 2.5e-4); 0.002 rejects the slope's omission "
            "(eq 26 at alpha = 0: 0.31) and a start 1 % slower"),
    PaperResult(
        id="002-wheel-window-upper", paper="002", location="Sec. 3.4, Fig. 3.8(a), Fig. 3.8(c)",
        quantity="theta_dot_max: the fastest post-impact start that keeps contact over its first step (mu = 1)",
        paper_value="1.1374", independent=WINDOW,
        run=Bracket(low=1.0, high=1.3, below=runs.window_upper_below, theory=runs.window_upper_theory,
                    tolerance=runs.UPPER_EDGE_TOLERANCE), presets=("fast",), miss=UPPER_EDGE,
        why="measured 0.014 at the fast preset (MuJoCo's edge is higher: its lift-off is a clearance above "
            "FLIGHT_CLEARANCE, and f_n touches 0 tangentially at the edge); 0.03 rejects eq 26's unbounded-friction "
            "edge 0.9595"),
    PaperResult(
        id="002-wheel-window-upper-unbounded", paper="002", location="Sec. 3.4, eq (26), Fig. 3.7",
        quantity="theta_dot_max with unbounded friction (no slip)", paper_value="0.9595", independent=WINDOW,
        run=Refusal("the bound holds only where the foot cannot slip: with any finite friction it slips as f_n -> 0 "
                    "and the edge moves up (the paper's own Fig. 3.8(a) discussion; the exact model gives 1.133 at "
                    "mu = 2 and 1.12 at mu = 1e6). MuJoCo's friction is finite: its edge at mu = 2 is in "
                    "002-wheel-fig38a-upper, beside the exact finite-mu value")),
    PaperResult(
        id="002-wheel-ab-edge", paper="002", location="Sec. 3.3, Fig. 3.5",
        quantity="the A/B edge in mu: below it the gait slips (mu_c)", paper_value="0.91",
        independent="theory.gait_boundaries (the A gait's eq 23 and the B gait's Newton continuation)",
        run=Bracket(low=0.8, high=1.0, below=runs.gait_type_below, theory=runs.ab_edge_theory, tolerance=0.05),
        presets=("fast",),
        why="MuJoCo's settled type from the A gait's start, bisected: measured 0.025 low at the fast preset "
            "(MuJoCo's force-ratio peak at the step's end is 1.5 % below the exact one: its critical_friction "
            "0.900 against 0.914, and the B gait's slip near the edge starts within 0.002 rad of the impact); 0.05 "
            "rejects the impulse-only bound |sigma~| = 0.237 and a wheel without hub inertia (0.325)"),
    PaperResult(
        id="002-wheel-d-lower-edge", paper="002", location="Sec. 3.3, Fig. 3.5",
        quantity="the lower end of the Type D branch in mu (below it the wheel rolls back)", paper_value="0.1",
        independent="theory.gait_boundaries (the D gait's Newton continuation down to backward roll)",
        run=Experiment(runs.d_lower_edge), presets=("fast",), miss=SLIP_LIFT.replace(
            "from the Fig. 3.6 start", "near this edge the D+ gait's slip grows by 0.25-0.9 per step; from the Fig. "
            "3.6 start") + "; every run of the grid mu = 0.06-0.1 detaches before it could roll back",
        why="the grid's step, 0.01: a wheel without hub inertia has no D branch at all"),
    PaperResult(
        id="002-wheel-fig35a", paper="002", location="Fig. 3.5(a)",
        quantity="the stable gait's fixed point over mu (mid-stance theta_dot; the paper plots post-impact)",
        paper_value="", independent=GAITS, presets=("fast",),
        run=Curve(x=runs.FIG35_MU, point=runs.fig35_fixed_point, theory=runs.fig35_fixed_point_theory,
                  x_label="friction coefficient mu", y_label="mid-stance theta_dot of the gait (units of omega_c)",
                  dense=60),
        miss=D_PLUS, why="each point is the validation's midstance_rate check at that mu (its own tolerance and why)"),
    PaperResult(
        id="002-wheel-fig35b", paper="002", location="Fig. 3.5(b)",
        quantity="the stable gait's multiplier over mu (largest modulus)", paper_value="", independent=GAITS,
        presets=("fast",),
        run=Curve(x=runs.FIG35_MU, point=runs.fig35_multiplier, theory=runs.fig35_multiplier_theory,
                  x_label="friction coefficient mu", y_label="multiplier lambda (largest modulus)", dense=60),
        miss=D_PLUS, why="each point is the validation's eigenvalue check at that mu (its own tolerance and why)"),
    PaperResult(
        id="002-wheel-fig37-lower", paper="002", location="Fig. 3.7, eq (26)",
        quantity="the attraction window's lower edge theta_dot_min over the slope (unbounded friction: mu = 10)",
        paper_value="", independent=WINDOW, presets=("fast",),
        run=Curve(x=(2.0, 3.5, 5.0, 6.5, 8.0, 9.5, 11.0, 12.5, 14.0), point=runs.fig37_lower,
                  theory=runs.fig37_lower_theory, x_label="slope alpha (deg)",
                  y_label="theta_dot_min (units of omega_c)"),
        why="each point a bisection to 2.5e-4; 0.002 as 002-wheel-window-lower"),
    PaperResult(
        id="002-wheel-fig38a-lower", paper="002", location="Fig. 3.8(a)",
        quantity="the attraction window's lower edge theta_dot_min over mu", paper_value="0.0872 for mu > 0.29",
        independent=WINDOW, presets=("fast",),
        run=Curve(x=(0.27, 0.3, 0.4, 0.5, 0.7, 1.0, 1.5, 2.0), point=runs.fig38a_lower,
                  theory=runs.fig38a_lower_theory, x_label="friction coefficient mu",
                  y_label="theta_dot_min (units of omega_c)"),
        why="each point a bisection to 2.5e-4; 0.002 as 002-wheel-window-lower"),
    PaperResult(
        id="002-wheel-fig38a-upper", paper="002", location="Fig. 3.8(a)",
        quantity="the attraction window's upper edge theta_dot_max over mu", paper_value="about 1.14 for large mu",
        independent=WINDOW, presets=("fast",),
        run=Curve(x=(0.27, 0.3, 0.4, 0.5, 0.7, 1.0, 1.5, 2.0), point=runs.fig38a_upper,
                  theory=runs.fig38a_upper_theory, x_label="friction coefficient mu",
                  y_label="theta_dot_max (units of omega_c)"),
        miss=UPPER_EDGE,
        why="0.03 as 002-wheel-window-upper"),
)
