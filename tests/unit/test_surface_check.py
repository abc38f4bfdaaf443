"""cablestudy.analyses.plausibility's surface check on shapes built here, where the
answer is known exactly (the end-to-end cases: tests/integration/test_surface_warning.py)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from cablestudy.analyses.plausibility import (
    SURFACE_TOLERANCE,
    has_free_surface,
    highest_points,
    joined,
    surface_warning,
    surface_warnings,
)
from cablestudy.study.environment import FLUID_DENSITY

S = np.linspace(0.0, 100.0, 101)
#: a parabolic arch through z = -10 m at both ends, its top 5 m out of the water at s = 50
ARCH = -10.0 + 15.0 * (1.0 - ((S - 50.0) / 50.0) ** 2)
#: a line hanging between two supports at the surface (z <= 0, 0 at the ends)
HANG = -20.0 * (1.0 - ((S - 50.0) / 50.0) ** 2)


def test_an_arch_out_of_the_water_names_its_highest_node() -> None:
    text = surface_warning(S, ARCH)
    m = re.match(r"surface: the line rises .* to z = (\S+) m at s = (\S+) m \(its highest", text)
    assert m, text
    assert float(m.group(1)) == 5.0 and float(m.group(2)) == 50.0  # the node at the top
    assert ";" not in text  # one warning: the separator between warnings is "; "
    assert joined([text]) == text


def test_a_line_held_at_the_surface_or_under_it_is_not_warned() -> None:
    assert surface_warning(S, HANG) == ""
    # round-off at a held end: below the tolerance (1e-6 of the length) is no rise
    ends = HANG.copy()
    ends[[0, -1]] = 0.5 * SURFACE_TOLERANCE * 100.0
    assert surface_warning(S, ends) == ""
    ends[0] = 2.0 * SURFACE_TOLERANCE * 100.0  # twice the tolerance: judged out
    assert "at s = 0 m" in surface_warning(S, ends)


def test_lines_of_a_system_name_the_highest_and_list_those_above() -> None:
    z = np.stack([HANG, ARCH, ARCH - 4.0])  # under; 5 m out; 1 m out
    s = np.broadcast_to(S, z.shape)
    text = surface_warning(s, z, ["a", "b", "c"])
    assert text.startswith("surface: line b rises") and "z = 5 m" in text
    assert text.endswith("(lines above the surface: b, c)")
    one = surface_warning(s[:2], z[:2], ["a", "b"])
    assert one.startswith("surface: line b rises") and "lines above" not in one


def test_a_batch_warns_only_its_kept_cases_and_skips_nan() -> None:
    z = np.stack([ARCH, HANG, ARCH, np.full_like(S, np.nan)])
    found = surface_warnings(S, z, np.array([True, True, False, True]))
    assert list(found) == [0] and found[0] == surface_warning(S, ARCH)
    top, at = highest_points(S, z)
    np.testing.assert_array_equal(top[:3], [5.0, 0.0, 5.0])
    np.testing.assert_array_equal(at[:3], [50.0, 0.0, 50.0])  # the first of equal nodes
    assert np.isnan(top[3]) and np.isnan(at[3])


@pytest.mark.parametrize(
    ("density", "liquid"),
    [
        (FLUID_DENSITY["water"], True),
        (FLUID_DENSITY["air"], False),
        (FLUID_DENSITY["vacuum"], False),
        (120.0, False),  # air at 100 bar
        (800.0, True),  # an oil
    ],
)
def test_only_a_liquid_has_a_surface(density: float, liquid: bool) -> None:
    assert has_free_surface(density) is liquid
