"""The static analysis of a chunk of a case grid (:class:`cablestudy.study.grid.CaseGrid`)
as arrays: a case is its index into the grid of sweep axes.

For a grid whose cases differ only in settings the batched still-water catenary kernel
takes as numbers (end positions of fixed ends, segment axial stiffnesses, a towing or
mooring end's load; the line's loads, lengths and attachments and the seabed, built once
per combination of their values by :mod:`cablestudy.study.grid_lines`, each line cut
into its own pieces by :mod:`cablestudy.analyses.static_grid_lines`;
:attr:`CaseGrid.arrays`), no per-case pydantic
object is built: a chunk of cases becomes arrays of end positions, stiffnesses and
loads, is solved by the compiled kernels (lines hanging free, and lines anchored on
the seabed with friction), the cases they do not settle by
:func:`cablestudy.statics.batch.solve_batch` (the reason per case in
:attr:`GridChunk.fallback_reason`, counted in the dataset's ``cases_fallback``), and
its outputs are stacked into one array per output variable (a :class:`GridChunk`), which
the runner streams to disk. A chunk in a current (the template's, or a swept speed or
heading) is solved by :func:`cablestudy.statics.batch.solve_batch`, where the drag
iteration runs per case inside a compiled batch. Any other static grid's chunk is solved
as validated cases are (:mod:`cablestudy.analyses.static_grid_cases`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..study.grid import _END_LOAD, _POSITION, _STIFFNESS, CaseGrid
from ..study.grid_lines import line_axes
from ..study.study import Study
from .common import segment_of
from .fallback import NO_KERNEL
from .grid_chunk import STATUS_NUMERICAL, GridChunk, array_chunk, numerical_fault
from .plausibility import fallback_warning, largest_strain, strain_warning
from .static_grid_limits import apply_grid_limits
from .static_grid_lines import SweptLines, geometry_groups, layout_arrays, node_segments
from .surface import template_surface_warnings
from .variables import KEPT_STATUSES


def _swept_inputs(grid: CaseGrid, lo: int, hi: int) -> tuple[Any, dict[str, Any], np.ndarray]:
    """The template's static problem, per end the positions of rows ``lo:hi`` ((n, 3),
    None for an end that is not fixed) and the segment stiffnesses ((n, n_segments)).
    Where the sweep changes the line's loads, ``pos['lines']`` holds the lines
    (:class:`SweptLines`)."""
    from ..study.problem import static_problem

    base = static_problem(grid.template)
    n = (hi - lo) * math.prod(grid.shape[1:])
    pos: dict[str, Any] = {}
    for end in "ab":
        cond = getattr(base, f"end_{end}")
        pos[end] = (
            np.tile(np.asarray(cond.position, dtype=float), (n, 1))
            if cond.kind == "fixed"
            else None
        )
    ea = np.tile(base.line.axial_stiffness, (n, 1))
    if line_axes(grid):
        pos["lines"] = SweptLines.of(grid, lo, hi)
        # each case's own line's stiffnesses (a catalogue size sets them), a swept
        # stiffness put in below
        ea = pos["lines"].stacked(lambda m: m.axial_stiffness).astype(float)
    for path in grid.swept:
        m = _POSITION.match(path)
        load = _END_LOAD.match(path)
        if m:
            pos[m.group(1)][:, int(m.group(2))] = grid.values(path, lo, hi)
        elif load:  # a towing or mooring end's known load: per case, as its end condition
            _put_end_load(pos, base, load, grid.values(path, lo, hi))
        elif _STIFFNESS.match(path):
            k = int(_STIFFNESS.match(path).group(1))  # type: ignore[union-attr]
            ea[:, k] = grid.values(path, lo, hi)
        # else a number of the line (grid_lines.per_line): its own line per case, above
    return base, pos, ea


def _put_end_load(pos: dict[str, Any], base: Any, m: Any, values: np.ndarray) -> None:
    """Put the swept values of an end's known load (``m``: the match of
    :data:`cablestudy.study.grid._END_LOAD`) into ``pos['<end>_force']`` (n, 3) or
    ``pos['<end>_z']`` (n,), each starting from the template's end condition."""
    end = m.group(1)
    cond = getattr(base, f"end_{end}")
    if m.group(3) is None:
        pos[f"{end}_z"] = np.asarray(values, dtype=float).copy()
        return
    key = f"{end}_force"
    if key not in pos:
        pos[key] = np.tile(np.asarray(cond.force, dtype=float), (len(values), 1))
    pos[key][:, int(m.group(3))] = values


