"""Regression: MuJoCo's 3D rimless wheel against Coleman, Chatterjee & Ruina (1997) (planar cycles, eqs 12-14;
3D eigenvalues, Sec. 8.1 Table 2), in both impact modes.

These run the real pipeline (rollouts, mid-stance sections, 5-D quadratic fit, checks) at the fast preset. The
tolerances are the scenario's own (:data:`mjpoincare.scenarios.rimless_wheel_3d.TOLERANCES`); nothing here loosens
them. Runtime: about 20 s on 2 cores.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import mujoco
import numpy as np
import pytest
from mjpoincare.analysis.rigid_body_kinematics import matrix_to_quat
from mjpoincare.analysis.theory import rimless_wheel_3d as theory
from mjpoincare.analysis.theory.rimless_wheel_3d import hybrid

from mjpoincare.cli import main
from mjpoincare.commands.validation import resolve_inputs
from mjpoincare.core.params import ParameterError
from mjpoincare.core.seam import RolloutReport
from mjpoincare.gate import forms as gate
from mjpoincare.scenarios import rimless_wheel_3d as rw3
from mjpoincare.scenarios.rimless_wheel_3d import reference_checks
from mjpoincare.scenarios.rimless_wheel_3d import runs as rw3_runs

pytestmark = pytest.mark.mujoco

REPO_MODELS = Path(__file__).resolve().parents[1] / "models"  # the MJCF files a user opens


@pytest.fixture(scope="module")
def contact() -> dict:
    return gate.run_case(gate.case("rimless-wheel-3d[fast]")).to_dict()


@pytest.fixture(scope="module")
def ideal() -> dict:
    return gate.run_case(gate.case("rimless-wheel-3d[fast,impact=ideal]")).to_dict()


NAMES = {"pitch_rate", "bank", "heading_eigenvalue", "wobble_modulus", "wobble_angle", "lambda5", "lambda2",
         "planar_pitch_rate", "planar_bank", "heading_drift", "stable"}


@pytest.mark.parametrize("mode", ["contact", "ideal"])
def test_fast_preset_checks(mode: str, request: pytest.FixtureRequest) -> None:
    """Table-2 case (n = 16, alpha = 0.125, psi = pi/10, J = 1/2): both impact modes have every check (their
    verdicts are the gate's: tests/test_gate.py) and the analytic wobble angle of Table 2."""
    result = request.getfixturevalue(mode)
    assert result["params"]["impact"] == mode
    assert {c["name"] for c in result["checks"]} == NAMES
    assert result["analytic"]["eigenvalues_named"]["wobble_angle"] == pytest.approx(0.39895, abs=1e-5)  # Table 2
    json.dumps(result, allow_nan=False)


def test_ideal_mode_isolates_the_integration(ideal: dict) -> None:
    """Exact guard and impact law: the impacts land on theta = pi/n and the planar cycle stays on eqs 12-14."""
    assert ideal["extras"]["max_guard_error"] < 1e-9
    by_name = {c["name"]: c for c in ideal["checks"]}
    assert by_name["planar_bank"]["error"] < 1e-9  # a vertical wheel plane stays vertical (no impact adds bank)
    assert "integration of the stance only" in by_name["planar_bank"]["why"]  # the check says what it tests
    assert abs(ideal["extras"]["heading_drift"]["per_100_impacts_fit"]) < 1e-3


def test_contact_mode_reports_heading_drift(contact: dict) -> None:
    """The heading is neutral: the soft impact biases it away from straight downhill. The 5-D fit's drift is
    reported (per 100 impacts); the planar runs' drift is judged (the ``heading_drift`` check, exact value 0), and
    vanishes at psi = 0 by symmetry."""
    drift = contact["extras"]["heading_drift"]
    reported = contact["reported"]["heading_drift_per_100_impacts"]  # also printed under the check table
    assert reported["value"] == pytest.approx(drift["per_100_impacts_fit"]) and reported["unit"] == "rad"
    assert drift["per_100_impacts_fit"] > 1e-3
    planar = contact["extras"]["heading_drift_per_100_impacts_planar"]
    assert set(planar) == {"0", "0.314159", "0.5"}
    assert planar["0"] == pytest.approx(0.0, abs=1e-9)  # symmetric
    assert 0 < planar["0.314159"] < planar["0.5"]
    judged = next(c for c in contact["checks"] if c["name"] == "heading_drift")
    assert judged["analytic"] == 0.0 and judged["error"] == pytest.approx(planar["0.5"] / 100.0)


def _planar_samples(params: dict, heading: float, drift: float) -> np.ndarray:
    """Mid-stance samples (rates in rad/s) of a wheel that rolls on the exact planar cycle of each heading it passes
    through, its heading moving by ``drift`` rad per impact from ``heading``."""
    unit = rw3_runs.rate_unit(params)
    rows = []
    for k in range(rw3_runs.PLANAR_IMPACTS):
        x = hybrid.midstance_fixed_point(rw3_runs.wheel(params, heading + drift * k))
        rows.append([x[0], x[1], x[2] * unit, x[3] * unit, x[4] * unit])
    return np.array(rows)


@pytest.mark.parametrize("drift", [0.0, 0.002])
def test_a_heading_that_drifts_fails_the_planar_checks(drift: float) -> None:
    """Samples on the exact planar cycles pass; a heading that drifts 0.002 rad per impact along the family of
    cycles (each sample on the exact cycle of its own heading) fails the heading drift (5 x its tolerance), the bank
    and the pitch rate, judged at the commanded headings."""
    params = {p.name: p.default for p in rw3.PARAMS}
    headings = rw3_runs.planar_headings(params)
    run = rw3_runs.Run(sequences=[_planar_samples(params, h, drift) for h in headings],
                       report=RolloutReport(diverged=np.zeros(len(headings), bool)))
    tol = rw3.TOLERANCES["contact"]["fast"]
    planar, _ = reference_checks.planar_checks(params, headings, run, tol)
    by_name = {c.name: c for c in planar}
    assert set(by_name) == {"planar_pitch_rate", "planar_bank", "heading_drift"}
    if drift == 0.0:
        assert all(c.error < 1e-9 for c in planar)
    else:
        assert by_name["heading_drift"].error == pytest.approx(drift)
        assert all(c.error > c.tolerance for c in planar), [(c.name, c.error, c.tolerance) for c in planar]


@pytest.mark.parametrize(("assignments", "name"), [
    ({"spokes": "2"}, "spokes"),
    ({"J": "0"}, "J"),
    ({"mu": "-1"}, "mu"),
    ({"impact": "foo"}, "impact"),
    ({"slope": "0.004"}, "slope"),  # below the existence threshold gamma_c = 0.005128 (001 eq 10)
    ({"mu": "0.1"}, "mu"),  # below the impact impulse ratio 0.1366 the banked cycle needs
    ({"heading": "1.6"}, "heading"),
])
def test_bad_input_names_the_parameter(assignments: dict[str, str], name: str) -> None:
    with pytest.raises(ParameterError, match=rf"^{name}\b"):
        resolve_inputs("rimless-wheel-3d", assignments, None)


def test_ideal_mode_ignores_friction() -> None:
    """The ideal mode's pivot holds whatever mu is (mu = 0 is accepted and built); only the contact mode needs
    friction (mu = 0 refused)."""
    _, _, params, settings = resolve_inputs("rimless-wheel-3d", {"impact": "ideal", "mu": "0"}, None)
    assert (params["impact"], params["mu"]) == ("ideal", 0.0)
    assert rw3.build(params, settings).nmocap == 1
    with pytest.raises(ParameterError, match=r"^mu\b"):
        resolve_inputs("rimless-wheel-3d", {"mu": "0"}, None)


def test_bad_input_exit_code(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "rimless-wheel-3d", "--set", "spokes=2"]) == 2
    assert "spokes" in capsys.readouterr().err


