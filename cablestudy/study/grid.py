"""Every study as a grid of cases: a case is its index into the grid of sweep axes.

The study is validated once as a template, each swept value once at its own path
(inside the smallest model that holds it where that is exactly the whole study's
validation, :mod:`cablestudy.study.grid_values`; else as a whole study), and the checks
that combine fields over the grid (:func:`expand_grid`): with NumPy where the
array chunk takes the grid (end positions of fixed ends, segment
stiffnesses, towing and mooring ends' loads; the line's loads, lengths, attachments,
coefficients and break limits and the seabed built once per combination of their
values, :mod:`cablestudy.study.grid_lines`; the static settings, solved per group:
:attr:`CaseGrid.arrays`, :mod:`cablestudy.analyses.static_grid`), else by the
models' own ``mode="after"`` validators on each case's study, which is the template with
its validated swept values copied in (:mod:`cablestudy.study.grid_studies`). A swept path
that cannot be copied into the template (a model whose validator derives other fields
from it, a keyed entry of a system, a value that is not a number or a string) is named
in :attr:`CaseGrid.whole`: each combination of its values is validated as a whole study,
once, and the other swept values copied in. No study is validated case by case unless a
value or a combination fails: then :func:`cablestudy.study.cases.report_sweep_faults`
names every fault at its line.

A static-only one-line sweep of numbers runs in chunks of rows of the grid
(:attr:`CaseGrid.chunked`, :mod:`cablestudy.run.grid_runner`); any other study runs its
cases (:meth:`CaseGrid.cases`) through the per-case evaluators.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .cases import (
    Case,
    SweepAxis,
    _copy_tree,
    _hash,
    _set_path,
    case_hashes,
    code_fingerprint,
    parse_sweep,
    report_sweep_faults,
)
from .environment import seabed_height, seabed_slope
from .grid_lines import (
    MAX_LINES,
    line_count,
    line_index,
    line_studies,
    per_line,
    static_setting,
    weightless,
)
from .loader import StudyError, StudySource, validate_data
from .study import Study

#: swept paths the array path takes: (kind, end or segment, component)
_POSITION = re.compile(r"^ends\.(a|b)\.position\.([012])$")
_STIFFNESS = re.compile(r"^line\.segments\.(\d+)\.axial_stiffness$")
#: the known load of an end that is not fixed: a towing end's force components, a
#: mooring end's horizontal force components and height (end, 'force' or 'z', component)
_END_LOAD = re.compile(r"^ends\.(a|b)\.(force\.([012])|z)$")


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
    #: positions, stiffnesses, lines and seabeds (:mod:`cablestudy.study.grid_lines`; else
    #: :func:`cablestudy.analyses.static_grid_cases.evaluate_static_chunk`
    #: builds each case's study by copying and solves the chunk as validated cases)
    arrays: bool = True
    #: whether the grid runs in chunks of rows (:mod:`cablestudy.run.grid_runner`): a
    #: static-only one-line sweep of numbers, or a system's position sweep; else its
    #: cases (:meth:`cases`) run through the per-case evaluators
    chunked: bool = True
    #: swept paths that cannot be copied into the template: each combination of their
    #: values is validated as a whole study (:meth:`study_at`)
    whole: tuple[str, ...] = ()
    #: the study source (to validate the combinations of :attr:`whole` paths)
    src: StudySource | None = None
    #: studies of the combinations of :attr:`whole` values, and the cases, once built
    memo: dict[Any, Any] = field(default_factory=dict, compare=False, repr=False)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(a.size for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

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

    def study_at(self, index: tuple[int, ...]) -> Study:
        """The validated study of the case at ``index``: the template (or the whole study
        of its :attr:`whole` values) with its other validated swept values copied in;
        raises as a full validation of the case would."""
        from .grid_studies import case_study

        built = self.memo.get("cases")
        if built is not None:  # each case's study is built once
            return built[int(np.ravel_multi_index(index, self.shape))].study
        if len(self.axes) == 1 and not self.whole:
            # a single axis: the study its value was checked in (expand_grid)
            found = self.memo.get(("value", index[0]))
            if found is not None:
                return found
        base = self.template
        if self.whole:
            picks = tuple(
                (p, index[axis])
                for axis, a in enumerate(self.axes)
                for p in a.paths
                if p in self.whole
            )
            base = self.memo.get(picks)
            if base is None:
                assert self.src is not None
                data = {k: v for k, v in self.src.data.items() if k != "sweep"}
                data = _copy_tree(data)
                values = {
                    p: v
                    for axis, a in enumerate(self.axes)
                    for p, v in zip(a.paths, a.values, strict=True)
                }
                for p, i in picks:
                    _set_path(data, p, _copy_tree(values[p][i]))
                base = self.memo[picks] = validate_data(data, self.src)
        copied = {
            p: vals[index[axis]]
            for p, (axis, vals) in self.validated.items()
            if p not in self.whole
        }
        return case_study(base, copied) if copied else base

    def case_hashes(self, index: tuple[int, ...]) -> tuple[str, str]:
        """(case hash, static hash) of the case at ``index``: the content hashes of the
        template (:func:`cablestudy.study.cases.case_hashes`: every validated setting with
        its defaults, and the solver code) with the case's swept values, all of them and
        those that can change its static solution (a path outside ``analysis``, or into
        ``analysis.static`` but its strain warning). No dump of the case's study."""
        found = self.memo.get("keys")
        if found is None:
            found = self.memo["keys"] = case_hashes(self.template)
        values = {
            p: vals[index[axis]]
            for axis, a in enumerate(self.axes)
            for p, vals in zip(a.paths, a.values, strict=True)
        }
        statics = {p: v for p, v in values.items() if _static_path(p)}
        return _hash([found[0], values]), _hash([found[1], statics])

    def cases(self) -> list[Case]:
        """Every case in C order of the grid, with its coordinates and content hashes
        (built once)."""
        found = self.memo.get("cases")
        if found is None:
            coordinates = [a.coordinate() for a in self.axes]
            found = []
            for index in itertools.product(*(range(n) for n in self.shape)):
                study = self.study_at(index)
                coords = {
                    a.name: c[i].item()
                    for a, c, i in zip(self.axes, coordinates, index, strict=True)
                }
                found.append(Case(index, coords, study, *self.case_hashes(index)))
            self.memo["cases"] = found
        return found