def _problems(base: Any, pos: dict[str, Any], ea: np.ndarray) -> list[Any]:
    """One static problem per case: the template's with the swept numbers put in
    (shallow copies of the frozen dataclasses; every array shared but the swept ones)."""
    ea_swept = not np.all(ea == base.line.axial_stiffness)
    lines = pos.get("lines")
    problems = []
    for i in range(len(ea)):
        changes: dict[str, Any] = {}
        for end in "ab":
            if pos[end] is not None:
                changes[f"end_{end}"] = _with(getattr(base, f"end_{end}"), position=pos[end][i])
            loads = {}
            if f"{end}_force" in pos:
                loads["force"] = pos[f"{end}_force"][i]
            if f"{end}_z" in pos:  # a float, as the study's (messages print its repr)
                loads["z"] = float(pos[f"{end}_z"][i])
            if loads:  # a towing or mooring end's swept load
                changes[f"end_{end}"] = _with(getattr(base, f"end_{end}"), **loads)
        line = base.line if lines is None else lines.models[lines.which[i]]
        if ea_swept:
            changes["line"] = _with(line, axial_stiffness=ea[i])
        elif lines is not None:
            changes["line"] = line
        if lines is not None:
            changes["medium"] = lines.media[lines.which[i]]
        problems.append(_with(base, **changes))
    return problems


def _in_current(base: Any, pos: dict[str, Any]) -> bool:
    """Whether some case of a chunk is in a current (the template's, or its own with a
    swept current: :class:`SweptLines`)."""
    lines = pos.get("lines")
    return any(m.has_current for m in ([base.medium] if lines is None else lines.media))


def _general_reasons(template: Study, problems: list[Any], general: list[int]) -> list[str]:
    """Why the general solver took each case of ``general`` no kernel tried, as the case
    alone says (:func:`cablestudy.analyses.fallback.fallback_reason`: a current with drag
    the compiled drag iteration does not take, else :data:`NO_KERNEL`)."""
    from .fallback import fallback_reason

    return [fallback_reason(template, problems[i]) for i in general]


def _with(obj: Any, **changes: Any) -> Any:
    """A shallow copy of the (frozen) dataclass ``obj`` with ``changes``: what
    :func:`dataclasses.replace` gives for these plain-data classes, without running
    ``__init__`` (a few hundred ns instead of ~10 us, which counts at a million cases)."""
    new = object.__new__(type(obj))
    new.__dict__.update(obj.__dict__)
    new.__dict__.update(changes)
    return new


