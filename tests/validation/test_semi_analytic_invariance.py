"""Invariance of the semi-analytic solution: the same line described from B to A, the
whole problem rotated about the vertical, and mirrored in the x-z plane give the same
(transformed) answer. Both solutions are converged to 1e-11, so they agree to ~1e-9
relative."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cablestudy.statics import EndCondition, LineModel, Medium, StaticProblem
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.statics.semi_analytic_shape import reversed_line

SOLVER = SemiAnalyticSolver()
TOL = 1e-11
AGREE = 1e-8


def base_line() -> LineModel:
    return LineModel(
        length=np.array([60.0, 90.0]),
        weight=np.array([40.0, 8.0]),
        mass=np.array([5.0, 1.5]),
        axial_stiffness=np.array([5e8, 2e7]),
        diameter=np.array([0.08, 0.05]),
        drag_normal=np.array([1.2, 1.5]),
        drag_tangential=np.array([0.01, 0.02]),
        added_mass_normal=np.ones(2),
        added_mass_tangential=np.zeros(2),
        bending_stiffness=np.zeros(2),
        damping_ratio=np.zeros(2),
        attachment_s=np.array([100.0]),
        attachment_force=np.array([[0.0, 0.0, 300.0]]),
        attachment_mass=np.zeros(1),
        attachment_volume=np.zeros(1),
    )


def rot(theta: float) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


PROBLEMS = {
    "sheared-current": dict(
        medium=Medium(
            density=1025.0,
            gravity=9.80665,
            current_z=np.array([-120.0, 0.0]),
            current_velocity=np.array([[0.2, 0.3, 0.0], [0.8, 0.0, 0.0]]),
        ),
        a=np.array([0.0, 0.0, -100.0]),
        b=np.array([110.0, 30.0, -5.0]),
    ),
    "sloped-seabed-with-friction": dict(
        medium=Medium(
            density=1025.0,
            gravity=9.80665,
            depth=100.0,
            seabed_slope=math.radians(3),
            seabed_heading=math.radians(20),
            friction=0.4,
        ),
        a=np.array([0.0, 0.0, -100.0]),
        b=np.array([100.0, 10.0, 0.0]),
    ),
}


def solve(medium: Medium, line: LineModel, a: np.ndarray, b: np.ndarray):  # noqa: ANN201
    res = SOLVER.solve(
        StaticProblem(
            line=line,
            medium=medium,
            end_a=EndCondition(kind="fixed", position=a),
            end_b=EndCondition(kind="fixed", position=b),
            n_nodes=150,
            tolerance=TOL,
        )
    )  # no node on the attachment
    assert res.status == 0, res.message
    return res


def close(x: np.ndarray, y: np.ndarray, scale: float) -> bool:
    return bool(np.max(np.abs(np.asarray(x) - np.asarray(y))) <= AGREE * scale)


@pytest.mark.parametrize("name", sorted(PROBLEMS))
def test_swapping_the_ends(name: str) -> None:
    p = PROBLEMS[name]
    one = solve(p["medium"], base_line(), p["a"], p["b"])
    two = solve(p["medium"], reversed_line(base_line()), p["b"], p["a"])
    F = np.abs(one.force_a).max()
    assert close(one.position, two.position[::-1], 150.0)
    assert close(one.tension, two.tension[::-1], F)
    assert close(one.force_a, two.force_b, F) and close(one.force_b, two.force_a, F)
    assert one.laid_length == pytest.approx(two.laid_length, rel=1e-8, abs=1e-8)


def _rotated_medium(m: Medium, R: np.ndarray, theta: float) -> Medium:
    return Medium(
        density=m.density,
        gravity=m.gravity,
        depth=m.depth,
        seabed_slope=m.seabed_slope,
        seabed_heading=m.seabed_heading + theta,
        friction=m.friction,
        current_z=m.current_z,
        current_velocity=m.current_velocity @ R.T,
    )


@pytest.mark.parametrize("name", sorted(PROBLEMS))
def test_rotating_the_heading_of_the_whole_problem(name: str) -> None:
    p = PROBLEMS[name]
    theta = math.radians(137.0)
    R = rot(theta)
    one = solve(p["medium"], base_line(), p["a"], p["b"])
    two = solve(_rotated_medium(p["medium"], R, theta), base_line(), R @ p["a"], R @ p["b"])
    F = np.abs(one.force_a).max()
    assert close(one.position @ R.T, two.position, 150.0)
    assert close(R @ one.force_a, two.force_a, F) and close(R @ one.force_b, two.force_b, F)
    assert close(one.tension, two.tension, F)


@pytest.mark.parametrize("name", sorted(PROBLEMS))
def test_mirroring_in_the_xz_plane(name: str) -> None:
    p = PROBLEMS[name]
    M = np.diag([1.0, -1.0, 1.0])
    m = p["medium"]
    mirrored = Medium(
        density=m.density,
        gravity=m.gravity,
        depth=m.depth,
        seabed_slope=m.seabed_slope,
        seabed_heading=-m.seabed_heading,
        friction=m.friction,
        current_z=m.current_z,
        current_velocity=m.current_velocity @ M,
    )
    one = solve(m, base_line(), p["a"], p["b"])
    two = solve(mirrored, base_line(), M @ p["a"], M @ p["b"])
    F = np.abs(one.force_a).max()
    assert close(one.position @ M, two.position, 150.0)
    assert close(M @ one.force_a, two.force_a, F) and close(M @ one.force_b, two.force_b, F)
