"""A sweep of the system frequency domain solved in one compiled call
(cablestudy.dynamics.system_frequency_sweep, cablestudy.dynamics.system_fd_sweep; issue
24): as a study runs it (no warm start) it is the case-by-case solve bit for bit; with
a warm start (each case started from its neighbours' converged drag; measured, not
what a study runs, since each answer would then depend on its neighbours) it stops at
an iterate of the same fixed point within the iteration's tolerance, in fewer
iterations.

The bar of the warm start. The drag iteration stops when the velocity amplitudes change
by at most ``tolerance`` (1e-6) of the largest; the iterate it stops at lies about
``tolerance q / (1 - q)`` from the fixed point (``q`` the contraction of the mixed
iteration), whatever its start (here the fixed point is the same iteration run to
1e-9, where rounding still lets it stop). Measured against the fixed point (the same iteration to
1e-11) on the imported case8 (surge 2 m, 50 frequencies 0.02-0.5 Hz, 20 elements): the
cold start's answers lie up to 4.1e-7 of the largest from it (displacements; tensions
1.3e-7), the warm start's up to 2.9e-7; the two differ by up to 5.0e-7. A tenth of the
tolerance cannot separate them: the cold start's own distance from the fixed point is
half the tolerance. The bar is the tolerance itself, for each start against the fixed
point.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from cablestudy.dynamics.frequency_model import DragSettings
from cablestudy.dynamics.system_frequency import solve_system_harmonic
from cablestudy.dynamics.system_frequency_sweep import solve_system_sweep
from tests.unit.test_system_fd_kernel import _case8_model

TOLERANCE = DragSettings().tolerance
#: the iteration's tolerance (module docstring)
BAR = TOLERANCE
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
        np.concatenate(r.envelope()[0]),
    ]


def _close(a, b, bar: float) -> None:  # noqa: ANN001
    assert a.status == b.status == 0, (a.message, b.message)
    for got, ref in zip(_quantities(a), _quantities(b), strict=True):
        big = np.abs(ref).max()
        assert big > 0.0
        np.testing.assert_allclose(got, ref, rtol=0, atol=bar * big)


@pytest.mark.parametrize("dof", [0, 2])
def test_a_cold_sweep_is_the_cases_alone(case8: object, dof: int) -> None:
    """Without warm start every case of the sweep is solve_system_harmonic's answer bit
    for bit (same iteration, same work arrays reused), whatever the order given."""
    X = np.zeros((1, 6), dtype=complex)
    X[0, dof] = -2j if dof == 0 else -1j
    w = 2.0 * np.pi * FREQUENCIES[::-1]  # given in falling order
    swept = solve_system_sweep(case8, w, [X] * w.size, warm=False)
    for wi, got in zip(w, swept, strict=True):
        alone = solve_system_harmonic(case8, wi, X)
        assert got.iterations == alone.iterations
        _close(got, alone, 0.0)


def test_a_warm_sweep_stops_within_the_tolerance_in_fewer_iterations(case8: object) -> None:
    """Warm starts (neighbours' drag, extrapolated) and cold starts both land within the
    tolerance of the fixed point (module docstring), the warm ones in fewer iterations;
    a sweep of two motions keeps each motion's cases together."""
    X1 = np.array([[-2j, 0, 0, 0, 0, 0]])
    X2 = np.array([[0, 0, -1j, 0, 0, 0]])
    w = 2.0 * np.pi * FREQUENCIES
    motions = [X1] * w.size + [X2] * w.size
    ww = np.concatenate([w, w])
    tight = solve_system_sweep(
        case8, ww, motions, DragSettings(tolerance=1e-9, max_iterations=200), warm=False
    )
    cold = solve_system_sweep(case8, ww, motions, warm=False)
    warm = solve_system_sweep(case8, ww, motions, warm=True)
    for c, h, t in zip(cold, warm, tight, strict=True):
        _close(c, t, BAR)
        _close(h, t, BAR)
    iters_cold = sum(r.iterations for r in cold)
    iters_warm = sum(r.iterations for r in warm)
    assert iters_warm < 0.8 * iters_cold, (iters_warm, iters_cold)


def test_a_failed_case_in_a_sweep_is_as_alone(case8: object) -> None:
    """A case that does not converge in the allowed iterations fails in the sweep with
    the message it has alone (its warm start failed too, then the cold start ran), and
    the cases after it still solve."""
    X = np.array([[-2j, 0, 0, 0, 0, 0]])
    w = 2.0 * np.pi * np.array([0.30, 0.31, 0.32, 0.33])
    settings = DragSettings(max_iterations=4)
    alone = [solve_system_harmonic(case8, wi, X, settings) for wi in w]
    swept = solve_system_sweep(case8, w, [X] * w.size, settings)
    assert any(a.status != 0 for a in alone)
    for a, s in zip(alone, swept, strict=True):
        if a.status != 0:
            assert s.status in (0, a.status)
            if s.status:
                assert s.message == a.message
        else:
            _close(s, a, BAR)


def test_a_system_without_drag_sweeps_directly(case8: object) -> None:
    """No drag: one linear solve a case, the same with or without warm start."""
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
    for got, wi in zip(solve_system_sweep(model, w, [X] * w.size), w, strict=True):
        _close(got, solve_system_harmonic(model, wi, X), 0.0)