def test_model_file_and_rebuild() -> None:
    """models/rimless_wheel_3d.xml loads on its own; the MjSpec rebuild sets spokes, inertia, slope and mode."""
    model = mujoco.MjModel.from_xml_path(str(REPO_MODELS / "rimless_wheel_3d.xml"))
    assert (model.nq, model.nv) == (7, 6)
    _, _, params, settings = resolve_inputs("rimless-wheel-3d", {"spokes": "10", "slope": "0.2", "J": "1"}, None)
    rebuilt = rw3.build(params, settings)
    feet = [i for i in range(rebuilt.ngeom) if rebuilt.geom(i).name.startswith("foot")]
    assert len(feet) == 10
    np.testing.assert_allclose(rebuilt.body("wheel").inertia, [0.5, 1.0, 0.5])
    np.testing.assert_allclose(rebuilt.opt.gravity, [9.81 * np.sin(0.2), 0, -9.81 * np.cos(0.2)])
    ideal = rw3.build({**params, "impact": "ideal"}, settings)
    assert (ideal.nq, ideal.nv, ideal.nmocap) == (4, 3, 1)


def test_start_quaternions_are_mujocos() -> None:
    """The start and post-impact orientations written into qpos are the quaternions MuJoCo itself would give the
    stance-spoke frames (mju_mat2Quat), on every branch of the conversion."""
    w = theory.RimlessWheel3D(16, 0.125, 0.5, math.pi / 10)
    poses = [rw3.hybrid.pose(x[0], x[1], theta) for x in rw3_runs.fit_starts(w, 2e-3) for theta in (0.0, 0.2, 3.0)]
    for R in [*poses, np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0])]:
        expected = np.empty(4)
        mujoco.mju_mat2Quat(expected, np.ascontiguousarray(R).ravel())
        np.testing.assert_allclose(matrix_to_quat(R), expected, rtol=0, atol=1e-15)


def test_reference_bench_integrates_at_the_given_tolerance() -> None:
    """exact_model_bench passes rtol to the exact reference: a loose tolerance changes its errors, the default
    tolerance of later calls is untouched."""
    _, _, params, _ = resolve_inputs("rimless-wheel-3d", {"impact": "ideal"}, None)
    loose = rw3_runs.exact_model_bench(params, 1e-3)
    assert loose["rtol"] == 1e-3
    w = theory.RimlessWheel3D(16, 0.125, 0.5, math.pi / 10)
    x0 = rw3.hybrid.midstance_fixed_point(w) + 1e-3
    assert not np.array_equal(rw3.hybrid.midstance_map(w, x0, rtol=1e-3, atol=1e-3)[0],
                              rw3.hybrid.midstance_map(w, x0)[0])
    tight = rw3_runs.exact_model_bench(params, rw3.hybrid.RTOL)
    assert loose["pitch_rate_error"] != tight["pitch_rate_error"]
    assert tight["lambda2_error"] < 1e-4