@dataclass
class StaticArrays:
    """Static results of a chunk's cases stacked along a leading case axis: what a list of
    :class:`cablestudy.statics.base.StaticResult` holds, as arrays."""

    s: np.ndarray  # (n, m) [m]
    position: np.ndarray  # (n, m, 3) [m]
    tension: np.ndarray  # (n, m) [N]
    force_a: np.ndarray  # (n, 3) [N]
    force_b: np.ndarray  # (n, 3) [N]
    status: np.ndarray  # (n,) int64
    messages: list[str]
    laid_length: np.ndarray  # (n,) [m]
    iterations: np.ndarray  # (n,) float
    residual: np.ndarray  # (n,)
    drag_iterations: np.ndarray  # (n,) float

    @classmethod
    def of(cls, results: list[Any]) -> StaticArrays:
        """Stack static results (a status-0 result with non-finite values becomes the
        failure :meth:`StaticResult.check_finite` gives, as case by case)."""
        results = list(results)
        position = np.stack([r.position for r in results])  # (n, m, 3)
        tension = np.stack([r.tension for r in results])
        force_a = np.stack([r.force_a for r in results])
        force_b = np.stack([r.force_b for r in results])
        core_finite = (
            np.isfinite(position).all(axis=(1, 2))
            & np.isfinite(tension).all(axis=1)
            & np.isfinite(force_a).all(axis=1)
            & np.isfinite(force_b).all(axis=1)
        )
        for i in np.flatnonzero(~core_finite):  # StaticResult.check_finite, where it matters
            results[i] = results[i].check_finite()
        return cls(
            s=np.stack([r.s for r in results]),
            position=position,
            tension=tension,
            force_a=force_a,
            force_b=force_b,
            status=np.array([r.status for r in results], dtype=np.int64),
            messages=[r.message for r in results],
            laid_length=np.array([r.laid_length for r in results], dtype=float),
            iterations=np.array([r.iterations for r in results], dtype=float),
            residual=np.array([r.residual for r in results], dtype=float),
            drag_iterations=np.array([r.drag_iterations for r in results], dtype=float),
        )

    #: the fields that are arrays with a leading case axis
    ARRAYS = (
        "s",
        "position",
        "tension",
        "force_a",
        "force_b",
        "status",
        "laid_length",
        "iterations",
        "residual",
        "drag_iterations",
    )

    def take(self, rows: np.ndarray) -> StaticArrays:
        """The cases ``rows`` (in order)."""
        return StaticArrays(
            **{name: getattr(self, name)[rows] for name in self.ARRAYS},
            messages=[self.messages[i] for i in rows.tolist()],
        )

    def put(self, rows: np.ndarray, other: StaticArrays) -> None:
        """Overwrite cases ``rows`` with the cases of ``other`` (in order)."""
        for name in self.ARRAYS:
            getattr(self, name)[rows] = getattr(other, name)
        for i, msg in zip(rows.tolist(), other.messages, strict=True):
            self.messages[i] = msg


def _compiled_solve(
    base: Any, pos: dict[str, Any], ea: np.ndarray
) -> tuple[StaticArrays, np.ndarray, list[str]] | None:
    """:func:`_compiled_solve_one` per group of cases on the same seabed (a swept depth,
    slope or friction: :meth:`SweptLines.seabeds`) whose lines are cut into as many
    pieces (swept lengths or attachment positions: :meth:`SweptLines.pieces`), put back
    in the chunk's order."""
    if _in_current(base, pos):  # solve_batch: the drag iteration per case, compiled
        return None
    lines = pos.get("lines")
    if lines is None:
        return _compiled_solve_one(base, pos, ea)
    seabed = lines.seabeds()
    pieces = lines.pieces()
    key = seabed * (int(pieces.max()) + 1) + pieces
    groups = np.unique(key)
    if groups.size == 1:
        return _compiled_solve_one(_with(base, medium=lines.media[seabed[0]]), pos, ea)
    out: StaticArrays | None = None
    left: list[np.ndarray] = []
    why: list[str] = []
    for g in groups.tolist():
        rows = np.flatnonzero(key == g)
        sub = _take(pos, rows)
        medium = lines.media[seabed[rows[0]]]
        got = _compiled_solve_one(_with(base, medium=medium), sub, ea[rows])
        if got is None:  # what the seabed does not decide: the same for every group
            return None
        if out is None:
            n = len(ea)
            out = StaticArrays(
                **{
                    name: np.empty(
                        (n, *getattr(got[0], name).shape[1:]), getattr(got[0], name).dtype
                    )
                    for name in StaticArrays.ARRAYS
                },
                messages=[""] * n,
            )
        out.put(rows, got[0])
        left.append(rows[got[1]])
        why.extend(got[2])
    order = np.argsort(np.concatenate(left), kind="stable")
    assert out is not None
    return out, np.concatenate(left)[order], [why[i] for i in order.tolist()]


