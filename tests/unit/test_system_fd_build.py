"""The system frequency domain's model built cheaply (issue 24: ``method: auto`` built
it at 3x the cost of a time-domain case) is the model built the plain way, bit for bit:

- the lines re-solved at the model's nodes in one call per group of the compiled
  kernels (:func:`cablestudy.statics.batch.solve_compiled_many`, through the
  analysis' ``_catenary_many``) against the catenary solver's ``solve`` line by line:
  both run the same kernels case by case and verify each answer the same way, so the
  states, and the model built on them, are equal, not just close;
- the end couplings picked entry by entry from the lines' matrices against the sparse
  products with the free basis: each entry is one product by 1 in both.

On MoorPy's case8 (bridles on free junctions, legs anchored on the seabed: the contact
kernel, lifting off to the free-hanging one) and MoorDyn's lines.txt (chains laid on
the seabed: the contact kernel proper), at 3, 4 and 11 nodes a line.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cablestudy.analyses.system import system_model
from cablestudy.analyses.system_frequency import _catenary_many
from cablestudy.dynamics.frequency_model import ReducedLine
from cablestudy.dynamics.system_frequency import (
    EndCoupling,
    SystemLinear,
    _coordinate_coupling,
    _sparse_coupling,
    system_linear,
)
from cablestudy.interchange import import_model, imported_yaml
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system_methods import solve_system_by
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

ROOT = Path(__file__).parents[2]
SOLVER = STATIC_SOLVERS["catenary"]


def _system(which: str):  # noqa: ANN202
    if which.startswith("case8"):
        text = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
        _, cases = expand_cases(parse_study_text(text, "case8.yaml"))
    else:
        rel = "moordyn/tests/Mooring/lines.txt"
        path = ROOT / "tests" / "data" / rel
        imported = import_model(path.read_text(), rel, folder=path.parent)
        _, cases = expand_cases(parse_study_text(imported_yaml(imported, rel), "<imported>"))
    system = system_model(cases[0].study)
    if which == "case8-bending":  # bending in the lines' model (the catenary carries none)
        system = replace(
            system,
            lines=tuple(
                replace(
                    sl,
                    problem=replace(
                        sl.problem,
                        line=replace(
                            sl.problem.line,
                            bending_stiffness=np.full_like(sl.problem.line.bending_stiffness, 2e4),
                        ),
                    ),
                )
                for sl in system.lines
            ),
        )
    res = solve_system_by(system, "catenary", STATIC_SOLVERS)
    assert res.status == 0, res.message
    return system, res


@pytest.fixture(scope="module", params=["case8", "lines.txt"])
def solved(request: pytest.FixtureRequest):  # noqa: ANN201
    return _system(request.param)


@pytest.mark.parametrize("nodes", [3, 4, 11])
def test_batched_re_solve_is_the_solver_line_by_line(solved, nodes: int) -> None:  # noqa: ANN001
    system, res = solved
    one, why = system_linear(system, res, nodes=nodes, solve=SOLVER.solve)
    assert one is not None, why
    many, why = system_linear(system, res, nodes=nodes, solve_many=_catenary_many)
    assert many is not None, why
    for a, b in zip(one.lines, many.lines, strict=True):
        for name in ("s", "position", "tension", "end_force", "axial_stiffness", "mass"):
            np.testing.assert_array_equal(getattr(a.line, name), getattr(b.line, name))
        for name in ("K", "M", "C"):
            np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    for x, y in zip(one.packed.arrays, many.packed.arrays, strict=True):
        np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("nodes", [3, 11])
def test_end_couplings_picked_are_the_sparse_products(solved, nodes: int) -> None:  # noqa: ANN001
    system, res = solved
    model, why = system_linear(system, res, nodes=nodes, solve_many=_catenary_many)
    assert model is not None, why
    for red in model.lines:
        fast = _coordinate_coupling(red.line)
        assert fast is not None  # held ends: a coordinate basis
        for got, ref in zip(fast, _sparse_coupling(red.line), strict=True):
            for g, r in zip(got, ref, strict=True):
                np.testing.assert_array_equal(g, r)


def _bits(a, b) -> None:  # noqa: ANN001
    """``a`` and ``b`` the same array byte for byte (shape, type, every bit)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape and a.dtype == b.dtype
    assert np.ascontiguousarray(a).tobytes() == np.ascontiguousarray(b).tobytes()


