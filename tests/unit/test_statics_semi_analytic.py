"""Behaviour of the semi-analytic solver: end types and force conventions, drag loop,
starting guesses for awkward geometries, failures as data."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from cablestudy.statics import STATIC_SOLVERS, EndCondition, Medium, StaticProblem
from cablestudy.statics.base import STATUS_OK, STATUS_TIME_LIMIT
from cablestudy.statics.semi_analytic import SemiAnalyticSolver

from ..statics_helpers import fixed, make_line

SOLVER = SemiAnalyticSolver()
WATER = Medium(density=1025.0, gravity=9.80665)


def current(speed: float, heading_deg: float = 0.0) -> Medium:
    h = math.radians(heading_deg)
    return Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=np.array([0.0]),
        current_velocity=np.array([[speed * math.cos(h), speed * math.sin(h), 0.0]]),
    )


def test_registered_as_catenary_and_supports_everything() -> None:
    assert isinstance(STATIC_SOLVERS["catenary"].solver, SemiAnalyticSolver)
    prob = StaticProblem(
        line=make_line([10.0, 5.0], [3.0, 1.0], 1e6, attachments=[(4, (0, 0, 1))]),
        medium=current(1.0),
        end_a=fixed(0, 0, 0),
        end_b=EndCondition(kind="mooring", force=np.array([5.0, 0, 0]), z=1.0),
    )
    assert SOLVER.unsupported(prob) == []


def test_towing_is_explicit_and_follows_the_force_convention() -> None:
    """Towing (seed 3.2): the given force is applied to the line at B, so force_b (on the
    attachment) is its negative, and force_a + force_b = total applied load."""
    F = np.array([300.0, 50.0, 120.0])
    atts = [(30.0, (0.0, 0.0, -200.0))]
    prob = StaticProblem(
        line=make_line([50.0], [4.0], 1e6, attachments=atts),
        medium=WATER,
        end_a=fixed(0, 0, 0),
        end_b=EndCondition(kind="force", force=F),
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK and res.iterations == 0
    assert np.allclose(res.force_b, -F, rtol=0, atol=1e-12)
    total = np.array([0.0, 0.0, -4.0 * 50.0 - 200.0])
    assert np.allclose(res.force_a + res.force_b, total, atol=1e-10)
    assert res.tension[-1] == pytest.approx(np.linalg.norm(F), rel=1e-14)
    assert res.tension[0] == pytest.approx(np.linalg.norm(res.force_a), rel=1e-14)


def test_mooring_end_meets_its_height_and_horizontal_force() -> None:
    """Mooring (seed 3.3): known horizontal force on the line at B and B's height."""
    Fh = np.array([800.0, -300.0, 0.0])
    prob = StaticProblem(
        line=make_line([120.0], [30.0], 1e8),
        medium=WATER,
        end_a=fixed(0, 0, -80),
        end_b=EndCondition(kind="mooring", force=Fh, z=0.0),
        tolerance=1e-11,
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    assert res.position[-1, 2] == pytest.approx(0.0, abs=1e-9)
    assert np.allclose(res.force_b[:2], -Fh[:2], atol=1e-9)
    # the same line solved with both ends fixed at the found positions gives the same forces
    both = SOLVER.solve(
        StaticProblem(
            line=prob.line,
            medium=WATER,
            end_a=fixed(0, 0, -80),
            end_b=fixed(*res.position[-1]),
            tolerance=1e-12,
        )
    )
    assert np.allclose(both.force_b, res.force_b, rtol=1e-8)


def test_free_end_a_is_solved_as_the_reversed_line() -> None:
    F = np.array([100.0, 0.0, 400.0])
    prob = StaticProblem(
        line=make_line([30.0, 20.0], [5.0, 9.0], [1e6, 3e5]),
        medium=WATER,
        end_a=EndCondition(kind="force", force=F),
        end_b=fixed(10, 0, -5),
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    assert np.allclose(res.force_a, -F, atol=1e-12)
    assert np.allclose(res.position[-1], [10, 0, -5], atol=1e-12)
    assert np.allclose(res.force_a + res.force_b, [0, 0, -(5 * 30 + 9 * 20)], atol=1e-9)


@pytest.mark.parametrize("kind", ["fixed", "force", "mooring"])
def test_still_water_pays_for_no_drag_loop(kind: str) -> None:
    end_b = {
        "fixed": fixed(60, 0, -10),
        "force": EndCondition(kind="force", force=np.array([100.0, 0, 300])),
        "mooring": EndCondition(kind="mooring", force=np.array([100.0, 0, 0]), z=-10.0),
    }[kind]
    res = SOLVER.solve(
        StaticProblem(
            line=make_line([100.0], [5.0], 1e6), medium=WATER, end_a=fixed(0, 0, 0), end_b=end_b
        )
    )
    assert res.status == STATUS_OK and res.drag_iterations == 0


@pytest.mark.parametrize("rb", [(60.0, 0.0, -10.0), (10.0, 5.0, -70.0), (95.0, 0.0, 0.0)])
def test_drag_dominated_light_tether_converges(rb: tuple[float, float, float]) -> None:
    """2 m/s on a 0.5 N/m tether (normal drag ~ 100 times the weight): the drag loop
    converges to the tolerance and the forces balance weight plus drag."""
    prob = StaticProblem(
        line=make_line([100.0], [0.5], 1e6, diameter=0.02),
        medium=current(2.0, 30),
        end_a=fixed(0, 0, 0),
        end_b=fixed(*rb),
        tolerance=1e-9,
        n_nodes=51,
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    assert res.drag_iterations > 0 and res.residual <= 1e-9
    # drag on the converged shape balances the end forces (pieces = output intervals here)
    from cablestudy.physics.hydro import drag_per_length

    chord = np.diff(res.position, axis=0)
    lc = np.linalg.norm(chord, axis=1)
    heading = math.radians(30)
    f = drag_per_length(
        np.array([2.0 * math.cos(heading), 2.0 * math.sin(heading), 0.0]),
        chord / lc[:, None],
        density=1025.0,
        diameter=np.full(50, 0.02),
        drag_normal=np.full(50, 1.2),
        drag_tangential=np.full(50, 0.01),
    )
    total = (f * lc[:, None]).sum(axis=0) + np.array([0, 0, -0.5 * 100.0])
    # the loop stops when the summed change of the drag loads is below tolerance times
    # the load scale, which bounds the imbalance; 10x margin for round-off in the sums
    assert np.max(np.abs(res.force_a + res.force_b - total)) <= 1e-8 * np.abs(total).max()
    assert np.linalg.norm(total) > 10 * 0.5 * 100.0  # drag really dominates the weight


def test_current_turning_with_depth_bends_the_line_out_of_plane() -> None:
    med = Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=np.array([-100.0, 0.0]),
        current_velocity=np.array([[0.0, 0.5, 0.0], [0.5, 0.0, 0.0]]),
    )
    prob = StaticProblem(
        line=make_line([150.0], [2.0], 1e7, diameter=0.03),
        medium=med,
        end_a=fixed(0, 0, 0),
        end_b=fixed(0, 0, -100),
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    top, bottom = res.position[10], res.position[-10]
    assert top[0] > 1.0 and bottom[1] > 1.0  # pushed along +x near the top, +y near the bottom


def test_attachments_clump_weight_and_buoy() -> None:
    """A buoy (upward force) and a clump weight on a line: the line rises at the buoy and
    the end forces balance all loads."""
    atts = [(40.0, (0.0, 0.0, 2000.0)), (80.0, (0.0, 0.0, -1500.0))]
    prob = StaticProblem(
        line=make_line([120.0], [20.0], 1e8, attachments=atts),
        medium=WATER,
        end_a=fixed(0, 0, -100),
        end_b=fixed(100, 0, 0),
        n_nodes=121,
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    assert np.allclose(res.force_a + res.force_b, [0, 0, 2000 - 1500 - 20 * 120], atol=1e-8)
    slope_before = res.position[40, 2] - res.position[39, 2]
    slope_after = res.position[41, 2] - res.position[40, 2]
    assert slope_after < slope_before  # the buoy makes a kink that is convex upwards


def test_weightless_slack_line_fails_with_a_message() -> None:
    res = SOLVER.solve(
        StaticProblem(
            line=make_line([100.0], [0.0], 1e6),
            medium=Medium(density=0.0, gravity=9.8),
            end_a=fixed(0, 0, 0),
            end_b=fixed(50, 0, 0),
        )
    )
    assert res.status != STATUS_OK and res.message
    assert np.all(np.isnan(res.position)) and np.isnan(res.force_a).all()


def test_weightless_taut_line_is_a_straight_bar() -> None:
    res = SOLVER.solve(
        StaticProblem(
            line=make_line([100.0], [0.0], 1e6),
            medium=Medium(density=0.0, gravity=9.8),
            end_a=fixed(0, 0, 0),
            end_b=fixed(60, 0, 80.1),
            tolerance=1e-12,
        )
    )
    assert res.status == STATUS_OK, res.message
    T = 1e6 * (math.hypot(60, 80.1) / 100 - 1)
    assert np.linalg.norm(res.force_a) == pytest.approx(T, rel=1e-10)


def test_weightless_slack_line_in_current_is_shaped_by_drag() -> None:
    """No still-water shape exists (slack, weightless); the drag start on the straight
    chord gives the loop its first loads."""
    res = SOLVER.solve(
        StaticProblem(
            line=make_line([100.0], [0.0], 1e6),
            medium=current(1.0, 90),
            end_a=fixed(0, 0, 0),
            end_b=fixed(50, 0, 0),
        )
    )
    assert res.status == STATUS_OK, res.message
    assert np.max(res.position[:, 1]) > 10.0


def test_time_limit_is_reported() -> None:
    prob = StaticProblem(
        line=make_line([100.0], [0.5], 1e6),
        medium=current(2.0),
        end_a=fixed(0, 0, 0),
        end_b=fixed(50, 0, -20),
    )
    res = SOLVER.solve(prob, deadline=time.monotonic() - 1.0)
    assert res.status == STATUS_TIME_LIMIT and "time limit" in res.message


def test_end_below_the_seabed_fails_with_a_message() -> None:
    med = Medium(density=1025.0, gravity=9.80665, depth=50.0, seabed_slope=math.radians(10.0))
    res = SOLVER.solve(
        StaticProblem(
            line=make_line([100.0], [5.0], 1e6),
            medium=med,
            end_a=fixed(0, 0, 0),
            end_b=fixed(-80, 0, -70),
        )
    )
    assert res.status != STATUS_OK and "below the seabed" in res.message


def test_sloped_seabed_laid_part_lies_on_the_slope() -> None:
    """A seabed rising 5 deg towards +x: the laid part lies on the plane, the anchor
    force points along the slope, and the tension falls towards the anchor by
    (mu cos + sin) w per metre when the line runs up-slope."""
    slope = math.radians(5.0)
    mu, w = 0.3, 400.0
    med = Medium(density=1025.0, gravity=9.80665, depth=100.0, seabed_slope=slope, friction=mu)
    prob = StaticProblem(
        line=make_line([300.0], [w], 5e8),
        medium=med,
        end_a=fixed(0, 0, -100),
        end_b=fixed(230, 0, 0),
        n_nodes=301,
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    assert res.laid_length > 50.0
    laid = res.s <= res.laid_length
    ground = -100.0 + math.tan(slope) * res.position[laid, 0]
    assert np.allclose(res.position[laid, 2], ground, atol=1e-8)
    dT = np.diff(res.tension[laid])
    rate = w * (mu * math.cos(slope) + math.sin(slope))
    taut = (res.tension[laid][1:] > 1e-6) & (res.tension[laid][:-1] > 1e-6)
    assert np.count_nonzero(taut) > 10
    assert np.allclose(dT[taut], rate * 1.0, rtol=1e-9)  # nodes 1 m apart
    assert res.tension[0] == 0.0 or res.tension[0] < 1e-6  # friction exhausts it


@pytest.mark.parametrize("heading", [0.0, 90.0])
def test_mooring_line_on_the_seabed_in_a_current(heading: float) -> None:
    """Seabed contact and drag together: the laid part stays on the seabed and straight,
    the anchor force lies in the seabed plane, and the line settles within tolerance."""
    h = math.radians(heading)
    med = Medium(
        density=1025.0,
        gravity=9.80665,
        depth=100.0,
        friction=0.3,
        current_z=np.array([0.0]),
        current_velocity=np.array([[math.cos(h), math.sin(h), 0.0]]),
    )
    prob = StaticProblem(
        line=make_line([300.0], [500.0], 5e8, diameter=0.1),
        medium=med,
        end_a=fixed(0, 0, -100),
        end_b=fixed(230, 0, 0),
        n_nodes=151,
    )
    res = SOLVER.solve(prob)
    assert res.status == STATUS_OK, res.message
    assert res.drag_iterations > 0 and res.residual <= prob.tolerance
    assert 100.0 < res.laid_length < 250.0
    laid = res.s < res.laid_length
    assert np.allclose(res.position[laid, 2], -100.0, atol=1e-9 * 300)
    assert np.all(res.position[:, 2] >= -100.0 - 1e-9 * 300)
    assert abs(res.force_a[2]) <= 1e-9 * np.abs(res.force_b).max()
    # the laid part is straight: its points lie on the line from the anchor to the TDP
    pts = res.position[laid]
    if len(pts) > 2:
        d = pts[-1] - pts[0]
        cross = np.cross(pts - pts[0], d / np.linalg.norm(d))
        assert np.max(np.abs(cross)) <= 1e-8 * 300


def test_both_ends_on_the_seabed() -> None:
    """Taut: the line lies straight on the seabed, stretched uniformly to the distance
    between its ends (T = EA (d/L - 1) for one segment). Slack: a failure with a reason."""
    med = Medium(density=1025.0, gravity=9.80665, depth=100.0, friction=0.3)
    taut = SOLVER.solve(
        StaticProblem(
            line=make_line([240.0], [500.0], 5e8),
            medium=med,
            end_a=fixed(0, 0, -100),
            end_b=fixed(150, 200, -100),
        )
    )
    assert taut.status == STATUS_OK, taut.message
    T = 5e8 * (250.0 / 240.0 - 1.0)
    assert np.allclose(taut.tension, T, rtol=1e-12) and taut.laid_length == 240.0
    assert np.allclose(taut.force_a, T * np.array([0.6, 0.8, 0.0]), rtol=1e-12)
    assert np.allclose(taut.position[:, 2], -100.0)
    assert np.allclose(taut.position[-1], [150, 200, -100])
    slack = SOLVER.solve(
        StaticProblem(
            line=make_line([300.0], [500.0], 5e8),
            medium=med,
            end_a=fixed(0, 0, -100),
            end_b=fixed(150, 200, -100),
        )
    )
    assert slack.status != STATUS_OK and "slack on the seabed" in slack.message