def _compiled_solve_one(
    base: Any, pos: dict[str, Any], ea: np.ndarray
) -> tuple[StaticArrays, np.ndarray, list[str]] | None:
    """The cases of a chunk (the template's static problem ``base`` with end positions
    ``pos`` and segment stiffnesses ``ea`` per case) through the compiled batch kernel
    straight from arrays: the inputs :func:`cablestudy.statics.batch_kernels._solve_group` (lines
    hanging free) and :func:`cablestudy.statics.batch_kernels._contact_inputs` (end A anchored on
    the seabed, end B above it: :func:`cablestudy.statics.batch_kernels.solve_contact_arrays`)
    build from one problem object per case, built here for all cases at once (so the
    same numbers, bit for bit, without a per-case object). Returns the stacked results,
    the cases the kernels leave to the one-by-one solver (not converged, not finite,
    touching the seabed between the ends, end B on it, slack on it: exactly the cases
    :func:`solve_batch` would hand on) and why (per such case:
    :data:`~cablestudy.statics.batch_kernels.NOT_SETTLED`, ``ON_SEABED``, or '' for a case no
    kernel takes), or None when the template does not take this path (then
    :func:`solve_batch` runs as before).
    """
    from ..statics.aot import kernel
    from ..statics.batch_kernels import NOT_SETTLED, ON_SEABED, _guess
    from ..statics.seabed import seabed_of
    from ..statics.verify import Pieces, check_lines

    line, med = base.line, base.medium
    # the kernel compiled ahead of time where it is built: no numba to load (issue 20)
    solve_cases = kernel("solve_cases")
    if (
        solve_cases is None
        or base.end_a.kind != "fixed"
        or base.end_b.kind != "fixed"
        or line.is_nonlinear
        or med.has_current
    ):
        return None
    N = len(ea)
    n_nodes = base.n_nodes
    rA = np.ascontiguousarray(pos["a"], dtype=float)
    rB = np.ascontiguousarray(pos["b"], dtype=float)
    rest = np.zeros(N, dtype=bool)
    contact = np.zeros(N, dtype=bool)
    contact_b = np.zeros(N, dtype=bool)
    plane = seabed_of(med)
    # each case's own line (SweptLines: its loads, lengths, attachments), else the template's
    lines = pos.get("lines")
    if plane is not None:
        limit = 1e-6 * (line.total_length if lines is None else lines.total_length())
        grounded_a = _height_below(plane, rA[:, None, :], limit, strict=False)
        grounded_b = _height_below(plane, rB[:, None, :], limit, strict=False)
        # anchored at one end (not below the seabed), the other above: the contact
        # kernel, as batch.contact_end decides for a case alone (anchored at B: on the
        # reversed line)
        contact = (
            grounded_a & ~grounded_b & ~_height_below(plane, rA[:, None, :], -limit, strict=True)
        )
        contact_b = (
            grounded_b & ~grounded_a & ~_height_below(plane, rB[:, None, :], -limit, strict=True)
        )
        rest |= (grounded_a | grounded_b) & ~contact & ~contact_b
    ell, EA, w, point, bounds = layout_arrays(line, ea, lines)
    P = ell.shape[1]
    q = np.zeros((N, P, 3))
    q[:, :, 2] = -w
    Ltot = bounds[:, -1]
    tol = np.full(N, base.tolerance, dtype=float)
    maxit = np.full(N, base.max_iterations, dtype=np.int64)
    s = np.linspace(np.zeros(N), Ltot, n_nodes, axis=1)
    position = np.full((N, n_nodes, 3), np.nan)
    tension = np.full((N, n_nodes), np.nan)
    TL = np.full((N, 3), np.nan)
    TA = np.full((N, 3), np.nan)
    laid = np.zeros(N)
    iters = np.zeros(N, dtype=np.int64)
    resid = np.zeros(N)

    def seabed_checked(c: np.ndarray, settled: np.ndarray) -> np.ndarray:
        """Of the contact kernel's cases ``c`` (settled where ``settled``), those that
        pass the whole-line check with the seabed's admissible reaction (status 0 means
        verified; the others go to the general solver). The line as defined A to B: the
        kernel's arrays of a line anchored at B are already turned back."""
        ok = np.zeros(c.size, dtype=bool)
        idx = c[settled]
        if idx.size:
            ok[settled] = check_lines(
                s=s[idx],
                position=position[idx],
                tension=tension[idx],
                force_a=TA[idx],
                force_b=-TL[idx],
                pieces=Pieces(
                    bounds=bounds[idx],
                    weight=-q[idx, :, 2],
                    axial_stiffness=EA[idx],
                    point=point[idx],
                ),
                tolerance=tol[idx],
                position_a=rA[idx],
                position_b=rB[idx],
                plane=plane,
            ).ok
        return ok

    def keep_contact(c: np.ndarray, got: dict[str, np.ndarray], a: str, b: str) -> None:
        """The contact kernel's answers ``got`` for the cases ``c``, its end forces
        ``a`` and ``b`` those at the line's ends A and B; the cases that did not settle
        or fail :func:`seabed_checked` go to the general solver."""
        position[c], tension[c] = got["position"], got["tension"]
        TA[c], TL[c] = got[a], -got[b]
        laid[c], iters[c], resid[c] = got["laid_length"], got["iterations"], got["residual"]
        settled = got["status"] == 0
        settled &= seabed_checked(c, settled)
        for i in c[~settled]:
            rest[i], why[i] = True, NOT_SETTLED

    # why the kernels hand a case to the general solver ('' for a case they never take:
    # both ends on the seabed, an end below it)
    why = [""] * N
    free = np.flatnonzero(~rest & ~contact & ~contact_b)
    if free.size:
        f = free
        Q = q[f] * ell[f][..., None]
        Cend = point[f].sum(axis=1) + Q.sum(axis=1)
        target = rB[f] - rA[f]
        EAeff = Ltot[f] / np.sum(ell[f] / EA[f], axis=1)
        TA0 = _guess(target, Ltot[f], Cend, EAeff, point[f, 0])
        pos_f = np.empty((f.size, n_nodes, 3))
        ten_f, TA_f, TL_f = (
            np.empty((f.size, n_nodes)),
            np.empty((f.size, 3)),
            np.empty((f.size, 3)),
        )
        it_f, res_f, st_f = np.zeros(f.size, np.int64), np.zeros(f.size), np.zeros(f.size, np.int64)
        solve_cases(
            ell[f],
            EA[f],
            np.ascontiguousarray(-q[f][..., 2]),
            point[f],
            bounds[f],
            np.zeros(f.size, dtype=np.int64),  # kind: end B fixed
            rA[f],
            target,
            TA0,
            tol[f],
            maxit[f],
            s[f],
            pos_f,
            ten_f,
            TA_f,
            TL_f,
            it_f,
            res_f,
            st_f,
        )
        good = (
            (st_f == 0)
            & np.all(np.isfinite(pos_f), axis=(1, 2))
            & np.all(np.isfinite(ten_f), axis=1)
            & np.all(np.isfinite(TA_f), axis=1)
            & np.all(np.isfinite(TL_f), axis=1)
        )
        # status 0 means verified: what fails the whole-line check goes to the general
        # solver
        idx = np.flatnonzero(good)
        good[idx] = check_lines(
            s=s[f][idx],
            position=pos_f[idx],
            tension=ten_f[idx],
            force_a=TA_f[idx],
            force_b=-TL_f[idx],
            pieces=Pieces(
                bounds=bounds[f][idx],
                weight=-q[f][idx, :, 2],
                axial_stiffness=EA[f][idx],
                point=point[f][idx],
            ),
            tolerance=tol[f][idx],
            position_a=rA[f][idx],
            position_b=rB[f][idx],
        ).ok
        for j in np.flatnonzero(~good):
            why[f[j]] = NOT_SETTLED
        if plane is not None:
            on_seabed = good & _height_below(plane, pos_f, -1e-6 * Ltot[f], strict=True)
            for j in np.flatnonzero(on_seabed):
                why[f[j]] = ON_SEABED
            good &= ~on_seabed
        position[f], tension[f], TA[f], TL[f] = pos_f, ten_f, TA_f, TL_f
        iters[f], resid[f] = it_f, res_f
        rest[f[~good]] = True
    if contact.any():
        from ..statics.batch_kernels import solve_contact_arrays

        c = np.flatnonzero(contact)
        got = solve_contact_arrays(
            ell[c], EA[c], -q[c][..., 2], point[c], bounds[c], rA[c], rB[c], plane,
            tol[c], maxit[c], s[c],
        )  # fmt: skip
        keep_contact(c, got, "force_a", "force_b")
    if contact_b.any():
        from ..statics.batch_kernels import solve_contact_arrays

        c = np.flatnonzero(contact_b)
        # each case's own line, reversed as a case alone is
        ell_r, EA_r, w_r, point_r, bounds_r = layout_arrays(
            line, ea[c], None if lines is None else lines.take(c), reverse=True
        )
        got = solve_contact_arrays(
            ell_r, EA_r, w_r, point_r, bounds_r, rB[c], rA[c], plane,
            tol[c], maxit[c], Ltot[c, None] - s[c],
        )  # fmt: skip
        keep_contact(c, got, "force_b", "force_a")
    out = StaticArrays(
        s=s,
        position=position,
        tension=tension,
        force_a=TA,
        force_b=-TL,
        status=np.zeros(N, dtype=np.int64),
        messages=[""] * N,
        laid_length=laid,
        iterations=iters.astype(float),
        residual=resid,
        drag_iterations=np.zeros(N),
    )
    left = np.flatnonzero(rest)
    return out, left, [why[i] for i in left]


