"""Sweeps as arrays: a case is its index into the grid of sweep axes.

For a sweep whose cases differ only in settings the batched still-water catenary kernel
takes as numbers (end positions of fixed ends, segment axial stiffnesses) and whose
analysis is static with method ``catenary``, the study is validated once as a template,
each swept value once at its own path, and the checks that combine fields (ends below
the seabed, a weightless line shorter than its chord) over the whole grid with NumPy.
No per-case pydantic object is built: a chunk of cases becomes arrays of end positions
and stiffnesses, is solved by the compiled kernels (lines hanging free, and lines
anchored on the seabed with friction), the cases they do not settle by
:func:`cablestudy.statics.batch.solve_batch` (counted in :attr:`GridChunk.fallback`), and
its outputs are stacked into one array per output variable (a :class:`GridChunk`), which
the runner streams to disk.

Any other static-only sweep of numbers (lengths, diameters, weights, depth, friction,
current, end forces, attachments, node counts, any static method) is a grid too: each
case's study is the template with its validated swept values put in by copying, its
combined checks run per case, and a chunk is solved as validated cases are
(:mod:`cablestudy.grid_static`). The cases no batch kernel took are counted with their
reason (:attr:`GridChunk.fallback_reason`).

Anything else (a modal or dynamic analysis, the quasi-static database, a swept value that
is not a number, a swept value or combination that fails validation) goes through
:func:`cablestudy.cases.expand_cases`, which reports faults exactly as before.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .cases import SweepAxis, _copy_tree, _hash, _set_path, code_fingerprint, parse_sweep
from .config.loader import StudyError, StudySource, validate_data
from .config.study import Study
from .plausibility import fallback_warning, joined, largest_strain, strain_warning
from .results import KEPT_STATUSES

#: status of a case whose solver raised inside an array chunk or gave non-finite values:
#: cablestudy.statics.base.STATUS_NUMERICAL, as evaluate_case gives it (not imported
#: here: the statics package loads every solver)
STATUS_NUMERICAL = 2

#: why the general solver solved a case no batch kernel takes (both ends on the seabed,
#: an end below it, end A resting on it)
NO_KERNEL = "no batch kernel takes these end conditions"

#: swept paths the array path takes: (kind, end or segment, component)
_POSITION = re.compile(r"^ends\.(a|b)\.position\.([012])$")
_STIFFNESS = re.compile(r"^line\.segments\.(\d+)\.axial_stiffness$")


@dataclass(frozen=True)
class CaseGrid:
    """A swept study as a grid: the validated template, the axes, and per swept path the
    values as a float array along its axis."""

    template: Study
    axes: list[SweepAxis]
    #: per swept path: (axis number, values along that axis)
    swept: dict[str, tuple[int, np.ndarray]]
    #: content hash of what every case shares (solver code, template study with its
    #: defaults, which path is on which axis, the shape of a row); a chunk's key adds its
    #: swept values (:meth:`chunk_key`)
    key: str
    #: per swept path: (axis number, the validated value at each index of that axis)
    validated: dict[str, tuple[int, tuple[Any, ...]]] = field(default_factory=dict)
    #: whether the compiled catenary kernels take the chunks straight from arrays of end
    #: positions and stiffnesses (else :func:`cablestudy.grid_static.evaluate_static_chunk`
    #: builds each case's study by copying and solves the chunk as validated cases)
    arrays: bool = True

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(a.size for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    def rows(self, lo: int, hi: int) -> tuple[slice, ...]:
        """The block of cases ``lo <= i0 < hi`` along the first axis."""
        return (slice(lo, hi),) + tuple(slice(0, n) for n in self.shape[1:])

    def values(self, path: str, lo: int, hi: int) -> np.ndarray:
        """The value of ``path`` for every case of rows ``lo:hi``, flattened in C order."""
        axis, vals = self.swept[path]
        block = [hi - lo, *self.shape[1:]]
        take = vals[lo:hi] if axis == 0 else vals
        shape = [1] * len(block)
        shape[axis] = len(take)
        return np.broadcast_to(take.reshape(shape), block).reshape(-1)

    def chunk_key(self, lo: int, hi: int) -> str:
        """Content hash of the cases of rows ``lo:hi`` (the grid's key and their values)."""
        values = {
            p: (vals[lo:hi] if ax == 0 else vals).tolist() for p, (ax, vals) in self.swept.items()
        }
        return _hash([self.key, values])


def grid_shape(axes: list[SweepAxis]) -> list[int]:
    """Lengths of the axes after the first (a chunk holds whole rows of them)."""
    return [a.size for a in axes[1:]]


def _numeric(axes: list[SweepAxis]) -> bool:
    return all(
        isinstance(v, int | float) and not isinstance(v, bool)
        for axis in axes
        for vals in axis.values
        for v in vals
    )


def _static_sweep(template: Study, axes: list[SweepAxis]) -> bool:
    """A static-only study without a quasi-static database (its own grid of solves per
    case and its own file) whose swept paths all hold numbers that can be put into
    copies of the template (:func:`cablestudy.grid_static.copyable`)."""
    from .grid_static import copyable

    an = template.analysis
    if an.modal is not None or an.dynamic is not None or an.database is not None:
        return False
    if not axes or not _numeric(axes):
        return False
    return all(copyable(template, p) for axis in axes for p in axis.paths)


def _eligible(template: Study, axes: list[SweepAxis]) -> bool:
    """A static-only, still-water, method 'catenary' study without a quasi-static
    database (its grid of solves per case is not an array kernel) whose swept paths are
    all end positions of fixed ends or segment stiffnesses, with numeric values."""
    an = template.analysis
    if an.modal is not None or an.dynamic is not None or an.static.method != "catenary":
        return False
    if an.database is not None:
        return False
    if template.environment.current or template.line.pulleys:
        return False
    line = template.line
    # the arrays' outputs take strain as T / EA and no break limits: a nonlinear law or
    # a failure condition is solved as validated cases are (cablestudy.grid_static)
    if line.is_spring or line.failure is not None:
        return False
    if any(seg.is_nonlinear or seg.failure is not None for seg in line.segments):
        return False
    if getattr(an.static, "installation", None) is not None:
        return False
    for axis in axes:
        for path, vals in zip(axis.paths, axis.values, strict=True):
            m = _POSITION.match(path)
            if m:
                if getattr(getattr(template.ends, m.group(1)), "kind", "") != "fixed":
                    return False
            elif not _STIFFNESS.match(path):
                return False
            if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in vals):
                return False
    return bool(axes)


