"""The quasi-static database (aqwa seed 5.8.1.4; issue 12 item 7).

"To avoid the iterative calculation of the mooring forces, the program establishes a
database covering all of the expected configurations of the cable": the static line of
a case is solved for end B at every point of a grid of positions relative to end A
(fixed), in the vertical plane through A along the heading from A to the study's end B,
and the end forces, end tensions, largest tension and laid length are tabulated
(:func:`solve_database`). Two grids (``analysis.database.grid``):

- ``cartesian`` (default): horizontal distance r >= 0 and height difference
  h = z_B - z_A, on the dimensions ``horizontal_distance`` and ``height_difference``;
- ``radial``: for lines off the seabed, as the seed has it ("the database uses a radial
  coordinate system in which Number of X Coordinates becomes the number of radial
  distances and the Number of Vertical Partitions is the number of angular
  positions"; the cable "is considered to be submerged in water of infinite depth"):
  the distance d = |r_B - r_A| > 0 and the angle a of the chord A-B above the
  horizontal, so r = d cos a, h = d sin a, on the dimensions ``distance`` and ``angle``.

They are written to the study's dataset (``database_*``, ``database_radial_*``) and to
a dataset of their own (:mod:`cablestudy.run.database_file`).

:class:`QuasiStaticDatabase` interpolates the table: bicubic Hermite patches in the
grid's own coordinates whose node derivatives (d/dp, d/dq, d2/dp dq) are those of the
not-a-knot bicubic spline through the nodes
(:class:`scipy.interpolate.RectBivariateSpline`), so the interpolant and its first
derivatives are continuous (C1) and the error falls as h^4 on a smooth table
(tension_max = max over the line has a kink where the largest tension moves from one
place to another, and laid_length one where the line lifts off the seabed: there the
error is first order in h). A radial database is looked up by (r, h) converted to
(d, a): a smooth map away from d = 0, which the grid excludes, so the lookup is C1 in
(r, h) as well. One lookup evaluates all quantities at once (a few microseconds); a
point outside the grid is refused with the grid's range.

The build checks every cell (:func:`check_cells`, the table ``cell_check``): one that
straddles the taut chord (end distance = the line's length, a kink in every table) or
whose patches at its centre are off a direct solve there by more than
:data:`CELL_TOLERANCE` is flagged, the case warns (:func:`cell_warning`), and a lookup in
a flagged cell is refused naming it (``allow_flagged`` returns it).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..statics import STATIC_SOLVERS, EndCondition
from ..statics.limits import apply_limits
from ..study.problem import static_limits, static_problem
from .variables import DATABASE_LAYOUTS, DATABASE_QUANTITIES

if TYPE_CHECKING:
    import xarray as xr

    from ..study import Study
    from ..study.cases import Case
    from ..study.loader import StudySource

#: the interpolated quantities (the tables but the per-point status)
QUANTITIES = tuple(q for q in DATABASE_QUANTITIES if q != "status")


def heading(study: Study) -> float:
    """Heading [rad from +x] of the vertical plane of the database: from end A towards
    the study's end B (a fixed end's position, else its force's horizontal direction;
    +x when neither has a horizontal part)."""
    a, b = study.ends.a, study.ends.b
    if b.kind == "fixed":
        dx, dy = b.position[0] - a.position[0], b.position[1] - a.position[1]  # type: ignore[union-attr]
    else:
        dx, dy = b.force[0], b.force[1]  # type: ignore[union-attr]
    if math.hypot(dx, dy) == 0.0:
        return 0.0
    return math.atan2(dy, dx)


def database_problems(case: Case, src: StudySource) -> list[str]:
    """Config errors of ``analysis.database`` (raised before any work)."""
    study = case.study
    db = study.analysis.database
    if db is None:
        return []
    where = src.line_of(("analysis", "database")) or ""
    out = []
    if study.line.is_spring:
        out.append(
            f"{where}: analysis.database: a kind: spring line's tension is closed-form in "
            "the end distance (the law of distance - length): it needs no database; "
            "allowed: omit analysis.database, or use kind: catenary"
        )
    if study.ends.a.kind != "fixed":
        out.append(
            f"{where}: analysis.database: end a must be 'fixed' (the database moves end B "
            f"relative to it); got {study.ends.a.kind!r}"
        )
        return out
    env = study.environment
    if db.grid == "radial" and env.depth is not None:
        line = src.line_of(("analysis", "database", "grid")) or where
        out.append(
            f"{line}: analysis.database.grid: 'radial' is the aqwa seed's grid for a line "
            "off the seabed, in water of infinite depth; got environment.depth "
            f"{env.depth:g} m; allowed: grid 'radial' without environment.depth, or grid "
            "'cartesian' (which tabulates a line touching the seabed)"
        )
        return out
    if env.depth is not None:
        assert db.horizontal_distance is not None and db.height_difference is not None
        za = study.ends.a.position[2]  # type: ignore[union-attr]
        th = heading(study)
        ax, ay = study.ends.a.position[0], study.ends.a.position[1]  # type: ignore[union-attr]
        worst = math.inf
        for r in (db.horizontal_distance.start, db.horizontal_distance.stop):
            x, y = ax + r * math.cos(th), ay + r * math.sin(th)
            ground = env.seabed_z(x, y)
            worst = min(worst, za + db.height_difference.start - ground)
        if worst < -1e-9 * env.depth:
            line = src.line_of(("analysis", "database", "height_difference", "start")) or where
            out.append(
                f"{line}: analysis.database.height_difference.start: puts end B "
                f"{-worst:.6g} m below the seabed; allowed: heights that keep end B above "
                "the seabed over the whole grid"
            )
    return out


def grid_values(study: Study) -> tuple[np.ndarray, np.ndarray]:
    """The two axes of the database grid in SI: (horizontal distance [m], height
    difference [m]) for grid cartesian, (distance [m], angle [rad]) for grid radial."""
    db = study.analysis.database
    assert db is not None
    first, second = db.axes
    p, q = np.asarray(first.values), np.asarray(second.values)
    return (p, np.radians(q)) if db.grid == "radial" else (p, q)


def grid_to_plane(grid: str, p: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """End B's horizontal distance and height difference from end A [m] at the grid
    coordinates (p, q) (see :func:`grid_values`)."""
    if grid == "radial":
        return p * np.cos(q), p * np.sin(q)
    return p, q


def solve_database(study: Study, deadline: float | None = None) -> dict[str, np.ndarray]:
    """The database of one case: the outputs of its layout
    (:data:`cablestudy.analyses.variables.DATABASE_LAYOUTS`), ``database_*`` on
    (horizontal_distance, height_difference[, component]) or ``database_radial_*`` on
    (distance, angle[, component]), the grid values and the heading."""
    db = study.analysis.database
    assert db is not None
    layout = DATABASE_LAYOUTS[db.grid]
    base = static_problem(study)
    solver = STATIC_SOLVERS[study.analysis.static.method]
    # each point is held to its laws' checked strain range as a study of that point is
    # (it failed there, but was tabulated with status 0); the break limits are not
    # applied: a table of the tensions is what the user compares with them
    limits = static_limits(study)
    limits = replace(limits, break_tension=np.full_like(limits.break_tension, np.inf))
    rA = np.asarray(base.end_a.position, dtype=float)
    th = heading(study)
    e = np.array([math.cos(th), math.sin(th), 0.0])
    P, Q = grid_values(study)
    R, Hh = np.broadcast_arrays(*grid_to_plane(db.grid, P[:, None], Q[None, :]))
    shape = (len(P), len(Q))
    out = {
        "force_a": np.full((*shape, 3), np.nan),
        "force_b": np.full((*shape, 3), np.nan),
        "tension_a": np.full(shape, np.nan),
        "tension_b": np.full(shape, np.nan),
        "tension_max": np.full(shape, np.nan),
        "laid_length": np.full(shape, np.nan),
        "status": np.zeros(shape, dtype=np.int64),
    }
    for i in range(shape[0]):
        for j in range(shape[1]):
            rB = rA + R[i, j] * e + np.array([0.0, 0.0, Hh[i, j]])
            prob = replace(base, end_b=EndCondition(kind="fixed", position=rB))
            res = apply_limits(solver.solve(prob, deadline=deadline).check_finite(), limits)
            out["status"][i, j] = res.status
            if res.status != 0:
                continue
            out["force_a"][i, j] = res.force_a
            out["force_b"][i, j] = res.force_b
            out["tension_a"][i, j] = np.linalg.norm(res.force_a)
            out["tension_b"][i, j] = np.linalg.norm(res.force_b)
            out["tension_max"][i, j] = np.max(res.tension)
            out["laid_length"][i, j] = res.laid_length
    out["cell_check"] = check_cells(
        db.grid,
        P,
        Q,
        out,
        float(sum(seg.length for seg in study.line.segments)),
        lambda r, h: apply_limits(
            _solve_at(solver, base, rA + r * e + np.array([0.0, 0.0, h]), deadline), limits
        ),
    )
    data = {f"{layout.prefix}{k}": v for k, v in out.items()}
    data[layout.grid_variables[0]] = P
    data[layout.grid_variables[1]] = Q
    data["database_heading"] = np.asarray(th)
    return data


#: codes of ``cell_check`` (the cell whose lower corner is the grid point, see
#: :func:`check_cells`): bits, 0 verified
CELL_NO_CELL = -1  # the grid's last row or column (no cell), or not checked
CELL_TAUT_CHORD = 1  # the cell straddles the taut chord (distance = the line's length)
CELL_OFF = 2  # the patch at the cell's centre is off a direct solve by > CELL_TOLERANCE
#: the largest error of a patch at a cell's centre against a direct solve, relative to
#: the largest end tension at the cell's corners (the line's length for laid_length)
#: before the cell is flagged: 1 %, 10^3..10^4 times the error of a smooth table's
#: patches at 5..17 points a side (guide: 1e-3..4e-6 of the largest end tension), so a
#: flagged cell is one the patches cannot follow (a kink inside or near it), not one a
#: smooth table resolves coarsely
CELL_TOLERANCE = 1e-2


def _solve_at(solver: Any, base: Any, rB: np.ndarray, deadline: float | None) -> Any:
    res = solver.solve(
        replace(base, end_b=EndCondition(kind="fixed", position=rB)), deadline=deadline
    )
    return res.check_finite()


def _span(lo: float, hi: float) -> tuple[float, float]:
    """The smallest and largest |x| over the interval [lo, hi]."""
    small = 0.0 if lo <= 0.0 <= hi else min(abs(lo), abs(hi))
    return small, max(abs(lo), abs(hi))


def taut_chord_cells(grid: str, P: np.ndarray, Q: np.ndarray, length: float) -> np.ndarray:
    """(n1 - 1, n2 - 1) bool: the cells whose end distance |r_B - r_A| crosses the line's
    unstretched ``length`` [m] (slack on one side, taut on the other: the tension turns
    to rising with EA there, a kink in every table the patches cannot follow)."""
    n1, n2 = len(P) - 1, len(Q) - 1
    out = np.zeros((n1, n2), dtype=bool)
    for i in range(n1):
        for j in range(n2):
            if grid == "radial":
                lo, hi = P[i], P[i + 1]
            else:
                (r0, r1), (h0, h1) = _span(P[i], P[i + 1]), _span(Q[j], Q[j + 1])
                lo, hi = math.hypot(r0, h0), math.hypot(r1, h1)
            out[i, j] = lo < length < hi
    return out


def check_cells(
    grid: str,
    P: np.ndarray,
    Q: np.ndarray,
    tables: dict[str, np.ndarray],
    length: float,
    solve: Any,
) -> np.ndarray:
    """``cell_check`` (n1, n2) int: per grid point the check of the cell of which it is
    the lower corner (:data:`CELL_NO_CELL` on the last row and column):
    :data:`CELL_TAUT_CHORD` where the cell straddles the taut chord
    (:func:`taut_chord_cells`), plus :data:`CELL_OFF` where the patches at the cell's
    centre are off a direct solve there (``solve(r, h)`` -> StaticResult) by more than
    :data:`CELL_TOLERANCE` (a negative interpolated tension always is), 0 verified.
    Not checked (-1 throughout) when a grid point failed: the lookup refuses such a
    table anyway."""
    out = np.full((len(P), len(Q)), CELL_NO_CELL, dtype=np.int64)
    quantities = {k: v for k, v in tables.items() if k in QUANTITIES}
    if any(not np.all(np.isfinite(v)) for v in quantities.values()):
        return out
    db = QuasiStaticDatabase.from_arrays(P, Q, quantities, grid=grid)
    names = db.names
    taut = taut_chord_cells(grid, P, Q, length)
    ends = np.maximum(tables["tension_a"], tables["tension_b"])
    for i in range(len(P) - 1):
        for j in range(len(Q) - 1):
            p, q = 0.5 * (P[i] + P[i + 1]), 0.5 * (Q[j] + Q[j + 1])
            got = db.lookup_grid(p, q)
            code = CELL_TAUT_CHORD if taut[i, j] else 0
            r, h = grid_to_plane(grid, np.asarray(p), np.asarray(q))
            res = solve(float(r), float(h))
            scale = float(np.max(ends[i : i + 2, j : j + 2]))
            if res.status != 0 or not scale > 0.0:
                code |= CELL_OFF  # not verified: no direct solve to compare with
            else:
                ref = {
                    "force_a": res.force_a,
                    "force_b": res.force_b,
                    "tension_a": np.linalg.norm(res.force_a),
                    "tension_b": np.linalg.norm(res.force_b),
                    "tension_max": np.max(res.tension),
                    "laid_length": res.laid_length,
                }
                for (name, k), value in zip(names, got, strict=True):
                    want = ref[name] if k is None else ref[name][k]
                    tol = CELL_TOLERANCE * (length if name == "laid_length" else scale)
                    negative = name.startswith("tension") and value < 0.0
                    if negative or not abs(value - want) <= tol:
                        code |= CELL_OFF
                        break
            out[i, j] = code
    return out


def cell_warning(data: dict[str, Any], length: float) -> str:
    """The case's warning about its database's failed grid points, else its flagged cells
    (:func:`check_cells`), or "" when every point solved and every cell is verified (or
    the case holds no database)."""
    for kind, layout in DATABASE_LAYOUTS.items():
        check = data.get(f"{layout.prefix}cell_check")
        if check is None:
            continue
        P, Q = (np.asarray(data[v]) for v in layout.grid_variables)
        status = np.asarray(data[f"{layout.prefix}status"])
        failed = status != 0
        if np.any(failed):  # the cells are not checked then (-1): say why instead
            i, j = np.argwhere(failed)[0]
            codes = ", ".join(str(c) for c in sorted(set(status[failed].tolist())))
            return (
                f"quasi-static database: {int(failed.sum())} of {status.size} grid points "
                f"failed (static status {codes}; NaN in their tables), e.g. "
                f"{_describe(kind, float(P[i]), float(Q[j]))}: a lookup refuses the "
                "database; solve that point as a study of its own for the solver's message, "
                "or shrink the grid to where the line solves"
            )
        return _flag_summary(kind, P, Q, np.asarray(check)[:-1, :-1], length)
    return ""


def _flag_summary(grid: str, P: np.ndarray, Q: np.ndarray, cells: np.ndarray, length: float) -> str:
    flagged = cells > 0
    if not np.any(flagged):
        return ""
    taut = int(np.count_nonzero(cells & CELL_TAUT_CHORD))
    off = int(np.count_nonzero(cells & CELL_OFF))
    i, j = np.argwhere(cells & CELL_OFF if off else flagged)[0]
    crosses = (
        f"{taut} straddle the taut chord (end distance = the line's length {length:g} m: "
        "its kink spoils the patches' slopes over the whole grid), "
        if taut
        else ""
    )
    return (
        f"quasi-static database: {int(flagged.sum())} of {cells.size} cells flagged ({crosses}"
        f"{off} are off a direct solve at their centre by more than {CELL_TOLERANCE:.0%} of "
        f"the cell's end tension, e.g. {_cell(grid, P, Q, i, j)}), and a lookup in a flagged "
        "cell is refused: keep the grid on one side of the taut chord"
    )


def _cell(grid: str, P: Any, Q: Any, i: int, j: int) -> str:
    if grid == "radial":
        a0, a1 = (f"{math.degrees(a):.6g}" for a in (Q[j], Q[j + 1]))
        return f"cell distance {P[i]:g} .. {P[i + 1]:g} m, angle {a0} .. {a1} deg"
    return (
        f"cell horizontal distance {P[i]:g} .. {P[i + 1]:g} m, height difference "
        f"{Q[j]:g} .. {Q[j + 1]:g} m"
    )


@dataclass
class QuasiStaticDatabase:
    """Interpolator of a quasi-static database (see the module docstring).

    ``first`` (n1,), ``second`` (n2,) the grid in SI: horizontal distance [m] and height
    difference [m] (``grid`` 'cartesian') or distance [m] and angle [rad] ('radial');
    ``names`` the quantities; ``values``, ``d_1``, ``d_2``, ``d_12`` (Q, n1, n2) the
    nodal values and derivatives of the stacked quantities (vector components as
    separate rows).
    """

    first: np.ndarray
    second: np.ndarray
    names: list[tuple[str, int | None]]
    values: np.ndarray
    d_1: np.ndarray
    d_2: np.ndarray
    d_12: np.ndarray
    heading: float = 0.0
    grid: str = "cartesian"
    #: monomial coefficients of each cell's bicubic, (Q, n1 - 1, n2 - 1, 4, 4): value =
    #: sum_mn C[m, n] t^m u^n with t, u the position in the cell in [0, 1]
    coefficients: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0, 4, 4)))
    #: per grid point the check of the cell of which it is the lower corner
    #: (:func:`check_cells`), None for a database written before the check
    cell_check: np.ndarray | None = None
    #: lookups in a flagged cell: refused (False, the default) or returned (True)
    allow_flagged: bool = False

    def __post_init__(self) -> None:
        if self.grid not in DATABASE_LAYOUTS:
            raise ValueError(
                f"grid {self.grid!r} is not a database grid; allowed: {', '.join(DATABASE_LAYOUTS)}"
            )
        P, Q = self.first, self.second
        hp, hq = np.diff(P), np.diff(Q)
        # Hermite basis as monomial coefficients in t: values (node 0, node 1) and
        # derivatives (times the cell size)
        H0 = np.array([[1.0, 0.0, -3.0, 2.0], [0.0, 0.0, 3.0, -2.0]])
        H1 = np.array([[0.0, 1.0, -2.0, 1.0], [0.0, 0.0, -1.0, 1.0]])
        Pp = np.broadcast_to(H0, (len(hp), 2, 4))
        Dp = H1[None] * hp[:, None, None]
        Pq = np.broadcast_to(H0, (len(hq), 2, 4))
        Dq = H1[None] * hq[:, None, None]

        def cells(A: np.ndarray) -> np.ndarray:
            # (Q, n1-1, n2-1, 2, 2): the four corner values of every cell
            return np.stack(
                (
                    np.stack((A[:, :-1, :-1], A[:, :-1, 1:]), -1),
                    np.stack((A[:, 1:, :-1], A[:, 1:, 1:]), -1),
                ),
                -2,
            )

        C = np.einsum("qijab,iam,jbn->qijmn", cells(self.values), Pp, Pq)
        C += np.einsum("qijab,iam,jbn->qijmn", cells(self.d_1), Dp, Pq)
        C += np.einsum("qijab,iam,jbn->qijmn", cells(self.d_2), Pp, Dq)
        C += np.einsum("qijab,iam,jbn->qijmn", cells(self.d_12), Dp, Dq)
        self.coefficients = np.ascontiguousarray(C)
        # per cell a (Q, 16) matrix acting on (t^m u^n) flattened: one matrix-vector
        # product per lookup
        self._cells = np.ascontiguousarray(
            C.transpose(1, 2, 0, 3, 4).reshape(C.shape[1], C.shape[2], C.shape[0], 16)
        )
        self._p = P.tolist()
        self._q = Q.tolist()
        self._p_array = np.ascontiguousarray(P, dtype=float)
        self._q_array = np.ascontiguousarray(Q, dtype=float)

    @classmethod
    def from_arrays(
        cls,
        first: np.ndarray,
        second: np.ndarray,
        tables: dict[str, np.ndarray],
        heading: float = 0.0,
        *,
        grid: str = "cartesian",
        cell_check: np.ndarray | None = None,
    ) -> QuasiStaticDatabase:
        """Build from the grid (SI: [m], and [m] or [rad], see the class) and tables
        (name -> (n1, n2) or (n1, n2, 3)); every table must be finite (a failed grid
        point cannot be interpolated across)."""
        from scipy.interpolate import RectBivariateSpline

        first = np.asarray(first, dtype=float)
        second = np.asarray(second, dtype=float)
        names: list[tuple[str, int | None]] = []
        rows = []
        for name, arr in tables.items():
            arr = np.asarray(arr, dtype=float)
            if arr.ndim == 3:
                for k in range(arr.shape[2]):
                    names.append((name, k))
                    rows.append(arr[:, :, k])
            else:
                names.append((name, None))
                rows.append(arr)
        V = np.stack(rows)
        bad = ~np.isfinite(V).all(axis=0)
        if np.any(bad):
            i, j = np.argwhere(bad)[0]
            raise ValueError(
                f"the database has {int(bad.sum())} failed grid points (e.g. "
                f"{_describe(grid, first[i], second[j])}); it cannot be interpolated "
                "across them: shrink the grid to where the line solves"
            )
        d1, d2, d12 = np.empty_like(V), np.empty_like(V), np.empty_like(V)
        for q in range(V.shape[0]):
            spl = RectBivariateSpline(first, second, V[q], kx=3, ky=3, s=0)
            d1[q] = spl(first, second, dx=1)
            d2[q] = spl(first, second, dy=1)
            d12[q] = spl(first, second, dx=1, dy=1)
        return cls(first, second, names, V, d1, d2, d12, heading, grid, cell_check=cell_check)

    @classmethod
    def from_dataset(cls, ds: xr.Dataset) -> QuasiStaticDatabase:
        """From a dataset holding one case's database: the study's dataset
        (``database_*`` or ``database_radial_*``) or the database's own
        (``<name>.database.nc``, :mod:`cablestudy.run.database_file`). Select a case first
        with ``ds.sel(...)`` when a sweep dimension holds more than one value (one value
        is its case)."""
        grid, prefix = _layout_of(ds)
        layout = DATABASE_LAYOUTS[grid]
        extra = [d for d in ds[f"{prefix}tension_a"].dims if d not in layout.dims]
        ds = ds.isel({d: 0 for d in extra if ds.sizes[d] == 1})  # one value: that case
        extra = [d for d in extra if ds.sizes.get(d, 1) > 1]
        if extra:
            raise ValueError(
                f"the dataset holds one database per case of the sweep dimensions {extra}; "
                "select one case (e.g. --sel DIM=VALUE)"
            )
        tables = {
            name: ds[f"{prefix}{name}"].transpose(*layout.dims, ...).values for name in QUANTITIES
        }
        standalone = prefix == ""
        axes = []
        for dim, var in zip(layout.dims, layout.grid_variables, strict=True):
            # a coordinate when every case has the same grid, else a variable per case
            name = f"{dim}_grid" if standalone else var
            axes.append(ds[dim].values if dim in ds.coords else ds[name].values)
        head = "heading" if standalone else "database_heading"
        th = float(ds[head].values) if head in ds else 0.0
        check = f"{prefix}cell_check"
        cells = ds[check].transpose(*layout.dims).values if check in ds else None
        return cls.from_arrays(axes[0], axes[1], tables, th, grid=grid, cell_check=cells)

    def to_grid(self, horizontal_distance: float, height_difference: float) -> tuple[float, float]:
        """The grid coordinates of end B at ``horizontal_distance`` [m] and
        ``height_difference`` [m] from end A: themselves (cartesian), or the distance
        [m] and the angle [rad] above the horizontal (radial)."""
        if self.grid == "radial":
            return (
                math.hypot(horizontal_distance, height_difference),
                math.atan2(height_difference, horizontal_distance),
            )
        return horizontal_distance, height_difference

    def lookup_grid(self, p: float, q: float) -> np.ndarray:
        """All quantities at once as one array, in the order of ``names``, at the grid
        coordinates (p, q) (the fast path of :meth:`lookup`: the range check here, then one
        compiled call: the cell search and its bicubic patch).

        Raises
        ------
        ValueError
            outside the grid, with the grid's range; in a cell flagged at the build
            (:func:`check_cells`), naming it, unless ``allow_flagged``.
        """
        P, Q = self._p, self._q
        if not (P[0] <= p <= P[-1] and Q[0] <= q <= Q[-1]):
            if self.grid == "radial":
                r, h = p * math.cos(q), p * math.sin(q)
                where = f"horizontal distance {r:g} m, height difference {h:g} m; "
            else:
                where = ""
            raise ValueError(
                f"position ({where}{_describe(self.grid, p, q)}) lies outside the "
                f"database; allowed: {_range(self.grid, P, Q)}"
            )
        if self.cell_check is not None and not self.allow_flagged:
            self._refuse_flagged(p, q)
        from .database_kernel import evaluate_cell

        return evaluate_cell(self._cells, self._p_array, self._q_array, p, q)

    def flagged_cell(self, p: float, q: float) -> str:
        """The description of the flagged cell (:func:`check_cells`) holding the grid
        coordinates (p, q) inside the grid, "" where it is verified or not checked."""
        if self.cell_check is None:
            return ""
        i = min(max(bisect.bisect_right(self._p, p) - 1, 0), len(self._p) - 2)
        j = min(max(bisect.bisect_right(self._q, q) - 1, 0), len(self._q) - 2)
        code = int(self.cell_check[i, j])
        if code <= 0:
            return ""
        why = []
        if code & CELL_TAUT_CHORD:
            why.append("it straddles the taut chord (end distance = the line's length)")
        if code & CELL_OFF:
            why.append(
                f"its patch at the centre is off a direct solve by more than {CELL_TOLERANCE:.0%} "
                "of the end tension"
            )
        return f"{_cell(self.grid, self._p, self._q, i, j)}: " + " and ".join(why)

    def _refuse_flagged(self, p: float, q: float) -> None:
        cell = self.flagged_cell(p, q)
        if cell:
            raise ValueError(
                f"position ({_describe(self.grid, p, q)}) lies in a flagged cell of the "
                f"database, {cell}: the bicubic patches cannot follow the table there and "
                "the lookup can be wrong by any amount; rebuild with a grid on one side of "
                "the taut chord (all end distances below, or all above, the line's length), "
                "or solve this position directly"
            )

    def lookup_array(self, horizontal_distance: float, height_difference: float) -> np.ndarray:
        """:meth:`lookup` as one array in the order of ``names``."""
        return self.lookup_grid(*self.to_grid(horizontal_distance, height_difference))

    def lookup(self, horizontal_distance: float, height_difference: float) -> dict[str, Any]:
        """Interpolated quantities at end B ``horizontal_distance`` [m] horizontally
        from end A (along the database's heading) and ``height_difference`` [m] above
        it, whatever the grid: force_a, force_b [N] (3,), tension_a, tension_b,
        tension_max [N], laid_length [m].

        Raises
        ------
        ValueError
            outside the grid, with the grid's range; in a cell flagged at the build
            (:func:`check_cells`), naming it, unless ``allow_flagged``.
        """
        v = self.lookup_array(horizontal_distance, height_difference)
        out: dict[str, Any] = {}
        for (name, k), val in zip(self.names, v, strict=True):
            if k is None:
                out[name] = float(val)
            else:
                out.setdefault(name, np.zeros(3))[k] = val
        return out


def _describe(grid: str, p: float, q: float) -> str:
    if grid == "radial":
        return f"distance {p:g} m, angle {math.degrees(q):.10g} deg"
    return f"horizontal distance {p:g} m, height difference {q:g} m"


def _range(grid: str, P: list[float], Q: list[float]) -> str:
    if grid == "radial":
        a0, a1 = (f"{math.degrees(a):.10g}" for a in (Q[0], Q[-1]))
        return f"distance {P[0]:g} .. {P[-1]:g} m and angle {a0} .. {a1} deg"
    return (
        f"horizontal distance {P[0]:g} .. {P[-1]:g} m and height difference {Q[0]:g} .. {Q[-1]:g} m"
    )


def _layout_of(ds: xr.Dataset) -> tuple[str, str]:
    """(grid kind, variable prefix) of the database in ``ds``."""
    grid = ds.attrs.get("database_grid")
    if grid in DATABASE_LAYOUTS and "tension_a" in ds:
        return str(grid), ""
    for kind, layout in DATABASE_LAYOUTS.items():
        if f"{layout.prefix}tension_a" in ds:
            return kind, layout.prefix
    raise ValueError("the dataset holds no quasi-static database (analysis.database)")


def open_database(path: str, **sel: Any) -> QuasiStaticDatabase:
    """The database of a result file, the study's (``<name>.nc``) or its own
    (``<name>.database.nc``) (``sel``: one case of a swept study, by dimension name and
    value)."""
    import xarray as xr

    ds = xr.load_dataset(path)
    if sel:
        ds = ds.sel(sel)
    return QuasiStaticDatabase.from_dataset(ds)
