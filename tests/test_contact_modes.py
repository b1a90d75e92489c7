"""The shared stick/slip classifier (:mod:`mjpoincare.analysis.contact_modes`): row labels from speed and from the
friction cone, and the merging of flicker into neighbouring phases, the same for every system."""

from __future__ import annotations

import numpy as np
from mjpoincare.analysis.contact_modes import (
    SLIP_NEG,
    SLIP_POS,
    STICK,
    cone_modes,
    merge_short_runs,
    run_starts,
    speed_modes,
)


def test_speed_modes_label_by_sign_beyond_the_threshold() -> None:
    speed = np.array([0.0, 0.004, 0.006, -0.006, -0.005, 0.005])
    assert speed_modes(speed, 5e-3).tolist() == [STICK, STICK, SLIP_POS, SLIP_NEG, STICK, STICK]


def test_cone_modes_need_the_ratio_on_the_cone_edge_with_the_opposing_sign() -> None:
    """Friction pushing back (f_t < 0) on the edge is a forward slide; inside the cone (1 - eps) is stick; NaN (no
    contact) is stick here, the callers exclude it."""
    ratio = np.array([-0.2, -0.199, -0.1985, 0.2, 0.0, np.nan])
    assert cone_modes(ratio, 0.2, eps=5e-3).tolist() == [SLIP_POS, SLIP_POS, STICK, SLIP_NEG, STICK, STICK]


def test_short_runs_merge_into_the_run_before_within_their_group() -> None:
    s, p = STICK, SLIP_POS
    mode = np.array([s, s, s, s, p, s, s, s, p, p, p, p])
    group = np.zeros(mode.size, int)
    merged = merge_short_runs(group, mode, shortest=2)
    assert merged.tolist() == [s] * 8 + [p] * 4
    assert run_starts(group, merged).tolist() == [0, 8]


def test_a_short_run_opening_a_group_joins_the_next_and_groups_never_mix() -> None:
    s, p = STICK, SLIP_POS
    mode = np.array([p, s, s, s, s, p, p, p])
    group = np.array([0, 0, 0, 0, 1, 1, 1, 1])
    merged = merge_short_runs(group, mode, shortest=2)
    # group 0 opens with a one-row slip: it joins the stick after it; group 1's one-row stick opens it: joins the slip
    assert merged.tolist() == [s, s, s, s, p, p, p, p]
    assert run_starts(group, merged).tolist() == [0, 4]


def test_runs_at_least_the_window_long_are_kept() -> None:
    s, p = STICK, SLIP_POS
    mode = np.array([s, s, p, p, s, s])
    group = np.zeros(mode.size, int)
    np.testing.assert_array_equal(merge_short_runs(group, mode, shortest=2), mode)