def expand_grid(src: StudySource) -> CaseGrid | None:
    """The study as a :class:`CaseGrid` when its sweep can run as arrays and every swept
    value and combination is valid; ``None`` otherwise (the caller then expands the
    cases one by one, which reports any fault at its line as before). A fault in the
    template itself is raised here, as :func:`expand_cases` would."""
    from .grid_static import combinations_ok, value_at

    template = validate_data(src.data, src)
    if template.lines:  # a system of lines: its position sweeps (cablestudy.system_grid)
        from .system_grid import expand_system_grid

        return expand_system_grid(src, template)
    axes = parse_sweep(src)
    if not _static_sweep(template, axes):
        return None
    arrays = _eligible(template, axes)
    base = {k: v for k, v in src.data.items() if k != "sweep"}
    # each swept value once, at its own path (the others as in the template)
    validated: dict[str, tuple[int, list[Any]]] = {
        p: (k, []) for k, axis in enumerate(axes) for p in axis.paths
    }
    for axis in axes:
        for i in range(axis.size):
            data = _copy_tree(base)
            try:
                for path, vals in zip(axis.paths, axis.values, strict=True):
                    _set_path(data, path, vals[i])
                study = validate_data(data, src)
            except (KeyError, StudyError):
                return None
            for path in axis.paths:
                validated[path][1].append(value_at(study, path))
    swept = {
        p: (k, np.asarray(vals, dtype=float))
        for k, axis in enumerate(axes)
        for p, vals in zip(axis.paths, axis.values, strict=True)
    }
    body = template.model_dump(mode="json", exclude={"name", "description", "sweep"})
    grid = CaseGrid(
        template,
        axes,
        swept,
        _hash([code_fingerprint(), body, {p: k for p, (k, _) in swept.items()}, grid_shape(axes)]),
        {p: (k, tuple(v)) for p, (k, v) in validated.items()},
        arrays,
    )
    if not (_combined_ok(grid) if arrays else combinations_ok(grid)):
        return None
    return grid