def _static_path(path: str) -> bool:
    """Whether a swept ``path`` can change a case's static solution (every path outside
    ``analysis``, and the static settings but the strain warning's limit)."""
    if not path.startswith("analysis"):
        return True
    return path == "analysis" or (
        path.startswith("analysis.static") and not path.startswith("analysis.static.strain_warning")
    )


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
    # a path into a segment of a catalogue line type cannot be copied in: its line is
    # validated as a whole study once per combination of its values (grid_lines)
    return all(copyable(template, p) or per_line(p) for axis in axes for p in axis.paths)


def _eligible(template: Study, axes: list[SweepAxis]) -> bool:
    """A static-only study (any static method: ``catenary`` through the compiled
    kernels, another through its solver per case) without a quasi-static database (its
    grid of solves per case is not an array kernel), with linear axial laws, in still
    water or a current (:func:`_current_ok`), whose swept paths are all end positions
    of fixed ends, segment stiffnesses, the numbers of the line, the seabed or the
    current (:func:`cablestudy.study.grid_lines.per_line`), a towing or mooring end's
    known load (:func:`_end_load`), or a static setting
    (:func:`cablestudy.study.grid_lines.static_setting`), with numeric values."""
    an = template.analysis
    if an.modal is not None or an.dynamic is not None:
        return False
    if an.database is not None:
        return False
    if template.line.pulleys or not _current_ok(template):
        return False
    line = template.line
    # the arrays' outputs take strain as T / EA: a nonlinear law is solved as validated
    # cases are (cablestudy.analyses.static_grid_cases); break conditions are checked
    # per case on the arrays (cablestudy.analyses.static_grid_limits)
    if line.is_spring:
        return False
    if any(seg.is_nonlinear for seg in line.segments):
        return False
    if getattr(an.static, "installation", None) is not None:
        return False
    for axis in axes:
        for path, vals in zip(axis.paths, axis.values, strict=True):
            m = _POSITION.match(path)
            if m:
                if getattr(getattr(template.ends, m.group(1)), "kind", "") != "fixed":
                    return False
            elif not (
                _STIFFNESS.match(path)
                or per_line(path)
                or _end_load(template, path)
                or static_setting(template, path)
            ):
                return False
            if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in vals):
                return False
    # a line per combination of the swept load values (cablestudy.study.grid_lines)
    return bool(axes) and line_count(axes) <= MAX_LINES


