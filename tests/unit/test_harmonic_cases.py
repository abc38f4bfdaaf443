"""The batched harmonic solver (cablestudy.dynamics.harmonic_cases): a case gives the
same numbers alone (solve_harmonic) or in a batch; the converged answer is the fixed
point of the drag linearisation (checked against a dense solve with the drag fitted
to it); a line in the x-z plane gives the same answer without its y unknowns; partly
held nodes are projected right. Lines: the moustafa cable of the Figs. 2-5 sweep
(drag in still water, several frequencies through the resonance and amplitudes), the
same cable in a cross current, in vacuum (no drag: one linear solve, LAPACK's), a
chain mooring on the seabed with drag, and that chain with nodes of 1 and 2 free
directions."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from cablestudy.analyses import frequency as frequency_analysis
from cablestudy.analyses.along_line import tension_along, tension_along_cases
from cablestudy.analyses.evaluate import evaluate_case, evaluate_chunk
from cablestudy.analyses.frequency import (
    _LINEAR_CACHE,
    _problem,
    drag_settings,
    end_displacements,
    linearised,
    solve_frequency_cases,
)
from cablestudy.analyses.line_harmonic import submerged_weight
from cablestudy.analyses.static import _STATIC_CACHE, solve_static
from cablestudy.dynamics.frequency import solve_harmonic
from cablestudy.dynamics.frequency_model import ReducedLine, block_diagonal, drag_tangent
from cablestudy.dynamics.harmonic_cases import in_plane, solve_harmonic_cases
from cablestudy.dynamics.validity import measures_cases
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text
from tests.drag_fit_reference import drag_linearisation
from tests.system_drag_reference import mean_drag_jacobian

FIGS = Path(__file__).resolve().parents[2] / "configs" / "moustafa-figs2-5.yaml"

CHAIN = """
name: chain
environment: {fluid: water, depth: 100.0, seabed: {friction: 0.0}}
line:
  segments:
    - {length: 300.0, diameter: 0.1, weight_in_fluid: 500.0, axial_stiffness: 5.0e8,
       drag_normal: 1.2, drag_tangential: 0.01}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [240.0, 0.0, 0.0]}
analysis:
  static: {method: catenary, nodes: 101, tolerance: 1.0e-12}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.3], amplitude: 2.0, frequency: 0.05}
    method: frequency
    elements: 40
sweep:
  analysis.dynamic.excitation.frequency: [0.02, 0.05, 0.1]
