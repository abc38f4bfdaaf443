"""The step check's verdict and words (cablestudy/dynamics/step_check.py): numbers in,
the tolerance per end, the first-order estimate of the steps needed, the warning."""

from __future__ import annotations

import numpy as np

from cablestudy.analyses import plausibility
from cablestudy.analyses.plausibility import KINDS, SEPARATOR
from cablestudy.dynamics.step_check import STEP, step_warning, verdict_of


def _verdict(fine_min: float, **kw: object):  # noqa: ANN202
    coarse = np.array([[200.0, 100.0], [150.0, 140.0]])  # (end, max/min) [N]
    fine = coarse.copy()
    fine[0, 1] = fine_min
    return verdict_of(
        coarse,
        fine,
        coarse[:, 0] - coarse[:, 1],
        names=("end A", "end B"),
        step_tolerance=0.01,
        floor=1e-6,
        contact_changes=4,
        slack_switches=0,
        points_per_period=64,
        **kw,
    )


def test_each_end_is_held_to_its_lines_largest_range() -> None:
    """Ends of one line share the tolerance of its largest range (100 N: 1 N); on two
    lines each end keeps its own (end B's range 10 N: 0.1 N)."""
    one = _verdict(100.0)
    np.testing.assert_array_equal(one.tolerance, [1.0, 1.0])
    two = _verdict(100.0, line_of_end=np.array([0, 1]))
    np.testing.assert_array_equal(two.tolerance, [1.0, 0.1])
    assert one.agrees and two.agrees


def test_the_steps_needed_are_first_order() -> None:
    """A halving that moves the minimum by d = 4 N: the run's error is about 2 d = 8 N,
    eight tolerances (1 N), so 8 x 64 = 512 steps a period bring it within one."""
    v = _verdict(96.0)
    assert not v.agrees and v.worst() == (0, 1)
    assert v.needed_points() == 512
    # within the tolerance the estimate is never below the halved step's count
    assert _verdict(99.9).needed_points() == 128


def test_the_warning_names_both_values_in_one_warning() -> None:
    text = step_warning(_verdict(96.0))
    assert text.startswith(f"{STEP}: the minimum tension at end A ")
    assert "100 N at points_per_period 64" in text
    assert "96 N with the period run again at 128" in text
    assert "about points_per_period 512 is needed" in text
    assert SEPARATOR not in text  # one warning: the run's summary splits on it
    assert STEP in KINDS and plausibility.STEP == STEP
    assert step_warning(_verdict(100.5)) == ""