def _plain(model: SystemLinear) -> SystemLinear:
    """``model`` with its reduced lines and couplings built line by line, the plain way."""
    return SystemLinear(
        names=model.names,
        lines=tuple(ReducedLine.of(r.line) for r in model.lines),
        ends=model.ends,
        point_kind=model.point_kind,
        point_body=model.point_body,
        point_arm=model.point_arm,
        point_mass=model.point_mass,
        point_drag=model.point_drag,
        point_current=model.point_current,
        n_bodies=model.n_bodies,
    )


@pytest.mark.parametrize("which", ["case8", "case8-bending", "lines.txt"])
@pytest.mark.parametrize("nodes", [2, 4, 11])
def test_lines_reduced_in_one_pass_are_the_plain_ones(which: str, nodes: int) -> None:
    system, res = _CACHE.get(which) or _CACHE.setdefault(which, _system(which))
    fast, why = system_linear(system, res, nodes=nodes, solve_many=_catenary_many)
    assert fast is not None, why
    assert "couplings" in fast.__dict__  # built with the lines
    if which == "case8-bending" and nodes > 4:  # inner blocks two nodes off the diagonal
        assert max(r.bandwidth for r in fast.lines) > 5
    plain = _plain(fast)
    for a, b in zip(fast.lines, plain.lines, strict=True):
        assert a.bandwidth == b.bandwidth
        for name in ("K", "M", "C", "node_basis", "offsets"):
            _bits(getattr(a, name), getattr(b, name))
        for x, y in zip(a.band_index + a.block_index, b.band_index + b.block_index, strict=True):
            _bits(x, y)
    for a, r in zip(fast.couplings, plain.lines, strict=True):
        b = EndCoupling.of(r)
        for got, ref in zip((a.K, a.M, a.C), (b.K, b.M, b.C), strict=True):
            for g, f in zip(got, ref, strict=True):
                _bits(g, f)
    assert fast.packed.bw == plain.packed.bw
    for x, y in zip(fast.packed.arrays, plain.packed.arrays, strict=True):
        _bits(x, y)


_CACHE: dict = {}


@pytest.mark.parametrize("which", ["case8", "case8-bending", "lines.txt"])
@pytest.mark.parametrize("nodes", [2, 4, 11])
def test_linear_lines_are_linear_line_of_each(which: str, nodes: int) -> None:
    """linear_lines (alike lines sharing their discretisation, each line's strains found
    once) gives linear_line's lines byte for byte: every array, the sparse matrices'
    stored entries and structure; case8's bridles and legs share (two kinds of nine)."""
    from cablestudy.dynamics.linear_model import linear_line, linear_lines
    from cablestudy.dynamics.modal import ModalProblem
    from cablestudy.statics.base import EndCondition

    system, res = _CACHE.get(which) or _CACHE.setdefault(which, _system(which))
    states = _catenary_many(
        [
            replace(
                sl.problem,
                end_a=EndCondition(kind="fixed", position=res.point_position[sl.a]),
                end_b=EndCondition(kind="fixed", position=res.point_position[sl.b]),
                n_nodes=nodes,
            )
            for sl in system.lines
        ]
    )
    held = EndCondition(kind="fixed")
    problems = [
        ModalProblem(
            line=sl.problem.line, medium=sl.problem.medium, end_a=held, end_b=held, static=st
        )
        for sl, st in zip(system.lines, states, strict=True)
    ]
    for got, ref in zip(linear_lines(problems), [linear_line(p) for p in problems], strict=True):
        for f in ("s", "position", "mass", "rest_length", "direction", "axial_stiffness"):
            _bits(getattr(got, f), getattr(ref, f))
        for f in ("axial_damping", "tension", "end_force", "drag_normal", "drag_tangential"):
            _bits(getattr(got, f), getattr(ref, f))
        for f in ("current", "tangent"):
            _bits(getattr(got, f), getattr(ref, f))
        assert (got.drag_body is None) == (ref.drag_body is None)
        for f in ("stiffness", "damping", "free_basis"):
            a, b = getattr(got, f), getattr(ref, f)
            assert a.shape == b.shape and a.format == b.format == "csr"
            for part in ("data", "indices", "indptr"):
                _bits(getattr(a, part), getattr(b, part))


