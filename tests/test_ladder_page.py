"""The friction biped's ladder page is the render of its committed validations, and it shows what tells a converging
miss from one converging to something else: the errors per rung and the stance foot's speed and height."""

from __future__ import annotations

from pathlib import Path

from mjpoincare.pages import ladder_page

ROOT = Path(__file__).resolve().parents[1]


def test_the_ladder_page_renders_from_its_validations() -> None:
    records = ladder_page.load(ROOT / ladder_page.LADDER)
    assert {str(d["results"][0]["params"]["gait"]) for d in records} == {"b", "c", "i", "ii", "iii"}
    assert (ROOT / ladder_page.PAGE).read_text() == ladder_page.render(records)


def test_each_gait_goes_from_the_coarsest_rung_to_the_finest() -> None:
    records = ladder_page.load(ROOT / ladder_page.LADDER)
    for gait in ("b", "c", "ii", "iii"):
        steps = [d["results"][0]["settings"]["timestep"] for d in records if d["results"][0]["params"]["gait"] == gait]
        assert steps == sorted(steps, reverse=True) and len(steps) == 3
