"""Every check has a rival (the nearest plausible wrong physics), and the discrimination page, which puts each rival's
distance against what its check lets through, renders from the gate's committed margins."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mjpoincare import scenarios
from mjpoincare.pages import discrimination_page
from mjpoincare.scenarios.base import Rival

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("name", sorted(scenarios.REGISTRY))
def test_every_check_of_every_scenario_has_a_rival(name: str) -> None:
    """A check counts only if the nearest wrong physics would fail it: each scenario names that physics for each of its
    checks (the run's numerical health, ``stable``, aside), and no rival for a check it does not have."""
    scenario = scenarios.REGISTRY[name]
    assert set(scenario.rivals) == set(scenario.checks) - {discrimination_page.HEALTH}
    for check, rival in scenario.rivals.items():
        assert rival.physics, f"{name}::{check}: a rival names its physics"


def test_a_rival_gives_its_distance_or_why_there_is_none() -> None:
    with pytest.raises(ValueError, match="give its distance"):
        Rival(physics="a wrong law")
    with pytest.raises(ValueError, match="give its distance"):
        Rival(physics="a wrong law", distance=lambda params: 1.0, indistinct="both")
    assert Rival(physics="a wrong law", indistinct="no check can see it").distance is None


def test_the_ratio_compares_the_distance_with_what_the_check_lets_through() -> None:
    row = discrimination_page.Row(case="c", check="k", tolerance=1e-3, error=2e-4, spread=1e-5, physics="p",
                                  distance=3e-3, indistinct="")
    assert row.ratio == pytest.approx(3e-3 / 1.21e-3)
    exact = discrimination_page.Row(case="c", check="k", tolerance=0.0, error=0.0, spread=0.0, physics="p",
                                    distance=1.0, indistinct="")
    assert exact.ratio == math.inf


def test_a_check_no_gate_case_tells_from_its_rival_says_why() -> None:
    """Where no gate case of the scenario rejects a check's rival, the rival states why (its ``weak`` line); a reason
    on a rival some gate case rejects is stale."""
    table = discrimination_page.rows(json.loads((ROOT / discrimination_page.MARGINS).read_text()))
    assert not discrimination_page.unexplained(table), [f"{r.case}::{r.check}" for r in
                                                        discrimination_page.unexplained(table)]
    told = discrimination_page.told_elsewhere(table)
    stale = sorted({key for key in told if scenarios.REGISTRY[key[0]].rivals[key[1]].weak})
    assert not stale, f"rivals told apart by a gate case keep a reason why not: {stale}"


def test_the_discrimination_page_renders_from_the_committed_margins() -> None:
    """Generated, never typed: the committed page is the render of the committed margins with today's rivals, and
    every rival's distance at every gate case is a finite number."""
    payload = json.loads((ROOT / discrimination_page.MARGINS).read_text())
    assert all(r.distance is None or math.isfinite(r.distance) for r in discrimination_page.rows(payload))
    assert (ROOT / discrimination_page.PAGE).read_text() == discrimination_page.render(payload)
