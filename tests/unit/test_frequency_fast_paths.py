"""The short cuts of the frequency-domain set-up give the arrays of the general code
bit for bit (a sweep's records must not change with them): the projection on a
coordinate free basis (entries picked) against scipy's products, the x-z system built
from the stored entries against scipy's column slicing, the block CSR matrices and
the held-ends basis against scipy's coordinate conversion, the component sums against
np.sum, and the non-finite check of a batch against the per-case one."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from cablestudy.analyses.common import _LAST_CHECKED, non_finite_cases, non_finite_outputs
from cablestudy.analyses.frequency import _LINEAR_CACHE, linearised
from cablestudy.analyses.static import _STATIC_CACHE, solve_static
from cablestudy.analyses.variables import OUTPUTS
from cablestudy.dynamics.frequency_model import ReducedLine, selected_rows, sum_components
from cablestudy.dynamics.harmonic_cases import _transposed, in_plane
from cablestudy.dynamics.linear_model import held_ends_basis
from cablestudy.dynamics.modal import _block_matrix, _free_basis
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

FIGS = Path(__file__).resolve().parents[2] / "configs" / "moustafa-figs2-5.yaml"


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def _same_csr(a: sp.spmatrix, b: sp.spmatrix) -> bool:
    return (
        a.shape == b.shape
        and _same(a.indptr, b.indptr)
        and _same(a.indices, b.indices)
        and _same(a.data, b.data)
    )


def _coordinate_block_matrix(
    n: int, diag: np.ndarray, off1: np.ndarray, off2: np.ndarray
) -> sp.csr_matrix:
    """The blocks given to scipy as coordinates (the construction _block_matrix
    replaces)."""
    ii, jj = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")
    rows, cols, vals = [], [], []

    def add(node_i: np.ndarray, node_j: np.ndarray, blocks: np.ndarray) -> None:
        rows.append((3 * node_i[:, None, None] + ii).ravel())
        cols.append((3 * node_j[:, None, None] + jj).ravel())
        vals.append(blocks.ravel())

    add(np.arange(n), np.arange(n), diag)
    for k, blocks in ((1, off1), (2, off2)):
        m = blocks.shape[0]
        if m:
            a = np.arange(m)
            add(a, a + k, blocks)
            add(a + k, a, np.transpose(blocks, (0, 2, 1)))
    return sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * n, 3 * n)
    )


@pytest.mark.parametrize("n", [1, 2, 3, 4, 81])
@pytest.mark.parametrize("bending", [False, True])
def test_block_matrix_is_scipys_coordinate_conversion(n: int, bending: bool) -> None:
    rng = np.random.default_rng(n)
    diag = rng.normal(size=(n, 3, 3))
    diag[0, 1, 1], diag[-1, 0, 2] = 0.0, -0.0  # stored zeros stay, with their sign
    off1 = rng.normal(size=(max(n - 1, 0), 3, 3))
    off2 = rng.normal(size=(max(n - 2, 0), 3, 3)) if bending else np.zeros((0, 3, 3))
    fast = _block_matrix(n, diag, off1, off2)
    assert _same_csr(fast, _coordinate_block_matrix(n, diag, off1, off2))
    assert fast.has_canonical_format


@pytest.mark.parametrize("n", [1, 2, 3, 81])
def test_held_ends_basis_is_the_node_bases_of_fixed_ends(n: int) -> None:
    held = _free_basis(np.eye(3))
    bases = [held] + [_free_basis(np.zeros((3, 0)))] * max(n - 2, 0) + ([held] if n > 1 else [])
    dims = np.array([b.shape[1] for b in bases])
    offsets = np.concatenate(([0], np.cumsum(dims)))
    sizes = 3 * dims
    node = np.repeat(np.arange(n), sizes)
    local = np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    k_of = np.maximum(dims[node], 1)
    general = sp.csr_matrix(
        (
            np.concatenate([b.ravel() for b in bases]),
            (3 * node + local // k_of, offsets[node] + local % k_of),
        ),
        shape=(3 * n, int(offsets[-1])),
    )
    assert _same_csr(held_ends_basis(n), general)


def test_sum_components_is_np_sum_bit_for_bit() -> None:
    """Every combination of signed zeros, infinities, NaN and numbers that cancel, real
    and complex, in the (cases, nodes, 3) layout of a sweep."""
    vals = [0.0, -0.0, 1.0, -1.0, 1e16, -1e16, math.inf, -math.inf, math.nan]
    real = np.array(list(itertools.product(vals, repeat=3)))
    parts = np.array([complex(x, y) for x, y in itertools.product(vals, repeat=2)])
    z = parts[np.array(list(itertools.product(range(parts.size), repeat=3)))]
    z = z[: 81 * (z.shape[0] // 81)].reshape(81, -1, 3)
    with np.errstate(invalid="ignore"):  # inf - inf
        assert _same(sum_components(real), np.sum(real, axis=-1))
        assert _same(sum_components(z), np.sum(z, axis=-1))


def _lines() -> list:
    """Linearised lines of the Figs. 2-5 cable: in still water (its x-z system is
    used), and with end motion and a current out of the plane."""
    text = FIGS.read_text().replace("method: auto", "method: frequency")
    current = text.replace(
        "  fluid: water\n", "  fluid: water\n  current: [{z: 0.0, speed: 0.3, heading_deg: 30.0}]\n"
    ).replace("method: analytic", "method: catenary")
    out = []
    for t in (text, current):
        _, cases = expand_cases(parse_study_text(t))
        _STATIC_CACHE.clear()
        _LINEAR_CACHE.clear()
        static = solve_static(cases[0], None)
        red, why = linearised(cases[0], static, None)
        assert red is not None, why
        out.append(red)
    return out


def _general(line) -> ReducedLine:  # noqa: ANN001
    """ReducedLine.of by scipy's products (a free basis of CSC format is not taken by
    the coordinate short cut)."""
    red = ReducedLine.of(replace(line, free_basis=sp.csc_matrix(line.free_basis)))
    return replace(red, line=line)


def _same_reduced(a: ReducedLine, b: ReducedLine) -> bool:
    return (
        a.bandwidth == b.bandwidth
        and all(_same(getattr(a, k), getattr(b, k)) for k in ("K", "M", "C", "node_basis"))
        and all(_same(x, y) for x, y in zip(a.band_index, b.band_index, strict=True))
        and all(_same(x, y) for x, y in zip(a.block_index, b.block_index, strict=True))
        and _same(a.offsets, b.offsets)
    )


def test_coordinate_basis_projection_and_x_z_system_are_scipys() -> None:
    planar, across = _lines()
    for red in (planar, across):
        assert selected_rows(red.line.free_basis) is not None  # the short cut applies
        assert _same_reduced(red, _general(red.line))
    # the x-z system: its basis is scipy's column slicing, its bands scipy's products
    plane = in_plane(planar)
    assert plane is not planar
    B = sp.csc_matrix(planar.line.free_basis)
    y = np.asarray(abs(B[1::3]).sum(axis=0)).ravel() > 0.0
    assert _same_csr(plane.line.free_basis, B[:, ~y].tocsr())
    assert _same_reduced(plane, _general(plane.line))
    assert in_plane(across) is across  # the current couples y
    # the transposed basis of the kernel is scipy's
    ptr, idx, val = _transposed(plane.line.free_basis)
    BT = plane.line.free_basis.T.tocsr()
    assert np.array_equal(ptr, BT.indptr) and np.array_equal(idx, BT.indices)
    assert _same(val, BT.data)


def test_non_finite_of_a_batch_is_that_of_each_case() -> None:
    """non_finite_cases names, per case, what non_finite_outputs finds in its outputs (NaN
    where the registry gives it a meaning is not counted)."""
    rng = np.random.default_rng(3)
    K = 6
    columns = {
        "tension_max": rng.normal(size=K),
        "tension_envelope_max": rng.normal(size=(K, 5)),
        "touchdown_min": rng.normal(size=K),  # NaN means no contact
        "linearisation_iterations": np.arange(K),
        "tension": rng.normal(size=(K, 5)),  # a static output: not checked here
    }
    columns["tension_max"][1] = math.inf
    columns["tension_envelope_max"][2, 3] = math.nan
    columns["tension_envelope_max"][1, 0] = -math.inf
    columns["touchdown_min"][[3, 4]] = [math.nan, math.inf]
    columns["tension"][5, 0] = math.nan
    names = [k for k in columns if k in OUTPUTS]
    assert "touchdown_min" in names and OUTPUTS["touchdown_min"].nan_means
    batch = non_finite_cases({k: columns[k] for k in names}, "dynamic")
    for k in range(K):
        _LAST_CHECKED.clear()
        alone = non_finite_outputs({n: columns[n][k, ...] for n in names}, "dynamic")
        assert batch[k] == alone
    assert batch[1] == ["tension_envelope_max", "tension_max"]
    assert batch[4] == ["touchdown_min"] and batch[3] == [] and batch[5] == []
