"""Compare the datasets of two result folders (e.g. the outputs of
benchmarks/run_all_configs.sh run on two checkouts): identical after dropping what a run
stamps (wall times, the history timestamp, hashes of the solver code).

Usage: python benchmarks/compare_datasets.py DIR_A DIR_B

Modal outputs are compared with a tolerance: the eigensolver's results differ from run
to run of the same code in the 13th digit of a frequency and about 1e-10 of a unit mode
shape, and a mode's sign is arbitrary; where two modes share a frequency (a vertical
line's two transverse directions) any rotation within the pair is a mode, so each group
of modes of equal frequency is compared by the space it spans.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import xarray as xr

#: what a run stamps: the history's timestamp, the solver code's hash (case_hash in a
#: database file hashes the code as well), the wall times
RUNTIME_ATTRS = {"history", "cablestudy_code_sha256"}
RUNTIME_VARS = {"wall_time", "case_hash"}


def _clean(ds: xr.Dataset) -> xr.Dataset:
    ds = ds.drop_vars([v for v in ds.variables if v in RUNTIME_VARS])
    ds.attrs = {k: v for k, v in ds.attrs.items() if k not in RUNTIME_ATTRS}
    return ds


def same_modes(da: xr.Dataset, db: xr.Dataset) -> bool:
    """Per case and group of modes of equal frequency, the second's shapes lie in the
    span of the first's (projected on it, they leave < 1e-8 of their norm)."""
    freqs = da["natural_frequency"].values
    axis = da["mode_shape"].dims.index("mode")
    shapes_a = np.moveaxis(da["mode_shape"].values, axis, -1)
    shapes_b = np.moveaxis(db["mode_shape"].values, axis, -1)
    n_modes = shapes_a.shape[-1]
    for idx in np.ndindex(*freqs.shape[:-1]):
        f = freqs[idx]
        a_case = np.nan_to_num(shapes_a[idx].reshape(-1, n_modes))
        b_case = np.nan_to_num(shapes_b[idx].reshape(-1, n_modes))
        j = 0
        while j < n_modes:
            k = j + 1
            while k < n_modes and abs(f[k] - f[j]) <= 1e-9 * abs(f[j]):
                k += 1
            a, b = a_case[:, j:k], b_case[:, j:k]
            coef = np.linalg.lstsq(a, b, rcond=None)[0]
            if np.linalg.norm(b - a @ coef) > 1e-8 * max(np.linalg.norm(b), 1e-300):
                return False
            j = k
    return True


def _close_modal(x: np.ndarray, y: np.ndarray) -> bool:
    """Equal up to sign, to 1e-9 relative (frequencies) or 1e-9 of the largest value."""
    scale = np.nanmax(np.abs(x))
    return bool(np.allclose(np.abs(x), np.abs(y), rtol=1e-9, atol=1e-9 * scale, equal_nan=True))


def _same_attrs(a: dict, b: dict) -> bool:
    """Attributes equal, array-valued ones (flag values) element by element."""
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def compare(path_a: Path, path_b: Path) -> str:
    da = _clean(xr.open_dataset(path_a)).load()
    db = _clean(xr.open_dataset(path_b)).load()
    if da.identical(db):
        return "identical"
    problems = []
    if set(da.variables) != set(db.variables):
        problems.append(f"variables differ: {sorted(set(da.variables) ^ set(db.variables))}")
    for k in sorted(set(da.attrs) | set(db.attrs)):
        if da.attrs.get(k) != db.attrs.get(k):
            problems.append(
                f"attr {k}: {str(da.attrs.get(k))[:200]!r} vs {str(db.attrs.get(k))[:200]!r}"
            )
    tolerant = []
    for v in sorted(set(da.variables) & set(db.variables)):
        x, y = da[v], db[v]
        if x.identical(y):
            continue
        if x.dims != y.dims or x.shape != y.shape or not _same_attrs(x.attrs, y.attrs):
            problems.append(f"{v}: dims, shape or attributes differ")
            continue
        if v == "mode_shape" and "natural_frequency" in da and same_modes(da, db):
            tolerant.append(f"{v} (same span per group of modes of equal frequency)")
            continue
        if "mode" in x.dims and x.dtype.kind == "f" and _close_modal(x.values, y.values):
            tolerant.append(v)
            continue
        problems.append(f"{v}: values differ")
    if problems:
        return "DIFFERENT: " + "; ".join(problems)
    return "equal (modal tolerance on " + ", ".join(tolerant) + ")"


def main(dir_a: Path, dir_b: Path) -> int:
    bad = 0
    for a in sorted(dir_a.glob("*.nc")):
        b = dir_b / a.name
        result = compare(a, b) if b.exists() else "MISSING in the second folder"
        bad += not result.startswith(("identical", "equal"))
        print(f"{a.name}: {result}")
    for b in sorted(dir_b.glob("*.nc")):
        if not (dir_a / b.name).exists():
            print(f"{b.name}: MISSING in the first folder")
            bad += 1
    print(f"{bad} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), Path(sys.argv[2])))
