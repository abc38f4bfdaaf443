"""The compiled drag iteration of the system frequency domain
(cablestudy.dynamics.system_fd_kernel, issue 24) against the NumPy/LAPACK iteration it
replaces (tests/system_frequency_reference.py, ``solve_reference``), and the
frequency domain at two elements a line (one inner node: the band of a line's inner
rows narrower than a node's drag block, which raised IndexError before).

Both iterations solve the same equations from the same quasi-static start with the
same fit, mixing and tolerance; they differ in rounding only (threshold instead of
partial pivoting, four right sides instead of six, the half-period sums of the fit,
reassociated sums). So they take the same number of iterations and their answers
differ by rounding amplified by the iteration, far below the iteration's tolerance
(1e-6 on the velocities, which is what separates two answers that stopped at different
iterations): measured at most 8.9e-10 of the largest value on the case8 model below
(surge, heave, pitch, 0.02-0.5 Hz) and 1.1e-8 on the imported case8 (surge 2 m, heave
1 m, 50 frequencies, 20 and 40 elements); the bar is 1e-7, a tenth of the tolerance.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from cablestudy.dynamics.system_frequency import system_linear
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system import solve_system
from cablestudy.statics.system_model import FREE
from tests.system_frequency_reference import envelope, solve_reference, solve_system_harmonic
from tests.system_models import CASE8_LINES, CASE8_POINTS, system_of

SOLVER = STATIC_SOLVERS["catenary"]
#: a tenth of the drag iteration's tolerance (module docstring)
BAR = 1e-7


def _case8_model(nodes: int, *, drag: float = 1.2):  # noqa: ANN202
    s = system_of(CASE8_POINTS, CASE8_LINES, np.zeros(6))
    lines = []
    for sl in s.lines:
        line = replace(
            sl.problem.line,
            added_mass_normal=np.array([1.0]),
            damping_ratio=np.array([0.5]),
            drag_normal=np.array([drag]),
            drag_tangential=np.array([0.01 * drag]),
        )
        lines.append(replace(sl, problem=replace(sl.problem, line=line, n_nodes=nodes)))
    system = replace(s, lines=tuple(lines))
    res = solve_system(system, SOLVER)
    assert res.status == 0, res.message
    # the free junctions carry mass, added mass and drag (the points' fit is exercised)
    free = system.point_kind == FREE
    model, why = system_linear(
        system,
        res,
        point_mass=np.where(free, 500.0, 0.0),
        point_added_mass=np.where(free, 200.0, 0.0),
        point_drag=np.where(free, 300.0, 0.0),
    )
    assert model is not None, why
    return model


def _same(a, b) -> None:  # noqa: ANN001
    """The compiled answer ``a`` is the reference ``b`` (module docstring)."""
    assert a.status == b.status == 0, (a.message, b.message)
    assert a.iterations == b.iterations
    for got, ref in (
        (a.end_tension, b.end_tension),
        (a.end_force, b.end_force),
        (a.body_force, b.body_force),
        (a.point_displacement, b.point_displacement),
        (np.concatenate(a.displacement), np.concatenate(b.displacement)),
        (np.concatenate(a.element_tension), np.concatenate(b.element_tension)),
    ):
        big = np.abs(ref).max()
        assert big > 0.0
        np.testing.assert_allclose(got, ref, rtol=0, atol=BAR * big)
    assert a.residual <= 1e-8 and b.residual <= 1e-8


@pytest.fixture(scope="module")
def case8() -> object:
    return _case8_model(21)


@pytest.mark.parametrize("frequency", [0.02, 0.1, 0.3, 0.5])
@pytest.mark.parametrize("dof", [0, 2, 4])
def test_compiled_iteration_is_the_reference(case8: object, dof: int, frequency: float) -> None:
    """case8 (bridles, free junctions with mass and drag) moved 2 m in surge, 1 m in
    heave or 0.05 rad in pitch: the compiled iteration gives the reference's answer."""
    X = np.zeros((1, 6), dtype=complex)
    X[0, dof] = -1j * (0.05 if dof >= 3 else 2.0 if dof == 0 else 1.0)
    w = 2.0 * np.pi * frequency
    a = solve_system_harmonic(case8, w, X)
    b = solve_reference(case8, w, X)
    assert a.iterations > 2  # the drag iteration ran
    _same(a, b)