def _combined_ok(grid: CaseGrid) -> bool:
    """The checks of :meth:`Study._physical` that involve swept fields, over the whole
    grid at once (end positions against the seabed; a weightless line between fixed ends
    closer than its length). Stiffness enters none of them."""
    t = grid.template
    env = t.environment

    def position(end: str) -> list[np.ndarray]:
        fixed = getattr(t.ends, end)
        out = []
        for c in range(3):
            path = f"ends.{end}.position.{c}"
            if path in grid.swept:
                axis, vals = grid.swept[path]
                shape = [1] * len(grid.shape)
                shape[axis] = len(vals)
                out.append(vals.reshape(shape))
            else:
                out.append(
                    np.asarray(float(fixed.position[c]))
                    if hasattr(fixed, "position")
                    else np.asarray(math.nan)
                )
        return out

    pa, pb = position("a"), position("b")
    rho, g = env.density, env.gravity
    weightless = all(seg.weight_in(rho, g) == 0.0 for seg in t.line.segments) and not any(
        att.mass != rho * att.volume or any(att.force) for att in t.line.attachments
    )
    if weightless and t.ends.a.kind == "fixed" and t.ends.b.kind == "fixed":
        chord = np.sqrt(sum((b - a) ** 2 for a, b in zip(pa, pb, strict=True)))
        if np.any(chord <= t.line.length):
            return False
    if env.depth is not None:
        rise = math.tan(math.radians(env.seabed.slope_deg))
        heading = math.radians(env.seabed.slope_heading_deg)
        for label, (x, y, z) in (("a", pa), ("b", pb)):
            if getattr(t.ends, label).kind != "fixed":
                continue
            ground = -env.depth + rise * (x * math.cos(heading) + y * math.sin(heading))
            if np.any(z < ground - 1e-9 * env.depth):
                return False
    return True


@dataclass
class GridChunk:
    """The outputs of rows ``lo:hi`` of a grid: one array per variable, cases first in
    C order (shape (n_cases, *extra dims)), and per case status, message and wall time
    (the chunk's time shared out equally)."""

    lo: int
    hi: int
    key: str
    status: np.ndarray
    message: np.ndarray  # unicode
    wall_time: np.ndarray
    data: dict[str, np.ndarray]
    #: cases no array kernel settled, solved one by one by the general solver
    fallback: int = 0
    #: per case, why its kept results are implausible or risky (unicode, '' if not)
    warning: np.ndarray | None = None
    #: per case, why the general solver solved it (unicode, '' if a batch kernel did)
    fallback_reason: np.ndarray | None = None

    def __post_init__(self) -> None:
        if self.warning is None:
            self.warning = np.full(len(self.status), "")
        if self.fallback_reason is None:
            self.fallback_reason = np.full(len(self.status), "")

    @property
    def n(self) -> int:
        return len(self.status)


def _swept_inputs(grid: CaseGrid, lo: int, hi: int) -> tuple[Any, dict[str, Any], np.ndarray]:
    """The template's static problem, per end the positions of rows ``lo:hi`` ((n, 3),
    None for an end that is not fixed) and the segment stiffnesses ((n, n_segments))."""
    from .problem import static_problem

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
    for path in grid.swept:
        m = _POSITION.match(path)
        if m:
            pos[m.group(1)][:, int(m.group(2))] = grid.values(path, lo, hi)
        else:
            k = int(_STIFFNESS.match(path).group(1))  # type: ignore[union-attr]
            ea[:, k] = grid.values(path, lo, hi)
    return base, pos, ea


def _problems(base: Any, pos: dict[str, Any], ea: np.ndarray) -> list[Any]:
    """One static problem per case: the template's with the swept numbers put in
    (shallow copies of the frozen dataclasses; every array shared but the swept ones)."""
    ea_swept = not np.all(ea == base.line.axial_stiffness)
    problems = []
    for i in range(len(ea)):
        changes: dict[str, Any] = {}
        for end in "ab":
            if pos[end] is not None:
                changes[f"end_{end}"] = _with(getattr(base, f"end_{end}"), position=pos[end][i])
        if ea_swept:
            changes["line"] = _with(base.line, axial_stiffness=ea[i])
        problems.append(_with(base, **changes))
    return problems


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

    def put(self, rows: np.ndarray, other: StaticArrays) -> None:
        """Overwrite cases ``rows`` with the cases of ``other`` (in order)."""
        for name in (
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
        ):
            getattr(self, name)[rows] = getattr(other, name)
        for i, msg in zip(rows.tolist(), other.messages, strict=True):
            self.messages[i] = msg


