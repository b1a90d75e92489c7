"""The gate across the environments one machine can emulate (:mod:`mjpoincare.gate.environments`): the BLAS kernels
crossed with the numpy dispatch levels a CPU offers; the committed ensemble measurement (``make margins``:
docs/results/gate/) and the gate's declarations agree with it; the gate's kernel-sensitive cases re-run under a second
OpenBLAS kernel (Prescott, which every x86-64 CPU runs) in a process of their own move by no more than their allowance
(:func:`mjpoincare.core.allowance.allowance`); a planted kernel dependence below the allowance's floor passes that
comparison and one beyond the allowance fails it."""

from __future__ import annotations

import dataclasses
import json
import sys
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

import pytest
from conftest import kernel_run_key, kernel_sensitive_cases, second_kernel

from mjpoincare.core.allowance import allowance, floor
from mjpoincare.gate import environments as gate_environments
from mjpoincare.gate import forms as gate
from mjpoincare.gate.environments import (
    Environment,
    margins_command,
    read_environment,
    runnable_kernels,
    start_environment,
)
from mjpoincare.pages import gate_page
from mjpoincare.scenarios.gate_cases import Miss

ROOT = Path(__file__).parents[1]
MARGINS = ROOT / gate_page.MARGINS
PLANT = Path(__file__).parent / "plant_kernel_dependence.py"
#: The case the planted dependence is planted in: the cheapest, the slotted skate at its fast preset.
PLANTED_CASE = "slotted-skate[fast]"


@cache
def measured() -> dict[tuple[str, str], dict[str, Any]]:
    """The committed ensemble measurement's rows, by (case, check), each form judged against today's declarations."""
    return {(r["case"], r["check"]): r for r in gate.judged(json.loads(MARGINS.read_text())["rows"])}


def _errors_here(labels: list[str]) -> gate_environments.Errors:
    return {(c.label, check.name): check.error for c in gate.cases() if c.label in labels
            for check in gate.run_case(c).checks}


def _spreads() -> dict[tuple[str, str], float]:
    """Per check, the spread two environments' errors are compared by: the larger of its measured spread (around the
    run the measurement made on its CPU's own kernel) and its range over the measured environments (two environments
    of the ensemble differ by up to that range, and neither need be the one the measurement ran by default: this CPU's
    may be any)."""
    return {key: max(float(row["spread"]), gate_page.environment_range(row)) for key, row in measured().items()}


def _tolerances() -> dict[tuple[str, str], float]:
    """Per check, its tolerance in the committed measurement (the allowance's floor is a fraction of it)."""
    return {key: float(row["tolerance"]) for key, row in measured().items()}


def test_kernels_offered_by_cpu_features() -> None:
    """A kernel is offered only where the CPU has its instructions; off x86-64 (no SSE3) none is."""
    assert runnable_kernels({"SSE3": True, "SSE42": True, "AVX": True}) == ("Prescott", "Nehalem", "Sandybridge")
    assert runnable_kernels({"SSE3": True, "SSE42": True, "AVX": True, "AVX2": True, "FMA3": True})[-2:] == (
        "Haswell", "Zen")
    assert "SkylakeX" not in runnable_kernels({"SSE3": True, "AVX2": True, "FMA3": True, "AVX512F": True})
    assert runnable_kernels({}) == ()


def test_the_ensemble_crosses_every_kernel_with_every_numpy_level() -> None:
    """The default, each runnable kernel with numpy at each dispatch level the CPU offers, and one BLAS thread."""
    ensemble = gate_environments.ensemble()
    labels = [e.label for e in ensemble]
    levels = gate_environments.numpy_levels()
    assert labels[0] == "default" and labels[-1] == "OPENBLAS_NUM_THREADS=1" and len(labels) == len(set(labels))
    kernels = [e for e in ensemble if "OPENBLAS_CORETYPE" in e.variables]
    assert len(kernels) == len(runnable_kernels()) * len(levels)
    assert {(e.variables["OPENBLAS_CORETYPE"], e.variables.get("NPY_DISABLE_CPU_FEATURES", "")) for e in kernels} == {
        (k, " ".join(disabled)) for k in runnable_kernels() for _, disabled in levels}


def test_numpy_levels_take_the_dispatch_down_to_avx2_and_to_the_baseline() -> None:
    """numpy 2's dispatch targets and numpy 1.26's: AVX2 disables exactly the AVX-512 ones, the baseline all; a CPU
    without AVX-512 has no AVX2 level apart from its own, one with no dispatch none."""
    assert gate_environments.numpy_levels(("X86_V3", "X86_V4", "AVX512_ICL")) == (
        ("", ()), ("numpy AVX2", ("X86_V4", "AVX512_ICL")), ("numpy baseline", ("X86_V3", "X86_V4", "AVX512_ICL")))
    assert gate_environments.numpy_levels(("AVX2", "FMA3", "AVX512F", "AVX512_SKX"))[1] == (
        "numpy AVX2", ("AVX512F", "AVX512_SKX"))
    assert [label for label, _ in gate_environments.numpy_levels(("X86_V3",))] == ["", "numpy baseline"]
    assert gate_environments.numpy_levels(()) == (("", ()),)


