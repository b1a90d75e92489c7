"""Timestep and contact time constant ladders of compass-biped-friction Gait B, as `converge` builds them (timestep
ladder: step and time constant together, 10 steps; time constant ladder: at the finest step), each rung one
`mjpoincare validate --json` (kept in OUT; a rung whose file exists is not rerun). Tabulates, per ladder, the
eigenvalues, the fixed point, the impact slip and the stance foot's net slide per step
(phases.slip_distance_measured, mean over the settled steps)
with mjpoincare.analysis.convergence.analyze, the analysis `converge` uses.

usage: .venv/bin/python docs/scripts/cbf_ladder.py OUT_DIR"""
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from mjpoincare.analysis.convergence import analyze

EXE = str(Path(sys.executable).with_name("mjpoincare"))  # the mjpoincare of the running venv
out = Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
steps = [1e-4 / 2**i for i in range(4)]
ladders = {"timestep": [(h, 10 * h) for h in steps],
           "solref_timeconst": [(steps[-1], 1e-3 / 2**i) for i in range(4)]}


def path(dt, tc):
    return out / f"gaitb_dt{dt:.6g}_tc{tc:.6g}.json"


def run(rung):
    dt, tc = rung
    if not path(dt, tc).exists():
        subprocess.run([EXE, "validate", "compass-biped-friction", "--set", "gait=b", "--set", f"timestep={dt:.6g}",
                        "--set", f"solref_timeconst={tc:.6g}", "--json", str(path(dt, tc))],
                       stdout=subprocess.DEVNULL, check=False)
    return rung


with ThreadPoolExecutor(2) as pool:
    list(pool.map(run, sorted({r for rs in ladders.values() for r in rs}, key=lambda r: r[0])))


def quantities(d):
    chk = {c["name"]: c for c in d["checks"]}
    ev_s, ev_a = chk["eigenvalues"]["simulated"], chk["eigenvalues"]["analytic"]
    cplx = lambda v: complex(*v) if isinstance(v, list) else complex(v)  # noqa: E731
    q = {}
    for i, (s, a) in enumerate(zip(ev_s, ev_a, strict=True)):
        s, a = cplx(s), cplx(a)
        q[f"eigenvalues[{i}].re"] = (a.real, s.real)
        if a.imag:
            q[f"eigenvalues[{i}].im"] = (a.imag, s.imag)
    for i, (a, s) in enumerate(zip(chk["fixed_point"]["analytic"], chk["fixed_point"]["simulated"], strict=True)):
        q[f"fixed_point[{i}]"] = (a, s)
    ph = d["phases"]
    q["slip_distance (m)"] = (ph["slip_distance_analytic"], float(np.mean(ph["slip_distance_measured"])))
    q["impact_slip (m)"] = (chk["impact_slip"]["analytic"], chk["impact_slip"]["simulated"])
    return q


for axis, rungs in ladders.items():
    rows = [quantities(json.loads(path(*r).read_text())) for r in rungs]
    h = [r[0] if axis == "timestep" else r[1] for r in rungs]
    print(f"\naxis {axis}: " + ", ".join(f"{x:.4g}" for x in h)
          + (" (solref_timeconst = 10 steps)" if axis == "timestep" else f" (timestep {rungs[0][0]:.4g})"))
    print("| quantity | analytic | " + " | ".join(f"h={x:.3g}" for x in h)
          + " | p (3-grid) | p (fit ± σ) | Richardson | GCI band | bias | verdict |")
    print("|---" * (len(h) + 8) + "|")
    for name in rows[0]:
        a = rows[0][name][0]
        vals = [r[name][1] for r in rows]
        c = analyze(h, vals, a)
        tg, fit = c.three_grid, c.fit
        star = " *" if np.isfinite(tg.safety_factor) and tg.safety_factor != 1.25 else ""
        p3 = "—" if not np.isfinite(tg.observed_order) else f"{tg.observed_order:.3g}"
        pf = "—" if not np.isfinite(fit.order) else f"{fit.order:.3g} ± {fit.order_stderr:.2g}"
        band = "—" if not np.isfinite(tg.gci) else f"{c.band:.2g}"
        verdict = c.verdict.value
        if verdict.startswith("does not"):
            verdict += f" (noise floor {c.noise_floor:.2g})"
        print(f"| {name} | {a:.6g} | " + " | ".join(f"{v:.6g}" for v in vals)
              + f" | {p3}{star} | {pf} | {tg.extrapolated:.7g} | {band} | {c.bias:.2g} | {verdict} |")
    print("one-step map residual rms (fit.residual_rms, mean of the 3 coordinates): "
          + ", ".join(f"{np.mean(json.loads(path(*r).read_text())['fit']['residual_rms']):.2e}" for r in rungs))