"""


def _moustafa(fluid: str = "water", current: bool = False) -> str:
    text = FIGS.read_text().replace("method: auto", "method: frequency")
    if fluid != "water":
        text = text.replace("fluid: water", f"fluid: {fluid}")
    if current:
        text = text.replace(
            "  fluid: water\n",
            "  fluid: water\n  current: [{z: 0.0, speed: 0.3, heading_deg: 90.0}]\n",
        ).replace("method: analytic", "method: catenary")
    return text


def _cases(text: str, pick: slice | list[int]) -> list:
    _, cases = expand_cases(parse_study_text(text))
    if isinstance(pick, slice):
        return cases[pick]
    return [cases[i] for i in pick]


def _setup(cases: list) -> tuple:
    _STATIC_CACHE.clear()
    _LINEAR_CACHE.clear()
    static = solve_static(cases[0], None)
    red, why = linearised(cases[0], static, None)
    assert red is not None, why
    omegas, motion = [], []
    for case in cases:
        X, f, _ = end_displacements(case.study.analysis.dynamic)
        omegas.append(2.0 * math.pi * f)
        motion.append(X)
    settings = drag_settings(cases[0].study.analysis.dynamic)
    return static, red, np.array(omegas), np.array(motion), settings


def _close(a: np.ndarray, b: np.ndarray) -> None:
    scale = max(float(np.max(np.abs(a))), 1e-300)
    assert float(np.max(np.abs(a - b))) <= 1e-12 * scale


def _dense_solve(red: ReducedLine, omega: float, X: np.ndarray, D: np.ndarray | None) -> np.ndarray:
    """Displacements (n, 3) of the dynamic system with drag blocks ``D`` by a dense LU
    solve of the projected system (the reference of the band solves)."""
    line = red.line
    n = line.n_nodes
    B = line.free_basis.toarray()
    A = (
        line.stiffness.toarray()
        - omega**2 * line.mass_matrix().toarray()
        + 1j * omega * line.damping.toarray()
    )
    if D is not None:
        A = A + 1j * omega * block_diagonal(D).toarray()
    up = np.zeros((n, 3), dtype=complex)
    up[0], up[-1] = X[0], X[-1]
    q = np.linalg.solve(B.T @ A @ B, -B.T @ (A @ up.ravel()))
    return (B @ q).reshape(n, 3) + up


def _fit(red: ReducedLine, omega: float, u: np.ndarray, settings) -> np.ndarray | None:  # noqa: ANN001
    """The reference drag fit (drag_linearisation) to displacements ``u``, leaning as the
    kernel does (dynamics/drag_lean.py): on the mean Jacobian over the motion
    (tests/system_drag_reference.py; over the fit's phases, where the kernel has it
    exact without current: their difference, ``N^-2`` of ``J``, weighs 1e-6 in the
    fit), on the small-motion tangent where a node takes the planar closed form (its
    y row, decoupled from the plane)."""
    line = red.line
    if not line.has_drag:
        return None
    v = 1j * omega * u
    lean = mean_drag_jacobian(line, v, settings.samples)
    if settings.exact:
        planar = (v[:, 1] == 0.0) & (line.tangent[:, 1] == 0.0) & (line.current[:, 1] == 0.0)
        planar &= line.body_drag == 0.0
        lean[planar] = drag_tangent(line)[planar]
    return drag_linearisation(line, v, settings.samples, lean, settings.exact)


def _fixed_point_error(
    red: ReducedLine, omega: float, X: np.ndarray, u: np.ndarray, settings
) -> float:  # noqa: ANN001
    """Relative difference between ``u`` and the dense solve of the dynamic system
    with the drag fitted to ``u`` itself."""
    ref = _dense_solve(red, omega, X, _fit(red, omega, u, settings))
    return float(np.abs(ref - u).max() / np.abs(ref).max())


@pytest.mark.parametrize(
    ("text", "pick", "planar", "bound"),
    [
        # 0.1-1.2 Hz in 0.05 Hz steps: the resonance near 0.85-1.0 Hz takes the most
        # drag iterations; amplitudes 0.025 and 0.1 m
        (_moustafa(), [0, 5, 15, 17, 21, 69, 84, 87, 91], True, 1e-8),
        # current along y: the nodes move out of the plane of tangent and current, and
        # the fit is sampled (its regularisation lets the iteration converge: with the
        # old 1e-10 it stalled between 1e-8 and 1e-5, see FIT_REGULARISATION)
        (_moustafa(current=True), [3, 16, 40, 85], False, 1e-8),
        (_moustafa(fluid="vacuum"), [2, 16, 50], False, 1e-8),  # no drag: one solve
        (CHAIN, slice(None), True, 1e-8),
    ],
    ids=["drag", "current", "vacuum", "seabed"],
)
def test_batched_cases_are_the_fixed_point_and_each_case_alone(
    text: str, pick: slice | list[int], planar: bool, bound: float
) -> None:
    """Each case of a batch equals, bit for bit, the case solved alone. The answer is
    the fixed point of the drag linearisation: a dense LU solve with the drag fitted to
    the answer gives it again, to ``bound``: with the closed-form fit the iteration
    runs to 1e-10 and the two agree to 1e-8 (measured 1e-11 to 2e-10 at 1e-11: the iteration's
    tolerance times the conditioning near the resonance). Lines in the x-z plane are
    solved without their y unknowns (in_plane)."""
    cases = _cases(text, pick)
    _, red, omegas, motion, settings = _setup(cases)
    assert (in_plane(red) is not red) == planar
    batch = solve_harmonic_cases(red, omegas, motion, settings)
    assert batch.ok.all() and batch.converged.all()
    check = replace(settings, tolerance=1e-10) if bound < 1e-6 else settings
    fixed = solve_harmonic_cases(red, omegas, motion, check)
    assert fixed.converged.all()
    for k in range(len(cases)):
        alone = solve_harmonic(red, omegas[k], motion[k], settings)
        assert alone.success, alone.message
        assert batch.iterations[k] == alone.drag_iterations
        assert bool(batch.converged[k]) == alone.drag_converged
        for got, want in (
            (batch.displacement[k], alone.displacement),
            (batch.element_tension[k], alone.element_tension),
            (batch.end_tension[k], alone.end_tension),
        ):
            assert got.tobytes() == want.tobytes()
        np.testing.assert_array_equal(batch.tension_static, alone.tension_static)
        assert _fixed_point_error(red, omegas[k], motion[k], fixed.displacement[k], check) < bound
    if red.line.has_drag:
        assert batch.iterations.max() > 1  # the drag iteration was exercised


def test_line_in_the_x_z_plane_gives_the_same_answer_without_its_y_unknowns() -> None:
    """in_plane drops the y unknowns of a line in the x-z plane moved in it: they stay
    zero, so the smaller system's answer is the full system's (to round-off: 1e-12 of
    the largest value; the iteration takes the same steps)."""
    cases = _cases(_moustafa(), [0, 17, 21, 87, 91])
    _, red, omegas, motion, settings = _setup(cases)
    assert in_plane(red) is not red
    small = solve_harmonic_cases(red, omegas, motion, settings)
    full = solve_harmonic_cases(red, omegas, motion, settings, plane=False)
    np.testing.assert_array_equal(small.iterations, full.iterations)
    for a, b in (
        (small.displacement, full.displacement),
        (small.end_tension, full.end_tension),
        (small.element_tension, full.element_tension),
    ):
        _close(b, a)
    assert not np.any(full.displacement[:, :, 1])


def test_partly_held_nodes_reduced_bands_and_batched_solve() -> None:
    """With nodes of 0, 1, 2 and 3 free directions (some held along a random plane or
    line, as a line model may hold nodes), the band storage of ReducedLine holds
    B^T K B and B^T M B exactly and B^T D B for drag blocks D, and a drag iteration of
    the batched solve is the dense solve with the same drag (to 1e-10: round-off times
    the conditioning), and the converged solve is the fixed point (as above). Its nodes
    move out of the x-z plane, so the fit is sampled; this line's iteration did not
    converge in 1000 steps before FIT_REGULARISATION was raised to 1e-6."""
    cases = _cases(CHAIN, slice(None))
    _, red0, omegas, motion, settings = _setup(cases)
    line0 = red0.line
    rng = np.random.default_rng(5)
    blocks = []
    for i in range(line0.n_nodes):
        k = 0 if i in (0, line0.n_nodes - 1) else (3, 2, 1, 3)[i % 4]
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        blocks.append(q[:, :k] if k < 3 else np.eye(3))
    basis = sp.block_diag([sp.csr_matrix(b) if b.size else sp.csr_matrix((3, 0)) for b in blocks])
    red = ReducedLine.of(replace(line0, free_basis=basis.tocsr()))
    assert set(np.diff(red.offsets).tolist()) == {0, 1, 2, 3}
    B = basis.toarray()
    bw = red.bandwidth

    def dense(band: np.ndarray) -> np.ndarray:
        N = band.shape[1]
        out = np.zeros((N, N), dtype=band.dtype)
        for i in range(N):
            for j in range(max(0, i - bw), min(N, i + bw + 1)):
                out[i, j] = band[bw + i - j, j]
        return out

    # the reduced matrices are sparse products of the same numbers: equal to round-off
    scale = np.abs(line0.stiffness).max()
    np.testing.assert_allclose(
        dense(red.K), B.T @ line0.stiffness.toarray() @ B, atol=1e-14 * scale
    )
    mass = line0.mass_matrix().toarray()
    np.testing.assert_allclose(dense(red.M), B.T @ mass @ B, atol=1e-14 * np.abs(mass).max())
    D = rng.normal(size=(line0.n_nodes, 3, 3))
    expect = B.T @ block_diagonal(D).toarray() @ B
    np.testing.assert_allclose(dense(red.drag_band(D)), expect, atol=1e-14 * np.abs(D).max())
    # one drag iteration: the solve with the drag fitted to the quasi-static start (the
    # end motion spread linearly along s), against the dense solve with that drag
    one = solve_harmonic_cases(red, omegas, motion, replace(settings, max_iterations=1))
    frac = (line0.s / line0.s[-1])[:, None]
    for k in range(omegas.size):
        start = (1.0 - frac) * motion[k, 0] + frac * motion[k, 1]
        ref = _dense_solve(red, omegas[k], motion[k], _fit(red, omegas[k], start, settings))
        assert np.abs(one.displacement[k] - ref).max() <= 1e-10 * np.abs(ref).max()
    # and the converged answer is the fixed point: this line's iteration stalls near
    # 1e-9 (measured 2e-9 to 9e-9), so it runs to 1e-8, and the dense solve with the
    # drag fitted to the answer gives it again to 1e-6 (1e-8 times the conditioning)
    tight = replace(settings, tolerance=1e-8)
    batch = solve_harmonic_cases(red, omegas, motion, tight)
    assert batch.converged.all()
    for k in range(omegas.size):
        assert _fixed_point_error(red, omegas[k], motion[k], batch.displacement[k], tight) < 1e-6


@pytest.mark.parametrize("text", [_moustafa(), CHAIN], ids=["span", "seabed"])
def test_validity_measures_as_arrays_match_the_per_case_function(text: str) -> None:
    cases = _cases(text, slice(0, None, 7))
    static, red, omegas, motion, settings = _setup(cases)
    line = red.line
    res = solve_harmonic_cases(red, omegas, motion, settings)
    med = _problem(cases[0]).medium
    ground = med.seabed_z(line.position[:, 0], line.position[:, 1])
    on_bed = np.abs(line.position[:, 2] - ground) <= 1e-6 * float(line.s[-1])
    held = np.diff(line.free_basis.tocsr().indptr).reshape(-1, 3).sum(axis=1) == 0
    common = dict(
        s=line.s,
        position=line.position,
        element_tension_static=line.tension,
        end_tension_static=res.tension_static,
        laid_length=static.laid_length,
        on_seabed=on_bed,
        submerged_weight=submerged_weight(_problem(cases[0]).line, line.s),
        held=held,
    )
    ratio, sag_ratio, travel = measures_cases(
        displacement=res.displacement,
        element_tension_amplitude=np.abs(res.element_tension),
        end_tension_amplitude=np.abs(res.end_tension),
        **common,
    )
    for k in range(len(cases)):  # each response alone (K = 1)
        alone = measures_cases(
            displacement=res.displacement[k][None],
            element_tension_amplitude=np.abs(res.element_tension[k])[None],
            end_tension_amplitude=np.abs(res.end_tension[k])[None],
            **common,
        )
        assert (ratio[k], sag_ratio[k], travel[k]) == tuple(v[0] for v in alone)
    if "depth" in text:
        assert static.laid_length > 0.0 and np.all(travel > 0.0)  # touchdown exercised


def test_auto_sweep_in_a_chunk_gives_each_case_its_record_alone() -> None:
    """``method: auto`` takes the batched frequency-domain answers of a chunk and falls
    back to the time domain case by case as before: on cases of the Figs. 2-5 sweep
    kept in the frequency domain (0.1, 0.35 Hz at 0.025 m) and one it refuses (0.7 Hz:
    amplitude/sag 0.0754 > 0.075), every record equals the one the case gets alone."""
    text = FIGS.read_text()
    picked = _cases(text, [0, 5, 12])
    chunk = evaluate_chunk(picked)
    methods = [str(r.data["dynamic_method"]) for r in chunk]
    assert methods == ["frequency", "frequency", "time"], methods
    for case, rec in zip(picked, chunk, strict=True):
        _STATIC_CACHE.clear()
        _LINEAR_CACHE.clear()
        alone = evaluate_case(case)
        assert (rec.status, rec.message) == (alone.status, alone.message)
        assert set(rec.data) == set(alone.data)
        for name, value in alone.data.items():
            assert np.asarray(rec.data[name]).tobytes() == np.asarray(value).tobytes(), name


def test_cases_beyond_one_call_are_solved_in_slices_with_the_same_outcomes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A chunk larger than BATCH_NODES case-nodes is solved in slices; each case's
    outcome is the one it gets in a single call."""
    cases = _cases(_moustafa(), slice(0, 7))
    static, red, *_ = _setup(cases)
    whole = solve_frequency_cases(cases, static, red)
    monkeypatch.setattr(frequency_analysis, "BATCH_NODES", 3 * red.line.n_nodes)  # 3 per slice
    sliced = solve_frequency_cases(cases, static, red)
    for a, b in zip(whole, sliced, strict=True):
        assert (a.status, a.distrust, a.summary) == (b.status, b.distrust, b.summary)
        for name, value in a.data.items():
            assert np.asarray(b.data[name]).tobytes() == np.asarray(value).tobytes(), name


def test_tension_along_cases_gives_np_interp_numbers() -> None:
    """The envelope of K responses at once equals tension_along (np.interp) row by row,
    bit for bit, at output points between, on and beyond the element midpoints."""
    rng = np.random.default_rng(11)
    s_nodes = np.cumsum(np.r_[0.0, rng.uniform(0.5, 1.5, 20)])
    mid = 0.5 * (s_nodes[:-1] + s_nodes[1:])
    s_out = np.sort(np.r_[np.linspace(-0.5, s_nodes[-1] + 0.5, 57), mid[::3], s_nodes[[0, -1]]])
    element = rng.uniform(0.0, 100.0, (6, s_nodes.size - 1))
    ends = rng.uniform(0.0, 100.0, (6, 2))
    got = tension_along_cases(s_out, s_nodes, element, ends)
    for k in range(6):
        want = tension_along(s_out, s_nodes, element[k], ends[k])
        assert got[k].tobytes() == want.tobytes()
