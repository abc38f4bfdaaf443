"""The batch path (many still-water cases at once) gives the one-by-one answer, with
and without the compiled kernel, and falls back to the one-by-one solver for cases it
does not take."""

from __future__ import annotations

import numpy as np

from cablestudy.statics import EndCondition, LineModel, Medium, StaticProblem
from cablestudy.statics.batch import solve_batch
from cablestudy.statics.batch_kernels import _solve_group, batchable
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.statics.semi_analytic_shape import make_layout


def make_line(L: float, w: float, EA: float, atts=()) -> LineModel:  # noqa: ANN001
    one = np.ones(1)
    return LineModel(
        length=L * one,
        weight=w * one,
        mass=one,
        axial_stiffness=EA * one,
        diameter=0.05 * one,
        drag_normal=1.2 * one,
        drag_tangential=0.01 * one,
        added_mass_normal=one,
        added_mass_tangential=0 * one,
        bending_stiffness=0 * one,
        damping_ratio=0 * one,
        attachment_s=np.array([a[0] for a in atts], dtype=float),
        attachment_force=np.array([a[1] for a in atts], dtype=float).reshape(-1, 3),
        attachment_mass=np.zeros(len(atts)),
        attachment_volume=np.zeros(len(atts)),
    )


def problems(n: int = 60) -> list[StaticProblem]:
    rng = np.random.default_rng(3)
    out = []
    water = Medium(density=1025.0, gravity=9.80665)
    for i in range(n):
        L = rng.uniform(50, 150)
        atts = [] if i % 2 else [(rng.uniform(0, L), (0.0, 0.0, -rng.uniform(0, 500)))]
        kind = ("fixed", "mooring", "force")[i % 3]
        b = {
            "fixed": EndCondition(
                kind="fixed",
                position=np.array(
                    [rng.uniform(10, 0.99 * L), rng.uniform(-10, 10), rng.uniform(-20, 20)]
                ),
            ),
            "mooring": EndCondition(
                kind="mooring",
                force=np.array([rng.uniform(100, 2e3), 0, 0]),
                z=rng.uniform(-20, 20),
            ),
            "force": EndCondition(
                kind="force", force=np.array([rng.uniform(100, 2e3), 0, rng.uniform(0, 3e3)])
            ),
        }[kind]
        out.append(
            StaticProblem(
                line=make_line(L, rng.uniform(1, 50), 10 ** rng.uniform(6, 9), atts),
                medium=water,
                end_a=EndCondition(kind="fixed", position=np.zeros(3)),
                end_b=b,
                n_nodes=51,
                tolerance=1e-10,
            )
        )
    return out


def _agree(a, b, L: float) -> None:  # noqa: ANN001
    assert a.status == 0 and b.status == 0
    F = np.max(np.abs(b.force_a))
    # both converge to 1e-10 with a polishing step: agreement to round-off level
    assert np.max(np.abs(a.position - b.position)) <= 1e-9 * L
    assert np.max(np.abs(a.force_a - b.force_a)) <= 1e-8 * F
    assert np.max(np.abs(a.force_b - b.force_b)) <= 1e-8 * F
    assert np.max(np.abs(a.tension - b.tension)) <= 1e-8 * F


def test_batch_equals_one_by_one() -> None:
    probs = problems()
    solver = SemiAnalyticSolver()
    for a, p in zip(solve_batch(probs), probs, strict=True):
        _agree(a, solver.solve(p), p.line.total_length)


def test_group_kernels_agree() -> None:
    probs = [p for p in problems() if p.line.attachment_s.size == 0]
    res = _solve_group(probs, 1, 51, [None] * len(probs))
    solver = SemiAnalyticSolver()
    for a, p in zip(res, probs, strict=True):
        assert a is not None
        _agree(a, solver.solve(p), p.line.total_length)


def test_group_with_attachments_uses_layouts() -> None:
    probs = [p for p in problems() if p.line.attachment_s.size == 1]
    layouts = [make_layout(p.line) for p in probs]
    groups: dict[int, list[int]] = {}
    for i, lay in enumerate(layouts):
        groups.setdefault(len(lay.ell), []).append(i)
    solver = SemiAnalyticSolver()
    for P, idx in groups.items():
        res = _solve_group([probs[i] for i in idx], P, 51, [layouts[i] for i in idx])
        for a, i in zip(res, idx, strict=True):
            assert a is not None
            _agree(a, solver.solve(probs[i]), probs[i].line.total_length)


def test_cases_the_batch_does_not_take_are_solved_one_by_one() -> None:
    current = Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=np.array([0.0]),
        current_velocity=np.array([[1.0, 0.0, 0.0]]),
    )
    seabed = Medium(density=1025.0, gravity=9.80665, depth=100.0)
    p_current = StaticProblem(
        line=make_line(100.0, 5.0, 1e7),
        medium=current,
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=np.array([60, 0, -10.0])),
    )
    p_anchor = StaticProblem(
        line=make_line(300.0, 500.0, 5e8),
        medium=seabed,
        end_a=EndCondition(kind="fixed", position=np.array([0, 0, -100.0])),
        end_b=EndCondition(kind="fixed", position=np.array([230, 0, 0.0])),
    )
    # free-hanging over a seabed that it touches between the ends: the batch declines it
    p_touch = StaticProblem(
        line=make_line(250.0, 500.0, 5e8),
        medium=seabed,
        end_a=EndCondition(kind="fixed", position=np.array([0, 0, -50.0])),
        end_b=EndCondition(kind="fixed", position=np.array([180, 0, -50.0])),
    )
    assert not batchable(p_current) and not batchable(p_anchor) and batchable(p_touch)
    res = solve_batch([p_current, p_anchor, p_touch, *problems(4)])
    assert res[0].status == 0 and res[0].drag_iterations > 0
    assert res[1].status == 0 and res[1].laid_length > 0
    assert res[2].status == 0 and res[2].laid_length > 0.0
    assert all(r.status == 0 for r in res[3:])
