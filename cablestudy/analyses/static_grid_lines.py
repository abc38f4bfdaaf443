"""The lines of an array chunk whose sweep changes the line itself
(:mod:`cablestudy.study.grid_lines`): its loads, its segments' lengths, its attachments'
positions and forces. Per distinct line its study, its
:class:`~cablestudy.statics.base.LineModel` and its cut into pieces (the very functions a
case alone goes through: :func:`cablestudy.study.problem.line_model`,
:func:`cablestudy.statics.semi_analytic_shape.make_layout`), and per case the number of
its line; from them the compiled kernels' per-case arrays (:func:`layout_arrays`) and the
groups of cases that share their points along the line (:func:`geometry_groups`: a line
of other lengths has its nodes elsewhere and its segments on other nodes).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..study.grid import CaseGrid
from ..study.grid_lines import line_index, line_studies
from .common import segment_of


@dataclass
class SweptLines:
    """The lines of a chunk whose sweep changes the line: per distinct line
    (:func:`cablestudy.study.grid_lines.line_studies`) its study and its
    :class:`~cablestudy.statics.base.LineModel` (by :func:`cablestudy.study.problem.line_model`,
    as for a case alone), and per case the number of its line."""

    studies: list[Any]
    models: list[Any]
    which: np.ndarray  # (n,) int64
    #: per distinct line its :class:`~cablestudy.statics.base.Medium`
    #: (:func:`cablestudy.study.problem.medium`: a swept seabed)
    media: list[Any]
    #: what is built once per grid (the grid's memo): the lines' layouts
    memo: dict[Any, Any] = field(default_factory=dict, repr=False)

    @classmethod
    def of(cls, grid: CaseGrid, lo: int, hi: int) -> SweptLines:
        from ..study.problem import line_model, medium

        studies = line_studies(grid)
        models = grid.memo.get("line_models")
        if models is None:
            models = grid.memo["line_models"] = [line_model(s) for s in studies]
            grid.memo["line_media"] = [medium(s) for s in studies]
        return cls(studies, models, line_index(grid, lo, hi), grid.memo["line_media"], grid.memo)

    def take(self, rows: np.ndarray) -> SweptLines:
        return SweptLines(self.studies, self.models, self.which[rows], self.media, self.memo)

    def seabeds(self) -> np.ndarray:
        """Per case the number of its seabed (cases with equal depth, slope, heading and
        friction share one)."""
        keys = [(m.depth, m.seabed_slope, m.seabed_heading, m.friction) for m in self.media]
        first = {k: i for i, k in reversed(list(enumerate(keys)))}
        return np.array([first[k] for k in keys], dtype=np.int64)[self.which]

    def stacked(self, get: Any) -> np.ndarray:
        """``get(model)`` of each case's line, stacked along a leading case axis."""
        return np.stack([np.asarray(get(m)) for m in self.models])[self.which]

    def area(self, k: np.ndarray) -> np.ndarray:
        """Per case the cross-section area [m^2] of the segment ``k`` of each point."""
        used, inverse = np.unique(self.which, return_inverse=True)
        per = np.array([[self.studies[j].line.segments[i].area for i in k] for j in used])
        return per[inverse.reshape(-1)]

    def total_length(self) -> np.ndarray:
        """Per case its line's unstretched length [m] (:attr:`LineModel.total_length`)."""
        return np.array([m.total_length for m in self.models], dtype=float)[self.which]

    def layouts(self, reverse: bool = False) -> list[Any]:
        """Per distinct line its cut into pieces (:func:`make_layout`; with ``reverse``,
        of the line described from B to A, as the contact kernel takes a line anchored
        at B), built once."""
        from ..statics.semi_analytic_shape import make_layout, reversed_line

        key = "line_layouts_reversed" if reverse else "line_layouts"
        found = self.memo.get(key)
        if found is None or len(found) != len(self.models):
            found = self.memo[key] = [
                make_layout(reversed_line(m) if reverse else m) for m in self.models
            ]
        return found

    def pieces(self) -> np.ndarray:
        """Per case a key of how many pieces its line is cut into, forwards and
        backwards (cases of one key stack into the kernels' arrays)."""
        fwd = np.array([len(la.ell) for la in self.layouts()], dtype=np.int64)
        back = np.array([len(la.ell) for la in self.layouts(True)], dtype=np.int64)
        return (fwd * (1 + int(back.max(initial=0))) + back)[self.which]

    def free_ends(self, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
        """Per case whether its line's ends A and B are free
        (:func:`cablestudy.analyses.static.tangent_ends`), built once per line."""
        from .static import tangent_ends

        key = ("line_free_ends", tolerance)
        found = self.memo.get(key)
        if found is None or found.shape[0] != len(self.studies):
            each = [tangent_ends(s.line, tolerance, np.zeros(1)) for s in self.studies]
            found = self.memo[key] = np.array(
                [(e["free_a"], e["free_b"]) for e in each], dtype=bool
            ).reshape(len(self.studies), 2)
        return found[self.which, 0], found[self.which, 1]

    def geometry(self) -> np.ndarray:
        """Per case the number of the first line with its segments' lengths (cases of
        one number have their nodes at the same arc lengths and on the same segments)."""
        keys = [m.length.tobytes() for m in self.models]
        first = {k: i for i, k in reversed(list(enumerate(keys)))}
        return np.array([first[k] for k in keys], dtype=np.int64)[self.which]


def layout_arrays(
    line: Any, ea: np.ndarray, lines: SweptLines | None, *, reverse: bool = False
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The compiled kernels' arrays of the cases of a chunk: per case its pieces'
    lengths ``ell`` (N, P), stiffnesses ``EA`` (N, P), weights in the fluid ``w``
    (N, P), point loads ``point`` (N, P + 1, 3) and cuts ``bounds`` (N, P + 1): those
    :func:`cablestudy.statics.batch_kernels._solve_group` (and, with ``reverse``, the
    contact kernel on the line described from B) builds from each case's own line, bit
    for bit. ``line``: the template's model (its make-up: segments and attachments);
    ``ea``: the segment stiffnesses per case (N, n_segments); ``lines``: each case's own
    line (all cut into the same number of pieces: :meth:`SweptLines.pieces`), else the
    template's for all."""
    N = len(ea)
    if line.length.size == 1 and line.attachment_s.size == 0:  # one piece, either way
        if lines is None:
            ell = np.full((N, 1), line.length[0])
            w = np.full((N, 1), line.weight[0])
        else:
            ell = lines.stacked(lambda m: m.length[:1])
            w = lines.stacked(lambda m: m.weight[:1])
        bounds = np.empty((N, 2))
        bounds[:, 0] = 0.0
        bounds[:, 1] = ell[:, 0]
        return ell, np.ascontiguousarray(ea[:, :1], dtype=float), w, np.zeros((N, 2, 3)), bounds
    from ..statics.semi_analytic_shape import make_layout, reversed_line

    if lines is None:
        lays = [make_layout(reversed_line(line) if reverse else line)]
        which = np.zeros(N, dtype=np.int64)
    else:
        lays, which = lines.layouts(reverse), lines.which
    used, inverse = np.unique(which, return_inverse=True)
    inverse = inverse.reshape(-1)

    def per_case(name: str) -> np.ndarray:
        return np.stack([getattr(lays[j], name) for j in used])[inverse]

    seg = per_case("segment")
    EA = np.take_along_axis(ea[:, ::-1] if reverse else ea, seg, axis=1).astype(float)
    return per_case("ell"), EA, per_case("weight"), per_case("point"), per_case("bounds")


def geometry_groups(s: np.ndarray, lines: SweptLines | None) -> list[np.ndarray] | None:
    """The cases of a chunk (``s`` (n, m): each case's arc lengths) in groups that share
    their arc lengths and their segments' lengths (one :func:`profile_quantities` call
    each), or None when all cases do."""
    same = np.array_equal(s, np.broadcast_to(s[0], s.shape))
    if lines is None:
        return None if same else _by_rows(s, np.arange(len(s)))
    geometry = lines.geometry()
    if same and np.all(geometry == geometry[0]):
        return None
    groups = []
    for g in np.unique(geometry):
        groups.extend(_by_rows(s, np.flatnonzero(geometry == g)))
    return groups


def _by_rows(s: np.ndarray, rows: np.ndarray) -> list[np.ndarray]:
    """``rows`` in groups of equal rows of ``s`` (in order)."""
    sub = s[rows]
    if np.array_equal(sub, np.broadcast_to(sub[0], sub.shape)):
        return [rows]
    _, inverse = np.unique(sub, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    return [rows[inverse == u] for u in np.unique(inverse)]


def node_segments(s: np.ndarray, template: Any, lines: SweptLines | None) -> np.ndarray:
    """Per case and node (``s`` (n, m) [m]) the index of the segment it lies on, on the
    case's own line (:func:`cablestudy.analyses.common.segment_of`, as a case alone)."""
    if lines is None:
        return np.broadcast_to(segment_of(template.line.segments, s[0]), s.shape)
    out = np.empty(s.shape, dtype=np.int64)
    geometry = lines.geometry()
    for g in np.unique(geometry):
        rows = np.flatnonzero(geometry == g)
        segs = lines.studies[lines.which[rows[0]]].line.segments
        out[rows] = segment_of(segs, s[rows])
    return out
