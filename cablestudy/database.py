"""The quasi-static database (aqwa seed 5.8.1.4; issue 12 item 7).

"To avoid the iterative calculation of the mooring forces, the program establishes a
database covering all of the expected configurations of the cable": the static line of
a case is solved for end B at every point of a grid of positions relative to end A
(fixed) -- horizontal distance r >= 0 along the heading from A to the study's end B, and
height difference h = z_B - z_A -- and the end forces, end tensions, largest tension and
laid length are tabulated (:func:`solve_database`). They are written to the study's
dataset on the dimensions ``horizontal_distance`` and ``height_difference``.

:class:`QuasiStaticDatabase` interpolates the table: bicubic Hermite patches whose node
derivatives (d/dr, d/dh, d2/dr dh) are those of the not-a-knot bicubic spline through
the nodes (:class:`scipy.interpolate.RectBivariateSpline`), so the interpolant and its
first derivatives are continuous (C1) and the error falls as h^4 on a smooth table
(tension_max = max over the line has a kink where the largest tension moves from one
place to another, and laid_length one where the line lifts off the seabed: there the
error is first order in h). One
lookup evaluates all quantities at once (a few microseconds); a point outside the grid
is refused with the grid's range.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from .problem import static_problem
from .statics import STATIC_SOLVERS, EndCondition

if TYPE_CHECKING:
    import xarray as xr

    from .cases import Case
    from .config import Study
    from .config.loader import StudySource

#: tabulated quantities: output name -> (name in the interpolator, units)
QUANTITIES = ("force_a", "force_b", "tension_a", "tension_b", "tension_max", "laid_length")


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
    if env.depth is not None:
        za = study.ends.a.position[2]  # type: ignore[union-attr]
        rise = math.tan(math.radians(env.seabed.slope_deg))
        th = heading(study)
        ax, ay = study.ends.a.position[0], study.ends.a.position[1]  # type: ignore[union-attr]
        worst = math.inf
        for r in (db.horizontal_distance.start, db.horizontal_distance.stop):
            x, y = ax + r * math.cos(th), ay + r * math.sin(th)
            hd = math.radians(env.seabed.slope_heading_deg)
            ground = -env.depth + rise * (x * math.cos(hd) + y * math.sin(hd))
            worst = min(worst, za + db.height_difference.start - ground)
        if worst < -1e-9 * env.depth:
            line = src.line_of(("analysis", "database", "height_difference", "start")) or where
            out.append(
                f"{line}: analysis.database.height_difference.start: puts end B "
                f"{-worst:.6g} m below the seabed; allowed: heights that keep end B above "
                "the seabed over the whole grid"
            )
    return out


def solve_database(study: Study, deadline: float | None = None) -> dict[str, np.ndarray]:
    """The database of one case: outputs named ``database_*`` on (horizontal_distance,
    height_difference[, component]) and the grid values."""
    db = study.analysis.database
    assert db is not None
    base = static_problem(study)
    solver = STATIC_SOLVERS[study.analysis.static.method]
    rA = np.asarray(base.end_a.position, dtype=float)
    th = heading(study)
    e = np.array([math.cos(th), math.sin(th), 0.0])
    R = np.asarray(db.horizontal_distance.values)
    Hh = np.asarray(db.height_difference.values)
    shape = (len(R), len(Hh))
    out = {
        "force_a": np.full((*shape, 3), np.nan),
        "force_b": np.full((*shape, 3), np.nan),
        "tension_a": np.full(shape, np.nan),
        "tension_b": np.full(shape, np.nan),
        "tension_max": np.full(shape, np.nan),
        "laid_length": np.full(shape, np.nan),
        "status": np.zeros(shape),
    }
    for i, r in enumerate(R):
        for j, h in enumerate(Hh):
            rB = rA + r * e + np.array([0.0, 0.0, h])
            prob = replace(base, end_b=EndCondition(kind="fixed", position=rB))
            res = solver.solve(prob, deadline=deadline).check_finite()
            out["status"][i, j] = res.status
            if res.status != 0:
                continue
            out["force_a"][i, j] = res.force_a
            out["force_b"][i, j] = res.force_b
            out["tension_a"][i, j] = np.linalg.norm(res.force_a)
            out["tension_b"][i, j] = np.linalg.norm(res.force_b)
            out["tension_max"][i, j] = np.max(res.tension)
            out["laid_length"][i, j] = res.laid_length
    data = {f"database_{k}": v for k, v in out.items()}
    data["database_distance_grid"] = R
    data["database_height_grid"] = Hh
    data["database_heading"] = np.asarray(th)
    return data


@dataclass
class QuasiStaticDatabase:
    """Interpolator of a quasi-static database (see the module docstring).

    ``distance`` [m] (nr,), ``height`` [m] (nh,) the grid; ``names`` the quantities;
    ``values``, ``d_r``, ``d_h``, ``d_rh`` (Q, nr, nh) the nodal values and derivatives
    of the stacked quantities (vector components as separate rows).
    """

    distance: np.ndarray
    height: np.ndarray
    names: list[tuple[str, int | None]]
    values: np.ndarray
    d_r: np.ndarray
    d_h: np.ndarray
    d_rh: np.ndarray
    heading: float = 0.0
    #: monomial coefficients of each cell's bicubic, (Q, nr - 1, nh - 1, 4, 4): value =
    #: sum_mn C[m, n] t^m u^n with t, u the position in the cell in [0, 1]
    coefficients: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 0, 4, 4)))

    def __post_init__(self) -> None:
        R, H = self.distance, self.height
        hr, hh = np.diff(R), np.diff(H)
        # Hermite basis as monomial coefficients in t: values (node 0, node 1) and
        # derivatives (times the cell size)
        P = np.array([[1.0, 0.0, -3.0, 2.0], [0.0, 0.0, 3.0, -2.0]])
        D = np.array([[0.0, 1.0, -2.0, 1.0], [0.0, 0.0, -1.0, 1.0]])
        Pr = np.broadcast_to(P, (len(hr), 2, 4))
        Dr = D[None] * hr[:, None, None]
        Ph = np.broadcast_to(P, (len(hh), 2, 4))
        Dh = D[None] * hh[:, None, None]

        def cells(A: np.ndarray) -> np.ndarray:
            # (Q, nr-1, nh-1, 2, 2): the four corner values of every cell
            return np.stack(
                (
                    np.stack((A[:, :-1, :-1], A[:, :-1, 1:]), -1),
                    np.stack((A[:, 1:, :-1], A[:, 1:, 1:]), -1),
                ),
                -2,
            )

        C = np.einsum("qijab,iam,jbn->qijmn", cells(self.values), Pr, Ph)
        C += np.einsum("qijab,iam,jbn->qijmn", cells(self.d_r), Dr, Ph)
        C += np.einsum("qijab,iam,jbn->qijmn", cells(self.d_h), Pr, Dh)
        C += np.einsum("qijab,iam,jbn->qijmn", cells(self.d_rh), Dr, Dh)
        self.coefficients = np.ascontiguousarray(C)
        # per cell a (Q, 16) matrix acting on (t^m u^n) flattened: one matrix-vector
        # product per lookup
        self._cells = np.ascontiguousarray(
            C.transpose(1, 2, 0, 3, 4).reshape(C.shape[1], C.shape[2], C.shape[0], 16)
        )
        self._r = R.tolist()
        self._h = H.tolist()

    @classmethod
    def from_arrays(
        cls,
        distance: np.ndarray,
        height: np.ndarray,
        tables: dict[str, np.ndarray],
        heading: float = 0.0,
    ) -> QuasiStaticDatabase:
        """Build from the grid and tables (name -> (nr, nh) or (nr, nh, 3)); every table
        must be finite (a failed grid point cannot be interpolated across)."""
        from scipy.interpolate import RectBivariateSpline

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
                f"the database has {int(bad.sum())} failed grid points (e.g. horizontal "
                f"distance {distance[i]:g} m, height difference {height[j]:g} m); it cannot "
                "be interpolated across them: shrink the grid to where the line solves"
            )
        dr, dh, drh = np.empty_like(V), np.empty_like(V), np.empty_like(V)
        for q in range(V.shape[0]):
            spl = RectBivariateSpline(distance, height, V[q], kx=3, ky=3, s=0)
            dr[q] = spl(distance, height, dx=1)
            dh[q] = spl(distance, height, dy=1)
            drh[q] = spl(distance, height, dx=1, dy=1)
        return cls(
            np.asarray(distance, float), np.asarray(height, float), names, V, dr, dh, drh, heading
        )

    @classmethod
    def from_dataset(cls, ds: xr.Dataset) -> QuasiStaticDatabase:
        """From a study dataset with one case's database (select a case first with
        ``ds.sel(...)`` when the study has sweep dimensions)."""
        if "database_tension_a" not in ds:
            raise ValueError("the dataset holds no quasi-static database (analysis.database)")
        extra = [
            d
            for d in ds["database_tension_a"].dims
            if d not in ("horizontal_distance", "height_difference")
        ]
        if extra:
            raise ValueError(
                f"the dataset holds one database per case of the sweep dimensions {extra}; "
                "select one case (e.g. --sel DIM=VALUE)"
            )
        tables = {}
        for name in QUANTITIES:
            arr = (
                ds[f"database_{name}"]
                .transpose("horizontal_distance", "height_difference", ...)
                .values
            )
            tables[name] = arr
        th = float(ds["database_heading"].values) if "database_heading" in ds else 0.0
        return cls.from_arrays(
            ds["horizontal_distance"].values, ds["height_difference"].values, tables, th
        )

    def lookup_array(self, distance: float, height: float) -> np.ndarray:
        """All quantities at once as one array, in the order of ``names`` (the fast path
        of :meth:`lookup`: one cell search and two small matrix products)."""
        r, h = self._r, self._h
        if not (r[0] <= distance <= r[-1] and h[0] <= height <= h[-1]):
            raise ValueError(
                f"position (horizontal distance {distance:g} m, height difference "
                f"{height:g} m) lies outside the database; allowed: horizontal distance "
                f"{r[0]:g} .. {r[-1]:g} m and height difference {h[0]:g} .. {h[-1]:g} m"
            )
        i = min(bisect.bisect_right(r, distance) - 1, len(r) - 2)
        j = min(bisect.bisect_right(h, height) - 1, len(h) - 2)
        t = (distance - r[i]) / (r[i + 1] - r[i])
        u = (height - h[j]) / (h[j + 1] - h[j])
        t2, u2 = t * t, u * u
        t3, u3 = t2 * t, u2 * u
        w = np.array(
            (1.0, u, u2, u3, t, t * u, t * u2, t * u3, t2, t2 * u, t2 * u2, t2 * u3)
            + (t3, t3 * u, t3 * u2, t3 * u3)
        )
        return self._cells[i, j] @ w

    def lookup(self, distance: float, height: float) -> dict[str, Any]:
        """Interpolated quantities at end B ``distance`` [m] horizontally from end A and
        ``height`` [m] above it: force_a, force_b [N] (3,), tension_a, tension_b,
        tension_max [N], laid_length [m].

        Raises
        ------
        ValueError
            outside the grid, with the grid's range.
        """
        v = self.lookup_array(distance, height)
        out: dict[str, Any] = {}
        for (name, k), val in zip(self.names, v, strict=True):
            if k is None:
                out[name] = float(val)
            else:
                out.setdefault(name, np.zeros(3))[k] = val
        return out


def open_database(path: str, **sel: Any) -> QuasiStaticDatabase:
    """The database of a result file (``sel``: one case of a swept study, by dimension
    name and value)."""
    import xarray as xr

    ds = xr.load_dataset(path)
    if sel:
        ds = ds.sel(sel)
    return QuasiStaticDatabase.from_dataset(ds)