def _compiled_solve(
    base: Any, pos: dict[str, Any], ea: np.ndarray
) -> tuple[StaticArrays, np.ndarray, list[str]] | None:
    """The cases of a chunk (the template's static problem ``base`` with end positions
    ``pos`` and segment stiffnesses ``ea`` per case) through the compiled batch kernel
    straight from arrays: the inputs :func:`cablestudy.statics.batch._solve_group` (lines
    hanging free) and :func:`cablestudy.statics.batch._contact_one` (end A anchored on
    the seabed, end B above it: :func:`cablestudy.statics.batch.solve_contact_arrays`)
    build from one problem object per case, built here for all cases at once (so the
    same numbers, bit for bit, without a per-case object). Returns the stacked results,
    the cases the kernels leave to the one-by-one solver (not converged, not finite,
    touching the seabed between the ends, end B on it, slack on it: exactly the cases
    :func:`solve_batch` would hand on) and why (per such case:
    :data:`~cablestudy.statics.batch.NOT_SETTLED`, ``ON_SEABED``, or '' for a case no
    kernel takes), or None when the template does not take this path (then
    :func:`solve_batch` runs as before).
    """
    from .statics.aot import free_hanging_kernel
    from .statics.batch import NOT_SETTLED, ON_SEABED, _guess
    from .statics.verify import Pieces, check_lines

    line, med = base.line, base.medium
    # the kernel compiled ahead of time where it is built: no numba to load (issue 20)
    solve_cases = free_hanging_kernel()
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
    plane = None
    rest = np.zeros(N, dtype=bool)
    contact = np.zeros(N, dtype=bool)
    contact_b = np.zeros(N, dtype=bool)
    if med.depth is not None:
        from .statics.seabed import Plane

        plane = Plane(med.depth, med.seabed_slope, med.seabed_heading, med.friction)
        limit = 1e-6 * line.total_length
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
    if line.length.size == 1 and line.attachment_s.size == 0:
        P = 1
        ell = np.full((N, 1), line.length[0])
        EA = np.ascontiguousarray(ea[:, :1], dtype=float)
        q = np.zeros((N, 1, 3))
        q[:, 0, 2] = -line.weight[0]
        point = np.zeros((N, 2, 3))
        bounds = np.empty((N, 2))
        bounds[:, 0] = 0.0
        bounds[:, 1] = ell[:, 0]
    else:
        from .statics.semi_analytic import make_layout

        lay = make_layout(line)
        P = len(lay.ell)
        ell = np.tile(lay.ell, (N, 1))
        EA = np.ascontiguousarray(ea[:, lay.segment], dtype=float)
        q = np.zeros((N, P, 3))
        q[:, :, 2] = -lay.weight
        point = np.tile(lay.point, (N, 1, 1))
        bounds = np.tile(lay.bounds, (N, 1))
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
        from .statics.batch import solve_contact_arrays

        c = np.flatnonzero(contact)
        got = solve_contact_arrays(
            ell[c], EA[c], -q[c][..., 2], point[c], bounds[c], rA[c], rB[c], plane,
            tol[c], maxit[c], s[c],
        )  # fmt: skip
        position[c], tension[c] = got["position"], got["tension"]
        TA[c], TL[c] = got["force_a"], -got["force_b"]
        laid[c], iters[c], resid[c] = got["laid_length"], got["iterations"], got["residual"]
        settled = got["status"] == 0
        settled &= seabed_checked(c, settled)
        for i in c[~settled]:
            rest[i], why[i] = True, NOT_SETTLED
    if contact_b.any():
        from .statics.batch import solve_contact_arrays
        from .statics.semi_analytic import make_layout, reversed_line

        c = np.flatnonzero(contact_b)
        m = c.size
        if line.length.size == 1 and line.attachment_s.size == 0:
            ell_r, EA_r, w_r = ell[c], EA[c], -q[c][..., 2]
            point_r, bounds_r = point[c], bounds[c]
        else:
            lay_r = make_layout(reversed_line(line))
            ell_r, w_r = np.tile(lay_r.ell, (m, 1)), np.tile(lay_r.weight, (m, 1))
            EA_r = ea[c][:, ::-1][:, lay_r.segment]
            point_r, bounds_r = np.tile(lay_r.point, (m, 1, 1)), np.tile(lay_r.bounds, (m, 1))
        got = solve_contact_arrays(
            ell_r, EA_r, w_r, point_r, bounds_r, rB[c], rA[c], plane,
            tol[c], maxit[c], Ltot[c, None] - s[c],
        )  # fmt: skip
        position[c], tension[c] = got["position"], got["tension"]
        TA[c], TL[c] = got["force_b"], -got["force_a"]
        laid[c], iters[c], resid[c] = got["laid_length"], got["iterations"], got["residual"]
        settled = got["status"] == 0
        settled &= seabed_checked(c, settled)
        for i in c[~settled]:
            rest[i], why[i] = True, NOT_SETTLED
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