def _end_load(template: Study, path: str) -> bool:
    """Whether ``path`` is a known load of an end that has one (:data:`_END_LOAD`: a
    ``force`` end's force, a ``mooring`` end's horizontal force and height), which the
    arrays put into each case's end condition (the batch kernels take both kinds)."""
    m = _END_LOAD.match(path)
    if m is None:
        return False
    kind = getattr(getattr(template.ends, m.group(1)), "kind", "")
    return kind == "mooring" or (kind == "force" and m.group(3) is not None)


def _current_ok(template: Study) -> bool:
    """Whether a template in a current (or in still water) takes the arrays: its cases in
    a current are solved by :func:`cablestudy.statics.batch.solve_batch` (the drag
    iteration per case in the compiled batch, :mod:`cablestudy.statics.batch_drag`, or the
    general solver where that does not take a case), except drag on the stretched
    diameter, which the catenary solver refuses (a case alone says so)."""
    if not template.environment.current or template.analysis.static.method != "catenary":
        return True  # another method's solver takes each case as a case alone
    return template.analysis.static.drag_diameter == "unstretched"


def expand_grid(src: StudySource, template: Study | None = None) -> CaseGrid:
    """The study as a :class:`CaseGrid` (one case without a sweep). Raises
    :class:`StudyError` naming every fault when the template, a swept value or a
    combination of them is invalid, before any work."""
    from .grid_studies import combinations_ok, copyable, value_at
    from .grid_values import validated_values

    if template is None:
        template = validate_data(src.data, src)
    axes = parse_sweep(src)
    whole = tuple(p for axis in axes for p in axis.paths if not copyable(template, p))
    chunked = not template.lines and _static_sweep(template, axes)
    arrays = chunked and _eligible(template, axes)
    base = {k: v for k, v in src.data.items() if k != "sweep"}
    # each swept value once, at its own path (the others as in the template)
    validated: dict[str, tuple[int, list[Any]]] = {
        p: (k, []) for k, axis in enumerate(axes) for p in axis.paths
    }
    alone = True  # every swept value valid at its own path
    # with a single axis, the study a value is checked in (the template with it put in)
    # is its case's study: the combinations are checked, and those of a grid run case by
    # case kept for its cases (which hold them anyway)
    single = len(axes) == 1
    studies: dict[Any, Study] = {}
    for axis in axes:
        inside = not any(p in whole for p in axis.paths)
        for i in range(axis.size):
            got = (
                validated_values(template, base, axis.paths, tuple(v[i] for v in axis.values))
                if inside
                else None
            )
            if got is not None:  # validated inside the model that holds it (grid_values)
                for path in axis.paths:
                    validated[path][1].append(got[0][path])
                if single and not chunked:
                    studies[("value", i)] = got[1]
                continue
            single = False
            data = _copy_tree(base)
            try:
                for path, vals in zip(axis.paths, axis.values, strict=True):
                    _set_path(data, path, _copy_tree(vals[i]))
                study = validate_data(data, src)
            except (KeyError, StudyError):
                alone = False
                break
            for path in axis.paths:
                validated[path][1].append(None if path in whole else value_at(study, path))
        if not alone:
            break
    swept = (
        {
            p: (k, np.asarray(vals, dtype=float))
            for k, axis in enumerate(axes)
            for p, vals in zip(axis.paths, axis.values, strict=True)
        }
        if chunked
        else {}
    )
    body = template.model_dump(mode="json", exclude={"name", "description", "sweep"})
    grid = CaseGrid(
        template,
        axes,
        swept,
        _hash([code_fingerprint(), body, {p: k for p, (k, _) in swept.items()}, grid_shape(axes)]),
        {p: (k, tuple(v)) for p, (k, v) in validated.items()},
        arrays,
        chunked,
        whole,
        src,
        memo=studies,
    )
    checked = single and bool(axes)  # every combination already checked
    if alone and chunked and (_combined_ok(grid) if arrays else checked or combinations_ok(grid)):
        return grid
    if alone and not chunked:
        try:
            grid.cases()
            return grid
        except (ValueError, AssertionError, TypeError, StudyError):
            pass
    # a value or a combination fails (or the arrays' own checks refuse one): name every
    # fault at its line; if the whole studies are all valid, each is validated as a whole
    report_sweep_faults(src, axes)
    every = tuple(p for axis in axes for p in axis.paths)
    grid = replace(grid, arrays=False, chunked=False, whole=every, swept={}, memo={})
    grid.cases()
    return grid