def test_environment_disagreements_hold_each_check_to_its_allowance() -> None:
    """A move within 3 x the spread passes, beyond it fails with the factor; a move below the floor (1e-6 of the
    tolerance) passes however small the spread; a check one side lacks fails; the allowance never drops below
    roundoff where a check has no tolerance."""
    here = {("c", "a"): 1.0, ("c", "b"): 0.5, ("c", "f"): 0.2, ("c", "n"): 0.0}
    there = {("c", "a"): 1.0 + 5e-6, ("c", "b"): 0.5 + 1e-3, ("c", "f"): 0.2 + 9e-9, ("c", "n"): 1e-13}
    spreads = {("c", "a"): 2e-6, ("c", "b"): 1e-4, ("c", "f"): 1e-15, ("c", "n"): 0.0}
    tolerances = {("c", "a"): 0.1, ("c", "b"): 0.1, ("c", "f"): 0.01, ("c", "n"): 0.0}
    lines = gate.environment_disagreements(there, here, spreads, tolerances, "K")
    assert len(lines) == 1 and lines[0].startswith("c::b: 0.5 here, 0.501 under K: moved 0.001, 3.33 x its allowance")
    assert "3 x its spread 0.0001 and 1e-06 x its tolerance" in lines[0]
    there[("c", "f")] = 0.2 + 1.1e-8
    named = gate.environment_disagreements(there, here, spreads, tolerances, "K")
    assert [x.split(":")[2] for x in named] == ["b", "f"]
    assert gate.environment_disagreements({}, {("c", "a"): 1.0}, spreads, tolerances, "K") == [
        "c::a: 1 here, nan under K"]


def test_outside_ensemble_names_the_distance_and_the_closest_environment() -> None:
    row = {"low": [0.010, "OPENBLAS_CORETYPE=Prescott"], "high": [0.012, "starts x(1+1e-9)"]}
    assert gate.outside_ensemble(row, 0.015).startswith(
        "error 0.015 lies 0.003 above the ensemble's range 0.01 to 0.012 (closest: starts x(1+1e-9))")
    assert "0.002 below" in gate.outside_ensemble(row, 0.008) and "Prescott" in gate.outside_ensemble(row, 0.008)
    assert "(make margins)" in gate.outside_ensemble(None, 0.01)


def test_the_committed_measurement_covers_every_gate_check_and_every_declaration() -> None:
    """Every check of every gate case has a row in the committed measurement and held its form there; a watched
    check's or a declared miss's spread is at least the ensemble's, and every environment's error lies in a miss's
    band. A case's checks are the ones it declares (gated, watched, missed): that they are its run's checks, neither
    more nor fewer, is test_gate's, on the run its other tests share, so no case runs again here."""
    rows = measured()
    for c in gate.cases():
        for name in (*c.gated, *(w.check for w in c.watched), *(m.check for m in c.misses)):
            row = rows.get((c.label, name))
            assert row is not None, f"{c.label}::{name} is not in {gate_page.MARGINS}: make margins"
            assert row["holds"], f"{c.label}::{name} did not hold its form in {gate_page.MARGINS}"
        for declared in (*c.watched, *c.misses):
            row = rows[(c.label, declared.check)]
            allowed = allowance(declared.spread, row["tolerance"])
            assert row["spread"] <= allowed or (isinstance(declared, Miss) and not declared.resolved), (
                f"{c.label}::{declared.check}: the ensemble's spread {row['spread']:.2g} beyond the allowance "
                f"{allowed:.2g} of the declared {declared.spread:.2g}")
        for miss in c.misses:
            row = rows[(c.label, miss.check)]
            for error in (row["error"], *row["environments"].values()):
                assert miss.matches(error), f"{c.label}::{miss.check}: {error:.6g} outside {miss.band}"


def test_the_gate_page_renders_from_the_committed_measurement() -> None:
    payload = json.loads(MARGINS.read_text())
    assert (ROOT / gate_page.PAGE).read_text() == gate_page.render(payload)
    assert payload["stamp"]["git_sha"] and not payload["stamp"]["git_dirty"]


