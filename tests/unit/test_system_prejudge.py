"""The quasi-static geometric check ``method: auto`` applies to a system before the
frequency domain (:mod:`cablestudy.dynamics.system_prejudge`,
:mod:`cablestudy.analyses.system_prejudge`)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from cablestudy.dynamics.system_prejudge import MARGIN, line_sags, shape_change_ratios
from cablestudy.dynamics.validity import sag

ROOT = Path(__file__).parents[2]


def _parabola(n: int, span: float, depth: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes at equal parameter of a parabola of ``span`` sagging ``depth`` mid-span in
    the x-z plane (unstretched arc length taken as the parameter times the span)."""
    x = np.linspace(0.0, span, n)
    z = -4.0 * depth * (x / span) * (1.0 - x / span)
    return x.copy(), np.stack([x, np.zeros(n), z], axis=1)


def test_sags_are_the_single_lines() -> None:
    rng = np.random.default_rng(3)
    shapes = rng.normal(size=(4, 7, 3))
    shapes[3] = np.linspace(0.0, 1.0, 7)[:, None] * [1.0, 2.0, 3.0]  # straight
    got = line_sags(shapes)
    # the same formula on the same numbers, whole arrays instead of one line: within
    # rounding of a few operations on numbers of order one
    np.testing.assert_allclose(got[:3], [sag(p) for p in shapes[:3]], rtol=1e-13)
    assert got[3] <= 1e-15


def test_rigid_motion_and_uniform_stretch_change_no_shape() -> None:
    """The measure is relative to the chord's motion: a translation of the whole line
    and a stretch along its chord that moves every node with its share of the chord
    change no shape: zero to rounding (x 1.001 - x at x <= 40 m rounds by a few times
    40 x 1.1e-16; over the 0.5 m sag, below 1e-13)."""
    s, static = _parabola(21, 40.0, 0.5)
    moved = np.stack([static + [2.0, -1.0, 0.3], static - [2.0, -1.0, 0.3]])
    ratio = shape_change_ratios(s[None], static[None], moved[:, None])
    assert ratio[0] <= 1e-14
    stretched = static * [1.001, 1.0, 1.0]
    ratio = shape_change_ratios(s[None], static[None], stretched[None, None])
    assert ratio[0] <= 1e-13


def test_sag_change_measured_against_the_sag() -> None:
    """A parabola whose sag grows from d to d + e with the ends held: the mid node moves
    by e, the largest deformation; the ratio is e / d exactly (to rounding). Both
    extremes are taken: the larger counts."""
    s, static = _parabola(21, 40.0, 0.5)
    _, deeper = _parabola(21, 40.0, 0.6)
    _, shallower = _parabola(21, 40.0, 0.45)
    ratio = shape_change_ratios(s[None], static[None], np.stack([deeper, shallower])[:, None])
    np.testing.assert_allclose(ratio, [0.1 / 0.5], rtol=1e-12)


def test_case8_two_metres_is_decided_before_the_frequency_domain() -> None:
    """case8 surged 2 m: the bridles' quasi-static shape change is 0.31 to 0.38 of their
    3 cm sag (above MARGIN x 0.075); at 0.1 m it is 0.012 to 0.014, far below, and the
    frequency domain runs (its own measure there: 0.03, trusted). The legs touch the
    seabed at their anchors and are not judged by this check."""
    from cablestudy.analyses import system_dynamic
    from cablestudy.analyses.system import _statics, evaluate_system_case
    from cablestudy.analyses.system_prejudge import quasi_static_ratios
    from cablestudy.study import parse_study_text
    from cablestudy.study.grid import expand_cases

    text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
    text = text.replace("elements: 20", "elements: 3")
    text = text.replace("points_per_period: 128", "points_per_period: 16")
    got = {}
    # statics are shared per static problem: a case solved earlier in this process (by
    # another test, without the extremes) would be this case's, with no extremes in it
    system_dynamic._STATIC_CACHE.clear()
    for amplitude in (0.1, 2.0):
        (_, [case]) = expand_cases(
            parse_study_text(text.replace("amplitude: 2.0", f"amplitude: {amplitude}"), "c8.yaml")
        )
        system, res, status, _, _, _ = _statics(case, deadline=1e18)
        assert status == 0
        ratio, judged = quasi_static_ratios(case, system, res)
        got[amplitude] = (ratio, judged)
        # the extremes solved with the statics (res.extra) or, for a motion they were not
        # solved for (a sweep's other amplitudes), on their own from the static state:
        # both are equilibria within the system Newton's tolerance (1e-9 of the forces,
        # a relative shape error of that order against 0.1 to 1 of the sag): 1e-6
        assert res.extra is not None
        alone = quasi_static_ratios(case, system, replace(res, extra=None))
        np.testing.assert_array_equal(alone[1][judged], True)
        np.testing.assert_allclose(alone[0][judged], ratio[judged], rtol=1e-6)
        rec = evaluate_system_case(case)
        assert rec.status == 0, rec.message
        reason = str(rec.data["dynamic_method_reason"])
        if amplitude == 2.0:
            assert str(rec.data["dynamic_method"]) == "time"
            assert "quasi-static" in reason and "before the frequency domain" in reason, reason
        else:
            assert str(rec.data["dynamic_method"]) == "frequency", reason
    small, large = got[0.1], got[2.0]
    legs = [2, 5, 8]
    assert not np.any(small[1][legs]) and np.all(np.delete(small[1], legs))
    assert np.nanmax(small[0]) < 0.2 * 0.075
    bridles = [0, 1, 3, 4, 6, 7]
    assert np.max(large[0][bridles]) > 2.0 * MARGIN * 0.075  # 0.376: twice the threshold
    # the quasi-static shape change grows with the amplitude: about 20x over 0.1 -> 2 m
    # on the bridles in line with the surge (slightly more: the geometry stiffens)
    assert np.all(large[0][[0, 1]] > 15.0 * small[0][[0, 1]])