def test_compiled_iteration_in_a_current(case8: object) -> None:
    """With a current at every node and point (no symmetry of the drag over half a
    period: the fit takes every phase and the mean force) the compiled iteration still
    gives the reference's answer."""
    U = np.array([0.6, -0.3, 0.0])
    lines = tuple(
        replace(r, line=replace(r.line, current=np.tile(U, (r.line.n_nodes, 1))))
        for r in case8.lines
    )
    model = replace(case8, lines=lines, point_current=np.tile(U, (case8.point_kind.size, 1)))
    X = np.array([[-1j, 0.0, -0.5j, 0.0, 0.0, 0.0]])
    for frequency in (0.05, 0.2):
        w = 2.0 * np.pi * frequency
        _same(solve_system_harmonic(model, w, X), solve_reference(model, w, X))


def test_two_elements_a_line_converge_to_the_fine_mesh() -> None:
    """Two elements a line (one inner node; the 160 m leg in the y-z plane has no x-y
    or x-z stiffness at it, so its band from the entries is 1 while the node's drag
    block needs 2): solved, equal to the reference, and its end tension amplitudes
    approach the 40-element answer at second order in the element length (measured
    1.2e-3, 2.9e-4, 7.1e-5 of the largest at 2, 4, 8 elements: a ratio of 4 a
    doubling; bars: below 3e-3 at 2 and falling by more than 3 a doubling)."""
    X = np.array([[-0.1j, 0, 0, 0, 0, 0]])
    w = 2.0 * np.pi * 0.1
    fine = solve_system_harmonic(_case8_model(41), w, X)
    assert fine.status == 0, fine.message
    big = np.abs(fine.end_tension).max()
    errors = []
    for nodes in (3, 5, 9):
        model = _case8_model(nodes)
        got = solve_system_harmonic(model, w, X)
        if nodes == 3:
            _same(got, solve_reference(model, w, X))
        errors.append(np.abs(np.abs(got.end_tension) - np.abs(fine.end_tension)).max() / big)
    assert errors[0] < 3e-3, errors
    assert errors[1] < errors[0] / 3.0 and errors[2] < errors[1] / 3.0, errors


def test_envelope_on_the_output_grid_is_numpys_interpolation(case8: object) -> None:
    """The envelope of every line onto the output's arc lengths by one linear map
    (built once per model) is ``np.interp`` of each line's nodes, to rounding (the two
    round a weighted sum differently: a few units of 1e-16 of the values), and the
    envelope computed over all lines at once is the per-line one bit for bit."""
    from cablestudy.analyses.system_frequency import _envelope_grid

    rng = np.random.default_rng(7)
    values = [rng.normal(size=r.line.n_nodes) for r in case8.lines]
    for n_out in (7, 21, 50):
        ref = [
            np.interp(np.linspace(0.0, r.line.s[-1], n_out), r.line.s, v)
            for r, v in zip(case8.lines, values, strict=True)
        ]
        got = _envelope_grid(case8, n_out) @ np.concatenate(values)
        np.testing.assert_allclose(got, np.concatenate(ref), rtol=0, atol=1e-14)
    out = solve_system_harmonic(case8, 2.0 * np.pi * 0.2, np.array([[-2j, 0, 0, 0, 0.01j, 0]]))
    hi, lo = envelope(out)
    hi_ref, lo_ref = envelope(replace(out, envelope_lines=None))
    for a, b in zip(hi + lo, hi_ref + lo_ref, strict=True):
        np.testing.assert_array_equal(a, b)