def expand_cases(src: StudySource) -> tuple[list[SweepAxis], list[Case]]:
    """The sweep axes and every case of the study (:meth:`CaseGrid.cases`)."""
    grid = expand_grid(src)
    return grid.axes, grid.cases()


def _combined_ok(grid: CaseGrid) -> bool:
    """The checks of :meth:`Study._physical` that involve swept fields, over the whole
    grid at once (end positions against the seabed; a weightless line between fixed ends
    closer than its length), and those of the models of each swept line
    (:func:`cablestudy.study.grid_lines.line_studies`). Stiffness enters none of them."""
    t = grid.template

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
    try:
        lines = line_studies(grid)
    except (ValueError, AssertionError, TypeError):
        return False
    light = np.array([weightless(study) for study in lines])
    if light.any() and t.ends.a.kind == "fixed" and t.ends.b.kind == "fixed":
        chord = np.sqrt(sum((b - a) ** 2 for a, b in zip(pa, pb, strict=True)))
        # per case, whether its line is weightless, and its line's length (swept
        # segment lengths: each line's own, Study._physical's total_length)
        which = line_index(grid, 0, grid.shape[0]).reshape(grid.shape)
        length = np.array([study.line.total_length for study in lines], dtype=float)[which]
        if np.any(light[which] & (chord <= length)):
            return False
    # the seabed per case: that of its line's combination (a swept depth, slope)
    which = line_index(grid, 0, grid.shape[0]).reshape(grid.shape)
    envs = [study.environment for study in lines]
    if all(e.depth is None for e in envs):
        return True
    if any(e.depth is None for e in envs):
        return False  # a seabed in some cases only: never from a swept number
    depth = np.array([e.depth for e in envs], dtype=float)[which]
    # per distinct seabed as Environment.seabed_z takes it, then per case
    slope = np.array([seabed_slope(e.seabed.slope_deg, e.seabed.slope_heading_deg) for e in envs])
    rise, cos, sin = (slope[:, j][which] for j in range(3))
    for label, (x, y, z) in (("a", pa), ("b", pb)):
        if getattr(t.ends, label).kind != "fixed":
            continue
        ground = seabed_height(depth, rise, cos, sin, x, y)
        if np.any(z < ground - 1e-9 * depth):
            return False
    return _mooring_heights_ok(grid, depth)


def _mooring_heights_ok(grid: CaseGrid, depth: np.ndarray) -> bool:
    """Whether every case's mooring end (its height ``z``, swept or the template's) lies
    above its seabed (``depth`` per case), as :meth:`Study._physical` asks: z >= -depth
    (the seabed's height under an end whose position is not known is -depth)."""
    for label in "ab":
        end = getattr(grid.template.ends, label)
        if getattr(end, "kind", "") != "mooring":
            continue
        path = f"ends.{label}.z"
        z: Any = float(end.z)
        if path in grid.swept:
            axis, vals = grid.swept[path]
            shape = [1] * len(grid.shape)
            shape[axis] = len(vals)
            z = vals.reshape(shape)
        if np.any(z < -depth - 1e-9 * depth):
            return False
    return True
