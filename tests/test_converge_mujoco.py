"""Three-grid convergence in the timestep (ratio 2, Celik et al. 2008): the observed order in a measured band and the
Richardson value within its GCI band of the analytic value, for the rimless wheel and the slotted skate.

The orders were measured with ``mjpoincare converge ... --axis timestep --points 3`` at seeds 0, 1, 2 and 1 or 2
threads: identical to six digits (wheel omega 1.472, step period 1.398; skate 0.9997, 0.9980, 0.9997). The
three-grid order is ``ln(eps32/eps21)/ln 2``, so a shift ``d`` of the finest value moves it by ``d/(eps21 ln 2)``.
Wheel: the measured order +- 0.5 absorbs a shift of 0.35 eps21 of the finest value (1.6e-4 on omega, 1.5e-4
relative: the machine-to-machine level of contact results at these steps). Skate (no contact detection: a
deterministic equality constraint, bit-identical over seeds and threads): the formal order 1 +- 0.1 absorbs 0.07
eps21 (6e-8 on the final speed).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from conftest import require_module
from mjpoincare.analysis import checks
from mjpoincare.analysis.checks import Check

from mjpoincare.cli import main
from mjpoincare.commands import validation
from mjpoincare.commands.converge import components, converge, write_plots

pytestmark = pytest.mark.mujoco
ANALYTIC = "converges to analytic"
#: The skate's first-order scheme: semi-implicit Euler at 5e-4 s with a dead-beat peg (its fast preset before the
#: search).
SKATE_EULER = {"integrator": "euler", "timestep": "5e-4", "solref_timeconst": "1e-3", "solref_dampratio": "1",
               "tolerance": "1e-14"}


def _timestep_axis(payload: dict[str, Any]) -> dict[str, Any]:
    axis = payload["analysis"]["timestep"]
    assert not axis["bad_rungs"], axis["bad_rungs"]  # no rung failed, diverged or warned
    return axis["components"]


def test_rimless_wheel_fixed_point_converges_to_the_analytic_value() -> None:
    # steps 2e-4, 1e-4, 5e-5 with the contact time constant at 10 steps (the fast preset's ratio); the fast preset's
    # own 4e-4 is outside the asymptotic range (order 0.4 over 4e-4..1e-4)
    # (damping ratio 1 and 0.5 mm feet: the fast preset before the search, at which the orders were measured)
    payload = converge("rimless-wheel", {"timestep": "2e-4", "solref_timeconst": "2e-3", "solref_dampratio": "1",
                                         "foot_radius": "5e-4"}, axes=("timestep",), points=3, workers=2)
    comps = _timestep_axis(payload)
    for name, measured in (("omega_post_impact", 1.47), ("step_period", 1.40)):
        entry = comps[name]
        assert entry["three_grid"]["observed_order"] == pytest.approx(measured, abs=0.5), name
        assert entry["verdict"] == ANALYTIC, (name, entry["bias"], entry["band"])


def test_slotted_skate_is_first_order_to_the_analytic_value(tmp_path: Path) -> None:
    # semi-implicit Euler at 5e-4 s with a dead-beat peg (the fast preset before the search) refined twice: a clean
    # first order
    path = str(tmp_path / "skate.json")
    payload = converge("slotted-skate", SKATE_EULER, "fast", axes=("timestep",), points=3, workers=2, json_path=path)
    comps = _timestep_axis(payload)
    for name in ("sigma4_forward", "sigma4_backward", "final_speed"):
        entry = comps[name]
        assert entry["three_grid"]["observed_order"] == pytest.approx(1.0, abs=0.1), name
        assert entry["three_grid"]["safety_factor"] == 1.25
        assert entry["verdict"] == ANALYTIC, (name, entry["bias"], entry["band"])
    resumed = converge("slotted-skate", SKATE_EULER, "fast", axes=("timestep",), points=3, json_path=path,
                       resume=True)
    assert resumed["rungs_run"] == 0 and resumed["analysis"] == payload["analysis"]
    require_module("matplotlib", "matplotlib")
    plots = write_plots(payload, str(tmp_path / "report"))
    assert {p.name for p in plots} >= {"converge-slotted-skate-sigma4_forward.png"}


@pytest.mark.parametrize("args", [["--axis", "mass"], ["--points", "2"], ["--ratio", "1"], ["--resume"],
                                  ["--set", "timestep=1e-4", "--set", "solref_timeconst=1e-4"]])
def test_bad_input_exits_2_before_any_simulation(args: list[str], capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["converge", "rimless-wheel", *args]) == 2
    assert capsys.readouterr().err.count("\n") == 1  # one line naming the parameter and its bound


def test_components_split_vectors_and_complex_values_and_skip_categories() -> None:
    eig = checks.absolute("eigenvalue", 0.5, complex(0.49, 0.0), 0.1, "", "")
    pair = Check(name="eigenvalues", analytic=np.array([0.1 + 0.5j, 0.1 - 0.5j]), simulated=np.array([0.2 + 0.4j]),
                 error=0.1, tolerance=1.0, kind="max-abs", unit="", why="")
    gait = checks.categorical("gait_type", "B", "B", 0, 1, "")
    values, skipped = components([eig, pair, gait, validation.stability_check(0, 0)])
    assert values["eigenvalue"] == [0.5, 0.49]  # a real analytic value: the real part is compared
    assert values["eigenvalues[1].im"][0] == -0.5
    assert math.isnan(values["eigenvalues[0].re"][1])  # a missing simulated component is NaN, never dropped
    assert skipped == ["gait_type", "stable"]


def test_a_check_whose_analytic_value_moves_with_the_run_is_analysed_by_its_error() -> None:
    """An analytic value evaluated on each run's own state (e.g. at its measured heading) differs between rungs:
    the error simulated - analytic is what converges, to 0, not the simulated value to the first rung's analytic."""
    from mjpoincare.commands.converge import _analyse_axis, rung_key

    rungs = [{"timestep": str(h)} for h in (4e-4, 2e-4, 1e-4)]
    rows = {rung_key(o): {"failed": None, "diverged": 0, "warnings": 0,
                          "components": {"x": [1.0 + 10 * h, 1.0 + 10 * h + 3 * h]}}
            for o, h in zip(rungs, (4e-4, 2e-4, 1e-4), strict=True)}
    entry = _analyse_axis("timestep", rungs, rows)["components"]["x"]
    assert entry["analysed"] == "error" and entry["analytic"] == 0.0
    assert entry["three_grid"]["observed_order"] == pytest.approx(1.0)
    assert entry["verdict"] == "converges to analytic"
