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
first derivatives are continuous (C1) and the error falls as h^4 on a smooth table. One
lookup evaluates all quantities at once (a few microseconds); a point outside the grid
is refused with the grid's range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
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


def _hermite(t: float, h: float) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite basis on [0, 1] at t: value weights (node 0, node 1) and derivative
    weights (scaled by the cell size h)."""
    t2, t3 = t * t, t * t * t
    return (
        np.array([2 * t3 - 3 * t2 + 1, -2 * t3 + 3 * t2]),
        np.array([(t3 - 2 * t2 + t) * h, (t3 - t2) * h]),
    )


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

    def lookup(self, distance: float, height: float) -> dict[str, Any]:
        """Interpolated quantities at end B ``distance`` [m] horizontally from end A and
        ``height`` [m] above it: force_a, force_b [N] (3,), tension_a, tension_b,
        tension_max [N], laid_length [m].

        Raises
        ------
        ValueError
            outside the grid, with the grid's range.
        """
        R, H = self.distance, self.height
        if not (R[0] <= distance <= R[-1] and H[0] <= height <= H[-1]):
            raise ValueError(
                f"position (horizontal distance {distance:g} m, height difference "
                f"{height:g} m) lies outside the database; allowed: horizontal distance "
                f"{R[0]:g} .. {R[-1]:g} m and height difference {H[0]:g} .. {H[-1]:g} m"
            )
        i = min(int(np.searchsorted(R, distance, side="right")) - 1, len(R) - 2)
        j = min(int(np.searchsorted(H, height, side="right")) - 1, len(H) - 2)
        hr, hh = R[i + 1] - R[i], H[j + 1] - H[j]
        br, dr = _hermite((distance - R[i]) / hr, hr)
        bh, dh = _hermite((height - H[j]) / hh, hh)
        sl = (slice(None), slice(i, i + 2), slice(j, j + 2))
        v = (
            np.einsum("qab,a,b->q", self.values[sl], br, bh)
            + np.einsum("qab,a,b->q", self.d_r[sl], dr, bh)
            + np.einsum("qab,a,b->q", self.d_h[sl], br, dh)
            + np.einsum("qab,a,b->q", self.d_rh[sl], dr, dh)
        )
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
