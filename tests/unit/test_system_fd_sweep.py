"""A sweep of the system frequency domain solved in one compiled call
(cablestudy.dynamics.system_frequency_sweep, cablestudy.dynamics.system_fd_sweep; issue
24): each case from its own start, so the sweep is the case-by-case solve bit for bit
(a case's record does not depend on the cases beside it).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from cablestudy.dynamics.frequency_model import DragSettings
from cablestudy.dynamics.system_frequency_sweep import solve_system_sweep_arrays
from tests.system_frequency_reference import envelope, solve_system_harmonic
from tests.unit.test_system_fd_kernel import _case8_model

FREQUENCIES = np.linspace(0.02, 0.5, 25)


@pytest.fixture(scope="module")
def case8() -> object:
    return _case8_model(21)


def _quantities(r) -> list[np.ndarray]:  # noqa: ANN001
    return [
        r.end_tension,
        r.end_force,
        r.body_force,
        r.point_displacement,
        np.concatenate(r.displacement),
        np.concatenate(r.element_tension),
        np.concatenate(envelope(r)[0]),
    ]


def _close(a, b, bar: float) -> None:  # noqa: ANN001
    assert a.status == b.status == 0, (a.message, b.message)
    for got, ref in zip(_quantities(a), _quantities(b), strict=True):
        big = np.abs(ref).max()
        assert big > 0.0
        np.testing.assert_allclose(got, ref, rtol=0, atol=bar * big)


@pytest.mark.parametrize("dof", [0, 2])
def test_a_cold_sweep_is_the_cases_alone(case8: object, dof: int) -> None:
    """Every case of the sweep is solve_system_harmonic's answer bit for bit (same
    iteration, same work arrays reused), whatever the order given."""
    X = np.zeros((1, 6), dtype=complex)
    X[0, dof] = -2j if dof == 0 else -1j
    w = 2.0 * np.pi * FREQUENCIES[::-1]  # given in falling order
    swept = solve_system_sweep_arrays(case8, w, [X] * w.size)[0]
    for wi, got in zip(w, swept, strict=True):
        alone = solve_system_harmonic(case8, wi, X)
        assert got.iterations == alone.iterations
        _close(got, alone, 0.0)


def test_a_failed_case_in_a_sweep_is_as_alone(case8: object) -> None:
    """A case that does not converge in the allowed iterations fails in the sweep with
    the message it has alone, and the cases after it still solve."""
    X = np.array([[-2j, 0, 0, 0, 0, 0]])
    w = 2.0 * np.pi * np.array([0.30, 0.31, 0.32, 0.33])
    settings = DragSettings(max_iterations=4)
    alone = [solve_system_harmonic(case8, wi, X, settings) for wi in w]
    swept = solve_system_sweep_arrays(case8, w, [X] * w.size, settings)[0]
    assert any(a.status != 0 for a in alone)
    for a, s in zip(alone, swept, strict=True):
        assert s.status == a.status
        assert s.message == a.message
        if a.status == 0:
            _close(s, a, 0.0)


def test_a_system_without_drag_sweeps_directly(case8: object) -> None:
    """No drag: one linear solve a case, as alone."""
    lines = tuple(
        replace(
            r,
            line=replace(
                r.line,
                drag_normal=np.zeros_like(r.line.drag_normal),
                drag_tangential=np.zeros_like(r.line.drag_tangential),
            ),
        )
        for r in case8.lines
    )
    model = replace(case8, lines=lines, point_drag=np.zeros_like(case8.point_drag))
    assert not model.has_drag
    X = np.array([[-2j, 0, 0, 0, 0, 0]])
    w = 2.0 * np.pi * FREQUENCIES[:6]
    for got, wi in zip(solve_system_sweep_arrays(model, w, [X] * w.size)[0], w, strict=True):
        _close(got, solve_system_harmonic(model, wi, X), 0.0)