def _height_below(plane: Any, r: np.ndarray, limit: Any, *, strict: bool) -> np.ndarray:
    """Per case (axis 0 of ``r``, points (n, m, 3)): whether some point's height above
    ``plane`` is below ``limit`` (``strict``: <, else <=), with the result
    :meth:`Plane.height_above` gives case by case (cases within round-off of the limit
    are decided by that call itself)."""
    limit = np.broadcast_to(np.asarray(limit, dtype=float), (r.shape[0],))
    h = (r - np.array([0.0, 0.0, -plane.depth])) @ plane.normal  # (n, m)
    low = h.min(axis=1)
    out = low < limit if strict else low <= limit
    near = np.flatnonzero(np.abs(low - limit) <= 1e-9 * (np.abs(limit) + np.abs(low) + 1.0))
    for i in near:
        hi = plane.height_above(r[i] if r.shape[1] > 1 else r[i, 0])
        out[i] = bool(np.any(hi < limit[i])) if strict else bool(np.any(hi <= limit[i]))
    return out


def array_outputs(
    st: StaticArrays, template: Study, ea: np.ndarray, lines: SweptLines | None = None
) -> tuple[dict[str, np.ndarray], np.ndarray, list[str]]:
    """:func:`cablestudy.analyses.static.static_outputs` of many static results at once: the
    same variables, bit for bit (the same element-wise operations on stacked arrays;
    :func:`cablestudy.physics.profile.profile_quantities` of the (cases, nodes) arrays).
    Returns the outputs (cases first), status and messages, with a failed case's values
    NaN; with ``lines``, each case's areas and segments are those of its own line's, per
    group of cases whose nodes lie at the same arc lengths on segments of the same
    lengths (:func:`cablestudy.analyses.static_grid_lines.geometry_groups`)."""
    groups = geometry_groups(st.s, lines)
    if groups is None:
        study = template if lines is None else lines.studies[lines.which[0]]
        return _group_outputs(st, study, ea, lines)
    n = len(st.status)
    out: dict[str, np.ndarray] = {}
    status = np.empty(n, dtype=np.int64)
    messages = [""] * n
    for rows in groups:
        sub = None if lines is None else lines.take(rows)
        study = template if sub is None else sub.studies[sub.which[0]]
        got, st_g, msg_g = _group_outputs(st.take(rows), study, ea[rows], sub)
        for name, arr in got.items():
            if name not in out:
                out[name] = np.empty((n, *arr.shape[1:]), dtype=arr.dtype)
            out[name][rows] = arr
        status[rows] = st_g
        for i, msg in zip(rows.tolist(), msg_g, strict=True):
            messages[i] = msg
    return out, status, messages