def stacked_outputs(
    results: list[Any], template: Study, ea: np.ndarray
) -> tuple[dict[str, np.ndarray], np.ndarray, list[str]]:
    """:func:`cablestudy.analyses.static_outputs` of many static results at once (see
    :func:`array_outputs`)."""
    return array_outputs(StaticArrays.of(results), template, ea)


def array_outputs(
    st: StaticArrays, template: Study, ea: np.ndarray
) -> tuple[dict[str, np.ndarray], np.ndarray, list[str]]:
    """:func:`cablestudy.analyses.static_outputs` of many static results at once: the
    same variables, bit for bit (the same element-wise operations on stacked arrays;
    the profile quantities are those of :func:`cablestudy.physics.profile.
    profile_quantities`, evaluated along axis 1 of (cases, nodes) arrays). Returns the
    outputs (cases first), status and messages, with a failed case's values NaN."""
    from .physics.profile import profile_quantities

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
    seg_end = np.cumsum([seg.length for seg in segs])
    k = np.minimum(np.searchsorted(seg_end, s, side="right"), len(segs) - 1)
    area = np.array([segs[i].area for i in k])
    m = s.size
    if m >= 3:
        d = np.gradient(position, s, axis=1, edge_order=2)
    else:
        d = np.repeat(np.diff(position, axis=1), m, axis=1)[:, :m]
    norm = np.linalg.norm(d, axis=2)
    t = d / np.where(norm > 0.0, norm, 1.0)[:, :, None]
    horizontal = np.hypot(t[:, :, 0], t[:, :, 1])
    elevation = np.arctan2(t[:, :, 2], horizontal)
    azimuth = np.arctan2(t[:, :, 1], t[:, :, 0])
    strain = tension / ea[:, k]
    elongation = np.concatenate(
        [np.zeros((n, 1)), np.cumsum(0.5 * (strain[:, 1:] + strain[:, :-1]) * np.diff(s), axis=1)],
        axis=1,
    )
    tension_wall = tension + env.density * env.gravity * position[:, :, 2] * area
    # a vertical tangent somewhere: that case's azimuths as profile_quantities gives them
    for i in np.flatnonzero(~np.all(horizontal > 1e-12, axis=1)):
        azimuth[i] = profile_quantities(
            s,
            position[i],
            tension[i],
            axial_stiffness=ea[i, k],
            area=area,
            density=env.density,
            gravity=env.gravity,
        )["azimuth"]
    out.update(
        elevation=elevation, azimuth=azimuth, elongation=elongation, tension_wall=tension_wall
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


def _segment_of(template: Study, s: np.ndarray) -> np.ndarray:
    """The segment of each arc length ``s`` [m] of the template's line."""
    seg_end = np.cumsum([seg.length for seg in template.line.segments])
    return np.minimum(np.searchsorted(seg_end, s, side="right"), len(seg_end) - 1)


def evaluate_grid_chunk(grid: CaseGrid, lo: int, hi: int) -> GridChunk:
    """Solve rows ``lo:hi`` of the grid as one batch and stack the outputs. Per case the
    same outputs, status and message as :func:`cablestudy.analyses.evaluate_case`; a
    fault inside the batch fails the chunk's cases with its text (never raises)."""
    from .statics.batch import solve_batch

    if getattr(grid, "is_system", False):  # a system's position sweep
        from .system_grid import evaluate_system_chunk

        return evaluate_system_chunk(grid, lo, hi)
    if not grid.arrays:
        from .grid_static import evaluate_static_chunk

        return evaluate_static_chunk(grid, lo, hi)
    t0 = time.perf_counter()
    n = (hi - lo) * math.prod(grid.shape[1:])
    reasons = np.full(n, "", dtype=object)
    status = np.zeros(n, dtype=np.int64)
    messages = [""] * n
    warnings: dict[int, list[str]] = {}  # only the cases that have some
    data: dict[str, np.ndarray] = {}
    n_general = n
    try:
        base, pos, ea = _swept_inputs(grid, lo, hi)
        deadline = time.monotonic() + grid.template.analysis.time_limit * n
        compiled = _compiled_solve(base, pos, ea)
        if compiled is None:
            general: list[int] = []
            results = solve_batch(_problems(base, pos, ea), deadline=deadline, general=general)
            fallback = {i: r.fallback for i, r in enumerate(results) if r.fallback}
            n_general = len(general)
            reasons[general] = NO_KERNEL
            st = StaticArrays.of(results)
        else:
            st, rest, why = compiled
            n_general = int(rest.size)
            if rest.size:  # what no kernel settled: the general solver, one by one
                sub = {k: (None if v is None else v[rest]) for k, v in pos.items()}
                st.put(
                    rest,
                    StaticArrays.of(
                        solve_batch(
                            _problems(base, sub, ea[rest]), deadline=deadline, contact=False
                        )
                    ),
                )
            fallback = {i: r for i, r in zip(rest.tolist(), why, strict=True) if r}
            reasons[rest] = NO_KERNEL
        for i, reason in fallback.items():
            reasons[i] = reason
        data, status, messages = array_outputs(st, grid.template, ea)
        max_strain = largest_strain(st.tension, ea[:, _segment_of(grid.template, st.s[0])])
        limit = grid.template.analysis.static.strain_warning
        for i in np.flatnonzero((status == 0) & (max_strain > limit)):
            warnings.setdefault(int(i), []).append(strain_warning(float(max_strain[i]), limit))
        for i, reason in fallback.items():
            if status[i] == 0:
                warnings.setdefault(i, []).append(fallback_warning(reason))
    except Exception as exc:  # noqa: BLE001 - a fault in a chunk fails its cases, as data
        status[:] = STATUS_NUMERICAL
        messages = [f"{type(exc).__name__}: {exc}"] * n
        warnings = {}
        data = {}
    wall = (time.perf_counter() - t0) / max(n, 1)
    return GridChunk(
        lo=lo,
        hi=hi,
        key=grid.chunk_key(lo, hi),
        status=status,
        message=np.array(messages, dtype=str).reshape(n),
        wall_time=np.full(n, wall),
        data=data,
        fallback=n_general,
        warning=_warning_column(n, warnings),
        fallback_reason=np.array(reasons.tolist(), dtype=str).reshape(n),
    )


def _warning_column(n: int, warnings: dict[int, list[str]]) -> np.ndarray:
    """The ``warning`` text of ``n`` cases, from the warnings of those that have some."""
    texts = {i: joined(w) for i, w in warnings.items()}
    width = max((len(t) for t in texts.values()), default=0)
    column = np.full(n, "", dtype=f"<U{max(width, 1)}")
    for i, text in texts.items():
        column[i] = text
    return column


def failed_grid_chunk(grid: CaseGrid, lo: int, hi: int, message: str) -> GridChunk:
    """Rows ``lo:hi`` failed outside the solvers (a worker lost): status 9, the reason,
    no data."""
    n = (hi - lo) * math.prod(grid.shape[1:])
    return GridChunk(
        lo=lo,
        hi=hi,
        key=grid.chunk_key(lo, hi),
        status=np.full(n, 9, dtype=np.int64),
        message=np.array([message] * n, dtype=str).reshape(n),
        wall_time=np.full(n, np.nan),
        data={},
    )
