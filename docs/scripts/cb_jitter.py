"""Impact-onset jitter of the passive compass biped as a noise floor. Per timestep (solref_timeconst = 10 steps,
the presets' ratio), one `mjpoincare validate compass-biped --json` per start_perturbation in STARTS (every start
state's velocities x (1 + s): moves each heel strike's sub-step phase, not the gait); a rung whose file exists is
not rerun. Prints per timestep the eigenvalues check's error (max abs) per start, their mean and spread (sample
std), the fit's one-step residual (rms over the 3 section coordinates) and the bootstrap std of the eigenvalues
(max over the 3), then the log-log slopes of each against the timestep.

usage: .venv/bin/python docs/scripts/cb_jitter.py OUT_DIR DT [DT ...]"""
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

EXE = str(Path(sys.executable).with_name("mjpoincare"))  # the mjpoincare of the running venv
STARTS = (0.0, 1e-12, 1e-9, 1e-6)
out = Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
steps = sorted((float(x) for x in sys.argv[2:]), reverse=True)


def path(dt, sp):
    return out / f"cb_dt{dt:.6g}_sp{sp:.0e}.json"


def run(job):
    dt, sp = job
    if not path(dt, sp).exists():
        subprocess.run([EXE, "validate", "compass-biped", "--set", f"timestep={dt:.6g}", "--set",
                        f"solref_timeconst={10 * dt:.6g}", "--set", f"start_perturbation={sp:g}", "--json",
                        str(path(dt, sp))], stdout=subprocess.DEVNULL, check=False)
    return job


with ThreadPoolExecutor(2) as pool:
    list(pool.map(run, [(dt, sp) for dt in steps for sp in STARTS]))

print("| timestep | eigenvalue error per start_perturbation " + ", ".join(f"{s:g}" for s in STARTS)
      + " | mean | spread (std) | one-step residual rms | bootstrap std | fixed_point error |")
print("|---|---|---|---|---|---|---|")
table = []
for dt in steps:
    runs = [json.loads(path(dt, sp).read_text()) for sp in STARTS]
    runs = [d["results"][0] if "results" in d else d for d in runs]  # the CLI's JSON holds one result per scenario
    chk = [{c["name"]: c for c in d["checks"]} for d in runs]
    err = np.array([c["eigenvalues"]["error"] for c in chk])
    resid = float(np.mean([np.sqrt(np.mean(np.square(d["fit"]["residual_rms"]))) for d in runs]))
    boot = float(np.mean([np.max(np.abs(np.array(d["fit"]["eigenvalue_std"], float))) for d in runs]))
    fp = float(np.mean([c["fixed_point"]["error"] for c in chk]))
    table.append((dt, err.mean(), err.std(ddof=1), resid, boot, fp))
    print(f"| {dt:.3g} | " + ", ".join(f"{e:.2e}" for e in err)
          + f" | {err.mean():.2e} | {err.std(ddof=1):.2e} | {resid:.2e} | {boot:.2e} | {fp:.2e} |")
t = np.array(table)
if len(t) >= 2:
    for j, name in [(1, "eigenvalue error (mean)"), (2, "eigenvalue spread"), (3, "one-step residual"),
                    (4, "bootstrap std"), (5, "fixed_point error")]:
        slope = np.polyfit(np.log(t[:, 0]), np.log(t[:, j]), 1)[0]
        print(f"log-log slope against timestep, {name}: {slope:.2f}")