def _group_outputs(
    st: StaticArrays, template: Study, ea: np.ndarray, lines: SweptLines | None
) -> tuple[dict[str, np.ndarray], np.ndarray, list[str]]:
    """:func:`array_outputs` of cases that share their arc lengths and the lengths of
    their segments, those of the line of ``template``."""
    from ..physics.profile import end_pulls, profile_quantities

    n = len(st.status)
    s = st.s[0]
    if not np.array_equal(st.s, np.broadcast_to(s, st.s.shape)):
        raise ValueError("cases of one chunk have different arc lengths")
    position, tension, force_a, force_b = st.position, st.tension, st.force_a, st.force_b
    status = st.status.copy()
    messages = list(st.messages)
    out: dict[str, np.ndarray] = {
        "arc_length": np.broadcast_to(s, (n, s.size)).copy(),
        "x": position[:, :, 0].copy(),
        "y": position[:, :, 1].copy(),
        "z": position[:, :, 2].copy(),
        "tension": tension.copy(),
        "force_a": force_a.copy(),
        "force_b": force_b.copy(),
        # np.linalg.norm of each (3,) force, bit for bit (the same dot product per row)
        "tension_a": np.sqrt(np.vecdot(force_a, force_a)),
        "tension_b": np.sqrt(np.vecdot(force_b, force_b)),
        "laid_length": st.laid_length.copy(),
        "static_iterations": st.iterations.copy(),
        "static_residual": st.residual.copy(),
        "drag_iterations": st.drag_iterations.copy(),
    }
    env, segs = template.environment, template.line.segments
    k = segment_of(segs, s)
    area = np.array([segs[i].area for i in k]) if lines is None else lines.area(k)
    out.update(
        profile_quantities(
            s,
            position,
            tension,
            axial_stiffness=ea[:, k],
            area=area,
            density=env.density,
            gravity=env.gravity,
            end_pull=end_pulls(force_a, force_b, **_tangent_ends(template, tension, lines)),
        )
    )
    ok = status == 0
    finite = np.ones(n, dtype=bool)
    bad_names: list[list[str]] = [[] for _ in range(n)]
    for name, arr in out.items():
        fin = np.isfinite(arr).reshape(n, -1).all(axis=1)
        for i in np.flatnonzero(ok & ~fin):
            bad_names[i].append(name)
        finite &= fin
    for i in np.flatnonzero(ok & ~finite):
        status[i] = STATUS_NUMERICAL
        messages[i] = f"non-finite values in {', '.join(sorted(bad_names[i]))}"
    failed = ~np.isin(status, KEPT_STATUSES)  # a case not verified keeps its numbers
    if failed.any():
        for arr in out.values():
            arr[failed] = np.nan
    return out, status, messages


