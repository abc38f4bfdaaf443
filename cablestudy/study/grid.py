"""Sweeps as arrays: a case is its index into the grid of sweep axes.

The study is validated once as a template, each swept value once at its own path, and
the checks that combine fields (ends below the seabed, a weightless line shorter than its
chord) over the whole grid with NumPy (:func:`expand_grid`). No per-case pydantic object
is built. A grid whose cases differ only in settings the batched still-water catenary
kernel takes as numbers (end positions of fixed ends, segment axial stiffnesses) runs as
arrays (:attr:`CaseGrid.arrays`, :mod:`cablestudy.analyses.static_grid`); any other static-only
sweep of
numbers (lengths, diameters, weights, depth, friction, current, end forces, attachments,
node counts, any static method) is a grid too, each case's study the template with its
validated swept values copied in (:mod:`cablestudy.study.grid_studies`).

Anything else (a modal or dynamic analysis, the quasi-static database, a swept value
that is not a number, a swept value or combination that fails validation) goes through
:func:`cablestudy.study.cases.expand_cases`, which reports faults exactly as before.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .cases import SweepAxis, _copy_tree, _hash, _set_path, code_fingerprint, parse_sweep
from .loader import StudyError, StudySource, validate_data
from .study import Study

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
    #: positions and stiffnesses (else
    #: :func:`cablestudy.analyses.static_grid_cases.evaluate_static_chunk`
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
    copies of the template (:func:`cablestudy.study.grid_studies.copyable`)."""
    from .grid_studies import copyable

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
    # a failure condition is solved as validated cases are (cablestudy.analyses.static_grid_cases)
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


def expand_grid(src: StudySource, template: Study | None = None) -> CaseGrid | None:
    """The study as a :class:`CaseGrid` when its sweep can run as arrays and every swept
    value and combination is valid; ``None`` otherwise (the caller then expands the
    cases one by one, which reports any fault at its line as before). A fault in the
    template itself is raised here, as :func:`expand_cases` would."""
    from .grid_studies import combinations_ok, value_at

    if template is None:
        template = validate_data(src.data, src)
    if template.lines:  # a system: cablestudy.run.grid_runner.study_grid
        return None
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
