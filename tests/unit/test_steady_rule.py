"""The time domain's steady-state rule (cablestudy.dynamics.steady): per-period extremes
judged against the period's dynamic range, with the Newton tolerance as a floor."""

from __future__ import annotations

import numpy as np

from cablestudy.dynamics.steady import extremes_settled


def _decaying(periods: int, mean: float, half_range: float, leftover: float, ratio: float):
    """Per-period extremes of a harmonic response of ``half_range`` about ``mean`` with
    a free vibration of initial amplitude ``leftover`` that decays by ``ratio`` per
    period and whose phase turns by 2 rad per period (so it moves both extremes)."""
    k = np.arange(periods)
    free = leftover * ratio**k * np.cos(2.0 * k)
    return mean + half_range + free, mean - half_range + free


def test_a_small_range_on_a_large_tension_is_judged_against_the_range() -> None:
    """2 N of range on 1512 N with extremes still moving by ~1 % of the range: steady by
    0.002 of the tension (3 N), not by 0.002 of the range (the rule)."""
    hi, lo = _decaying(8, 1511.0, 1.0, 0.5, 0.7)
    moving = np.abs(np.diff(hi[-3:]))
    assert moving.max() < 0.002 * 1512.0 and moving.max() > 0.002 * 2.0
    assert not extremes_settled(hi, lo, tolerance=0.002, window=2, floor=1.5e-4)


def test_the_run_settles_once_the_leftover_is_below_the_tolerance_of_the_range() -> None:
    """The same response run on: steady at the first period where both changes over the
    window are within 0.002 of the range (2 N), found by the rule and by hand alike."""
    hi, lo = _decaying(60, 1511.0, 1.0, 0.5, 0.7)
    by_rule = next(
        n
        for n in range(3, 61)
        if extremes_settled(hi[:n], lo[:n], tolerance=0.002, window=2, floor=0.0)
    )
    change = np.maximum(np.abs(np.diff(hi)), np.abs(np.diff(lo)))  # change[i]: i -> i + 1
    ok = change <= 0.002 * (hi[1:] - lo[1:])
    by_hand = next(n for n in range(3, 61) if ok[n - 3] and ok[n - 2])
    assert by_rule == by_hand


def test_a_line_that_does_not_move_settles_on_the_newton_floor() -> None:
    """No dynamic range, extremes that differ by solver round-off only (below the
    Newton tolerance): steady; a change above the floor is not."""
    rng = np.random.default_rng(1)
    hi = 1000.0 + 1e-6 * rng.standard_normal(5)
    lo = hi - 1e-9
    assert extremes_settled(hi, lo, tolerance=0.002, window=2, floor=1e-4)
    assert not extremes_settled(hi + [0, 0, 0, 0, 1e-3], lo, tolerance=0.002, window=2, floor=1e-4)


def test_every_watched_end_must_settle_and_nan_never_does() -> None:
    """Extremes of several ends (periods first): one moving end keeps the run going; a
    NaN extreme is never steady; fewer than window + 1 periods are not enough."""
    hi = np.array([[10.0, 20.0], [10.0, 20.0], [10.0, 20.0]])
    lo = hi - 1.0
    assert extremes_settled(hi, lo, tolerance=0.002, window=2, floor=0.0)
    moved = hi.copy()
    moved[-1, 1] += 0.01  # 1 % of that end's 1 N range
    assert not extremes_settled(moved, lo, tolerance=0.002, window=2, floor=0.0)
    bad = hi.copy()
    bad[-1, 0] = np.nan
    assert not extremes_settled(bad, lo, tolerance=0.002, window=2, floor=0.0)
    assert not extremes_settled(hi[:2], lo[:2], tolerance=0.002, window=2, floor=0.0)