def _tangent_ends(template: Study, tension: np.ndarray, lines: SweptLines | None) -> dict[str, Any]:
    """:func:`cablestudy.analyses.static.tangent_ends` of each case of a chunk (its own
    line's, with ``lines``): ``free_a``, ``free_b`` (cases,) and ``floor`` (cases,)."""
    from .static import tangent_ends

    tol = template.analysis.static.tolerance
    got = tangent_ends(template.line, tol, tension)
    if lines is not None:
        got["free_a"], got["free_b"] = lines.free_ends(tol)
    return got


def evaluate_grid_chunk(grid: CaseGrid, lo: int, hi: int) -> GridChunk:
    """Solve rows ``lo:hi`` of the grid as one batch and stack the outputs. Per case the
    same outputs, status and message as :func:`cablestudy.analyses.evaluate.evaluate_case`; a
    fault inside the batch fails the chunk's cases with its text (never raises). Cases
    whose swept static settings differ (node count, drag elements, tolerance:
    :mod:`cablestudy.analyses.static_grid_settings`) are solved per group of equal
    settings, each group's outputs padded to the grid's node count."""
    if getattr(grid, "is_system", False):  # a system's position sweep
        from .system_grid import evaluate_system_chunk

        return evaluate_system_chunk(grid, lo, hi)
    if not grid.arrays:
        from .static_grid_cases import evaluate_static_chunk

        return evaluate_static_chunk(grid, lo, hi)
    from .static_grid_settings import settings_groups, solve_in_groups

    t0 = time.perf_counter()
    n = (hi - lo) * math.prod(grid.shape[1:])
    reasons = np.full(n, "", dtype=object)
    status = np.zeros(n, dtype=np.int64)
    messages = [""] * n
    warnings: dict[int, list[str]] = {}  # only the cases that have some
    data: dict[str, np.ndarray] = {}
    try:
        base, pos, ea = _swept_inputs(grid, lo, hi)
        deadline = time.monotonic() + grid.template.analysis.time_limit * n
        groups = settings_groups(grid, lo, hi)
        if groups is None:
            data, status, messages, warnings, reasons = _solve_outputs(
                grid.template, base, pos, ea, deadline
            )
        else:
            data, status, messages, warnings, reasons = solve_in_groups(
                grid, groups, base, pos, ea, deadline, _solve_outputs, _with, _take
            )
    except Exception as exc:  # noqa: BLE001 - a fault in a chunk fails its cases, as data
        messages, warnings, data = numerical_fault(exc, status)
    return array_chunk(grid, lo, hi, t0, status, messages, data, warnings, reasons)


