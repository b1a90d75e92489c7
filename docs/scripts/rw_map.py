"""Rimless wheel spokes x slope map: omega_post_impact (the rolling fixed point omega*) error at the accurate preset
and at the preset's timestep halved (solref_timeconst held at 10 steps), one `mjpoincare validate rimless-wheel
--preset accurate --json` per cell and step (a file that exists is not rerun; a refused cell, exit 2, is listed).
The last column: max_clearance_rolling of validate --json, the highest the wheel's lowest foot rose above
the slope while rolling (a flight after the impact). Extra --set assignments (e.g. solref_dampratio=2) apply
to every run and name the output files.

usage: .venv/bin/python docs/scripts/rw_map.py OUT_DIR "N:SLOPE,SLOPE,...;N:..." DT,DT [NAME=VALUE ...]"""
import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

EXE = str(Path(sys.executable).with_name("mjpoincare"))  # the mjpoincare of the running venv
out = Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
cells = [(int(n), s) for part in sys.argv[2].split(";") for n, ss in [part.split(":")] for s in ss.split(",")]
steps = [float(x) for x in sys.argv[3].split(",")]
extra = sys.argv[4:]
tag = "_".join(extra).replace("=", "")


def path(n, s, dt):
    return out / f"rw_n{n}_s{s}_dt{dt:.6g}{'_' + tag if tag else ''}.json"


def run(job):
    n, s, dt = job
    p = path(n, s, dt)
    if not p.exists() and not p.with_suffix(".refused").exists():
        cmd = [EXE, "validate", "rimless-wheel", "--preset", "accurate", "--set", f"spokes={n}", "--set",
               f"slope={s}", "--set", f"timestep={dt:.6g}", "--set", f"solref_timeconst={10 * dt:.6g}"]
        for e in extra:
            cmd += ["--set", e]
        r = subprocess.run([*cmd, "--json", str(p)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if r.returncode == 2:
            p.with_suffix(".refused").write_text(r.stderr)
    return job


jobs = [(n, s, dt) for dt in sorted(steps, reverse=True) for n, s in cells]
with ThreadPoolExecutor(2) as pool:
    list(pool.map(run, jobs))

print(f"settings: preset accurate, solref_timeconst = 10 timesteps{', ' + ' '.join(extra) if extra else ''}")
print("| spokes | slope | omega* analytic | " + " | ".join(f"rel. error dt={dt:.3g}" for dt in steps)
      + " | error ratio (coarse/fine) | eigenvalue abs. error (finest) | checks failing (finest) "
      "| max_clearance_rolling (finest) |")
print("|---" * (len(steps) + 7) + "|")
for n, s in cells:
    if path(n, s, steps[0]).with_suffix(".refused").exists():
        msg = path(n, s, steps[0]).with_suffix(".refused").read_text().strip().splitlines()[-1]
        print(f"| {n} | {s} | refused: {msg} |")
        continue
    runs = [json.loads(path(n, s, dt).read_text()) for dt in steps]
    chk = [{c["name"]: c for c in d["checks"]} for d in runs]
    errs = [(c["omega_post_impact"]["simulated"] - c["omega_post_impact"]["analytic"])
            / c["omega_post_impact"]["analytic"] for c in chk]
    ratio = abs(errs[0]) / abs(errs[-1]) if errs[-1] else float("inf")
    print(f"| {n} | {s} | {chk[0]['omega_post_impact']['analytic']:.6g} | " + " | ".join(f"{e:+.2e}" for e in errs)
          + f" | {ratio:.2f} | {chk[-1]['eigenvalue']['error']:.1e} | "
          f"{', '.join(c['name'] for c in runs[-1]['checks'] if not c['passed']) or 'none'} "
          f"| {runs[-1].get('max_clearance_rolling', float('nan')) * 1e3:.2f} mm |")