@pytest.mark.mujoco
@pytest.mark.skipif("Prescott" not in runnable_kernels(), reason="OpenBLAS's Prescott kernel is x86-64 only")
def test_the_gate_holds_under_a_second_blas_kernel(request: pytest.FixtureRequest) -> None:
    """The kernel-sensitive cases, run under the second kernel (``conftest.second_kernel``) in a process of their own
    (started at collection, beside the rest of the suite; under pytest-xdist, here, beside this process's runs of
    them), move from this process's runs by at most their measured allowance (:func:`_allowances`)."""
    labels = kernel_sensitive_cases()
    assert labels, "the committed measurement names no kernel-sensitive case: nothing would be re-run"
    second = second_kernel()
    process = request.config.stash.get(kernel_run_key, None) or start_environment(second, labels)
    here = _errors_here(labels)  # while the second kernel runs, when this test started it
    lines = gate.environment_disagreements(read_environment(process, second, labels), here, _spreads(),
                                           _tolerances(), second.label)
    assert not lines, "\n".join(lines)


@pytest.mark.mujoco
@pytest.mark.skipif("Prescott" not in runnable_kernels(), reason="OpenBLAS's Prescott kernel is x86-64 only")
def test_a_planted_kernel_dependence_fails_beyond_its_allowance_and_passes_below_its_floor() -> None:
    """The skate's heading error moved whenever a kernel is forced: by 1.1 x its allowance it is named with its move,
    and nothing else of the case is; by half its floor (a millionth of its tolerance, far above its measured spread:
    a change the check cannot express) it passes."""
    forced = Environment("OPENBLAS_CORETYPE=Prescott", {"OPENBLAS_CORETYPE": "Prescott"})
    key = (PLANTED_CASE, "heading")
    beyond = 1.1 * allowance(_spreads()[key], _tolerances()[key])
    below = 0.5 * floor(_tolerances()[key])
    assert _spreads()[key] < below, "the heading's spread no longer lies below the floor: plant elsewhere"

    def planted(check: str, shift: float) -> Callable[[list[str]], list[str]]:
        return lambda labels: [sys.executable, str(PLANT), check, repr(shift), *margins_command(labels)[3:]]

    runs = [start_environment(forced, [PLANTED_CASE], command=planted("heading", shift)) for shift in (beyond, below)]
    here = _errors_here([PLANTED_CASE])
    failed, passed = (gate.environment_disagreements(read_environment(run, forced, [PLANTED_CASE]), here, _spreads(),
                                                     _tolerances(), forced.label) for run in runs)
    assert len(failed) == 1 and failed[0].startswith(f"{PLANTED_CASE}::heading:"), failed
    assert "1.1 x its allowance" in failed[0], failed
    assert passed == []


def test_xdist_groups_follow_the_gate_case_in_the_node_id() -> None:
    """Under ``--dist loadgroup`` (conftest's scheduler) a gate case's tests share a group, the kernel-sensitive
    cases' one with the second-kernel test; a label that prefixes another never takes the other's tests."""
    from conftest import KERNEL_GROUP, KERNEL_TEST, gate_group

    labels = sorted(["w[fast]", "w[fast,mu=0.24]", "w-3d[fast]"], key=len, reverse=True)
    sensitive = {"w-3d[fast]"}
    assert gate_group("tests/test_gate.py::test_gated_check[w[fast]::eigenvalue]", labels, sensitive) == "gate-w[fast]"
    assert gate_group("tests/test_baseline.py::test_x[w[fast,mu=0.24]]", labels, sensitive) == "gate-w[fast,mu=0.24]"
    assert gate_group("tests/test_gate.py::test_gated_check[w-3d[fast]::stable]", labels, sensitive) == KERNEL_GROUP
    assert gate_group(KERNEL_TEST, labels, sensitive) == KERNEL_GROUP
    assert gate_group("tests/test_tables.py::test_rows", labels, sensitive) is None


def test_a_declaration_is_judged_against_the_committed_measurement_without_simulating() -> None:
    """The form is a judgement of the measurement: the committed rows judged against today's declarations hold, and
    the same row judged against a watched check's spread declared a thirtieth of the measured one (its allowance
    a tenth) does not."""
    rows = measured()
    # the watched check whose spread stands highest above its allowance's floor (a spread at the floor holds at any
    # declared spread)
    watched, watch = max(((c, w) for c in gate.cases() for w in c.watched),
                         key=lambda cw: rows[(cw[0].label, cw[1].check)]["spread"]
                         / rows[(cw[0].label, cw[1].check)]["tolerance"])
    row = rows[(watched.label, watch.check)]
    assert gate.judge(watched, row)["holds"]
    smaller = dataclasses.replace(watch, spread=row["spread"] / 30)
    shrunk = dataclasses.replace(watched, watched=(smaller, *watched.watched[1:]))
    assert row["spread"] > 0 and not gate.judge(shrunk, row)["holds"]