def _solve_each(template: Study, problems: list[Any]) -> list[Any]:
    """Each static problem solved alone by the template's method (not ``catenary``), as
    :func:`cablestudy.analyses.static.solve_static` solves a case alone (each with its own
    time limit)."""
    from ..statics import STATIC_SOLVERS
    from ..statics.base import STATUS_NO_SOLUTION, StaticResult
    from .static import unsupported_static

    method = template.analysis.static.method
    solver = STATIC_SOLVERS[method]
    limit = template.analysis.time_limit
    out = []
    for p in problems:
        missing = unsupported_static(method, p)
        if missing:  # what the method cannot model in this case: refused as data
            s = np.linspace(0.0, p.line.total_length, p.n_nodes)
            text = f"static method {method!r} does not support {'; '.join(missing)}"
            out.append(StaticResult.failed(s, STATUS_NO_SOLUTION, text))
            continue
        out.append(solver.solve(p, deadline=time.monotonic() + limit).check_finite())
    return out


def _take(pos: dict[str, Any], rows: np.ndarray) -> dict[str, Any]:
    """The swept inputs ``pos`` of the cases ``rows`` (in order)."""
    return {
        k: (None if v is None else v.take(rows) if k == "lines" else v[rows])
        for k, v in pos.items()
    }


def _solve_outputs(
    template: Study, base: Any, pos: dict[str, Any], ea: np.ndarray, deadline: float
) -> tuple[dict[str, np.ndarray], np.ndarray, list[str], dict[int, list[str]], np.ndarray]:
    """The cases of a chunk (``template``'s static problem ``base`` with the swept inputs
    ``pos`` and stiffnesses ``ea`` per case; all with ``template``'s static settings)
    solved and their outputs stacked: (outputs, status, messages, warnings of the cases
    that have some, fallback reasons). Raises on a fault (the caller fails the chunk)."""
    from ..statics.batch import solve_batch

    n = len(ea)
    reasons = np.full(n, "", dtype=object)
    warnings: dict[int, list[str]] = {}
    method = template.analysis.static.method
    compiled = _compiled_solve(base, pos, ea) if method == "catenary" else None
    if method != "catenary":  # no batch kernel: the method's solver, case by case
        problems = _problems(base, pos, ea)
        st = StaticArrays.of(_solve_each(template, problems))
        fallback = {}
        reasons[:] = _general_reasons(template, problems, list(range(n)))
    elif compiled is None:
        general: list[int] = []
        problems = _problems(base, pos, ea)
        results = solve_batch(problems, deadline=deadline, general=general)
        fallback = {i: r.fallback for i, r in enumerate(results) if r.fallback}
        reasons[general] = _general_reasons(template, problems, general)
        st = StaticArrays.of(results)
    else:
        st, rest, why = compiled
        if rest.size:  # what no kernel settled: the general solver, one by one
            st.put(
                rest,
                StaticArrays.of(
                    solve_batch(
                        _problems(base, _take(pos, rest), ea[rest]),
                        deadline=deadline,
                        contact=False,
                    )
                ),
            )
        fallback = {i: r for i, r in zip(rest.tolist(), why, strict=True) if r}
        reasons[rest] = NO_KERNEL
    for i, reason in fallback.items():
        reasons[i] = reason
    # break conditions, as each case alone (cablestudy.analyses.static_grid_limits)
    apply_grid_limits(st, template, pos.get("lines"))
    data, status, messages = array_outputs(st, template, ea, pos.get("lines"))
    k = node_segments(st.s, template, pos.get("lines"))  # each case's own line's
    max_strain = largest_strain(st.tension, np.take_along_axis(ea, k, axis=1))
    limit = template.analysis.static.strain_warning
    for i in np.flatnonzero((status == 0) & (max_strain > limit)):
        warnings.setdefault(int(i), []).append(strain_warning(float(max_strain[i]), limit))
    for i, reason in fallback.items():
        if status[i] == 0:
            warnings.setdefault(i, []).append(fallback_warning(reason))
    # a line above the water's surface (cablestudy.analyses.plausibility)
    for i, text in template_surface_warnings(template, st.s, st.position, status):
        warnings.setdefault(i, []).append(text)
    return data, status, messages, warnings, reasons