def _rows_by_diagonal(ab: np.ndarray, bw_line: int, bw: int) -> np.ndarray:
    """Band storage to row storage diagonal by diagonal (the packing's former loop)."""
    k = ab.shape[1]
    out = np.zeros((k, 2 * bw + 1))
    for d in range(-bw_line, bw_line + 1):  # A[i, i + d] = ab[bw_line - d, i + d]
        lo, hi = max(0, -d), min(k, k - d)
        if hi > lo:
            out[lo:hi, bw + d] = ab[bw_line - d, lo + d : hi + d]
    return out


@pytest.mark.parametrize(
    ("k", "bw_line", "bw"), [(0, 0, 2), (1, 0, 0), (3, 2, 5), (6, 5, 5), (12, 5, 8), (4, 8, 8)]
)
def test_band_rows_by_one_gather_are_the_diagonal_copies(k: int, bw_line: int, bw: int) -> None:
    """The packing's band-to-row conversion (one gather) copies each entry where the
    diagonal loop put it, zeros elsewhere, byte for byte (signed zeros and all)."""
    from cablestudy.dynamics.system_fd_pack import _rows

    ab = np.random.default_rng(k + 10 * bw_line).normal(size=(2 * bw_line + 1, k))
    ab[ab > 1.0] = -0.0
    _bits(_rows(ab, bw_line, bw), _rows_by_diagonal(ab, bw_line, bw))


@pytest.mark.parametrize("which", ["case8", "lines.txt"])
def test_packed_end_coupled_dofs_are_each_lines(which: str) -> None:
    """The dofs coupled to the end nodes, found over all lines at once, are each line's
    non-zero rows of A_IE and columns of A_EI, in order, with the lines' offsets."""
    system, res = _CACHE.get(which) or _CACHE.setdefault(which, _system(which))
    model, why = system_linear(system, res, nodes=6, solve_many=_catenary_many)
    assert model is not None, why
    couple = []
    for c in model.couplings:
        nz = np.zeros(c.K[0].shape[0], dtype=bool)
        for Q in (c.K, c.M, c.C):
            nz |= np.any(Q[0] != 0.0, axis=1) | np.any(Q[1] != 0.0, axis=0)
        couple.append(np.flatnonzero(nz))
    arrays = model.packed.arrays
    coff = np.concatenate(([0], np.cumsum([c.size for c in couple]))).astype(np.int64)
    # (noff, koff, K, M, C, IE x 3, EI x 3, EE x 3, couple, coff, ...): pack_system's order
    _bits(arrays[14], np.concatenate(couple).astype(np.int64))
    _bits(arrays[15], coff)


def test_one_pass_reduction_refuses_other_bases() -> None:
    """held_lines is exact for the held ends' basis only: a line with another basis
    (every other column dropped) sends the build to the plain
    construction (None), however the others are held."""
    from cablestudy.dynamics.system_fd_build import held_lines

    system, res = _CACHE.get("case8") or _CACHE.setdefault("case8", _system("case8"))
    model, why = system_linear(system, res, nodes=5, solve_many=_catenary_many)
    assert model is not None, why
    lines = [r.line for r in model.lines]
    assert held_lines(lines) is not None
    other = replace(lines[0], free_basis=lines[0].free_basis[:, ::2].tocsr())
    assert held_lines([other, *lines[1:]]) is None
