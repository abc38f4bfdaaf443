"""Assembly of case records into one labelled Dataset, and atomic netCDF writes."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.variables import OUTPUTS, CaseRecord
from cablestudy.run.writer import write_atomic
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases
from tests.dataset_helpers import assemble

TEXT = """\
name: res
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: analytic, nodes: 3}
sweep:
  line.segments.0.axial_stiffness: [1.0e6, 1.0e7]
  zip:
    - name: support
      ends.b.position.0: [80.0, 90.0, 95.0]
      ends.b.position.2: [-5.0, -6.0, -7.0]
"""


def _records(cases, fail_index=(1, 2)):  # noqa: ANN001, ANN202
    out = {}
    for c in cases:
        ok = c.index != fail_index
        k = float(c.index[0] * 10 + c.index[1])
        out[c.hash] = CaseRecord(
            hash=c.hash,
            index=c.index,
            status=0 if ok else 2,
            message="" if ok else "singular Jacobian",
            wall_time=0.001,
            data={
                "arc_length": np.array([0.0, 50.0, 100.0]),
                "tension": np.array([k, k + 1, k + 2]) if ok else np.full(3, np.nan),
                "force_a": np.array([k, 0.0, -k]),
                "static_iterations": np.asarray(5),
            },
        )
    return out


def _assembled() -> tuple[xr.Dataset, object]:
    src = parse_study_text(TEXT, "res.yaml")
    axes, cases = expand_cases(src)
    return assemble(axes, cases, _records(cases), src, solver_settings={"tol": 1e-9}), src


def test_dims_coordinates_and_units() -> None:
    ds, _ = _assembled()
    assert dict(ds.sizes) == {"axial_stiffness": 2, "support": 3, "s": 3, "component": 3}
    assert ds["tension"].dims == ("axial_stiffness", "support", "s")
    assert ds["force_a"].dims == ("axial_stiffness", "support", "component")
    np.testing.assert_array_equal(ds["s"], [0.0, 50.0, 100.0])
    assert ds["s"].attrs["units"] == "m" and "arc length" in ds["s"].attrs["long_name"]
    assert ds["axial_stiffness"].attrs["units"] == "N"
    # zipped paths become coordinates along their shared dimension, with units
    np.testing.assert_array_equal(ds["support_0"], [80.0, 90.0, 95.0])
    np.testing.assert_array_equal(ds["support_2"], [-5.0, -6.0, -7.0])
    assert ds["support_0"].dims == ("support",) and ds["support_2"].attrs["units"] == "m"
    for name in list(ds.data_vars) + list(ds.coords):
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
    for name, spec in OUTPUTS.items():
        if name in ds:
            assert ds[name].attrs["units"] == spec.units


def test_failed_case_is_nan_with_status_and_message() -> None:
    ds, _ = _assembled()
    bad = ds.isel(axial_stiffness=1, support=2)
    assert int(bad["status"]) == 2 and str(bad["message"].item()) == "singular Jacobian"
    assert np.all(np.isnan(bad["tension"])) and np.all(np.isnan(bad["force_a"]))
    assert np.isnan(bad["static_iterations"])  # counters too: NaN, never a sentinel
    assert ds["message"].attrs["units"] == "1" and ds["component"].attrs["units"] == "1"
    good = ds.isel(axial_stiffness=1, support=1)
    assert int(good["status"]) == 0 and str(good["message"].item()) == ""
    np.testing.assert_array_equal(good["tension"], [11.0, 12.0, 13.0])
    assert ds.attrs["cases"] == 6 and ds.attrs["cases_failed"] == 1


def test_provenance_attributes() -> None:
    ds, src = _assembled()
    assert ds.attrs["study_yaml"] == TEXT
    assert ds.attrs["study_sha256"] == src.sha256  # type: ignore[attr-defined]
    for key in (
        "cablestudy_version",
        "numpy_version",
        "scipy_version",
        "xarray_version",
        "cablestudy_code_sha256",
    ):
        assert ds.attrs[key]
    assert json.loads(ds.attrs["solver_settings"]) == {"tol": 1e-9}


def test_undeclared_output_is_refused() -> None:
    src = parse_study_text(TEXT, "res.yaml")
    axes, cases = expand_cases(src)
    recs = _records(cases)
    recs[cases[0].hash].data["mystery"] = np.asarray(1.0)
    with pytest.raises(KeyError, match="mystery"):
        assemble(axes, cases, recs, src)


def test_write_round_trip(tmp_path: Path) -> None:
    ds, _ = _assembled()
    path = write_atomic(ds, tmp_path / "deep" / "res.nc")
    back = xr.load_dataset(path)
    xr.testing.assert_identical(back.drop_vars("message"), ds.drop_vars("message"))
    assert [str(m) for m in back["message"].values.ravel()] == [
        str(m) for m in ds["message"].values.ravel()
    ]
    assert list(tmp_path.joinpath("deep").iterdir()) == [path]
    mask = os.umask(0o022)
    os.umask(mask)
    assert path.stat().st_mode & 0o777 == 0o666 & ~mask  # not mkstemp's private 0600


def test_crash_during_write_keeps_the_earlier_result(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    ds, _ = _assembled()
    path = write_atomic(ds, tmp_path / "res.nc")
    before = path.read_bytes()

    def crash(self: xr.Dataset, target: str, *args: object, **kwargs: object) -> None:
        Path(target).write_bytes(b"CDF\x01 half a file")  # partial output, then the crash
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", crash)
    with pytest.raises(OSError, match="disk full"):
        write_atomic(ds.assign(tension=ds["tension"] * 2), path)
    monkeypatch.undo()
    assert path.read_bytes() == before  # untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["res.nc"]  # no temporary left
    xr.testing.assert_equal(xr.load_dataset(path)["tension"], ds["tension"])


def _netcdf_layout(path: Path) -> dict[str, Any]:
    """Everything a netCDF file holds, as netCDF4 reads it (NaN-safe through repr)."""
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        out: dict[str, Any] = {
            "format": nc.data_model,
            "dims": [(d.name, d.size) for d in nc.dimensions.values()],
            "attrs": [(k, repr(nc.getncattr(k)), type(nc.getncattr(k))) for k in nc.ncattrs()],
        }
        for name, var in nc.variables.items():
            var.set_auto_maskandscale(False)
            out[name] = (
                var.dtype,
                var.dimensions,
                [(k, repr(var.getncattr(k))) for k in var.ncattrs()],
                var.chunking(),
                var.filters(),
                repr(var[...].tolist()),
            )
        return out


@pytest.mark.parametrize("small", [False, True], ids=["judged", "small-result"])
@pytest.mark.parametrize("extra_coord", [False, True], ids=["dimension-coords", "zip-coord"])
def test_direct_netcdf_writer_writes_what_xarray_writes(
    tmp_path: Path, extra_coord: bool, small: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy.run import writer
    from cablestudy.run.writer import write_variables_atomic

    if not small:  # this result's variables judged one by one, as a large result's are
        monkeypatch.setattr(writer, "SMALL_RESULT_BYTES", 0)

    rng = np.random.default_rng(1)
    x = rng.normal(size=(3, 2, 4))
    x[1, 0, 2] = np.nan
    data_vars = {
        "status": (("span", "ea"), np.array([[0, 4], [0, 0], [9, 0]]), {"units": "1"}),
        "message": (
            ("span", "ea"),
            np.array([["", "non-finite"], ["", ""], ["task failed: é", ""]], dtype=object),
            {"units": "1", "long_name": "why"},
        ),
        "wall_time": (("span", "ea"), rng.random((3, 2)), {"units": "s", "long_name": "t"}),
        "force_a": (("span", "ea", "component"), rng.normal(size=(3, 2, 3)), {"units": "N"}),
        "x": (("span", "ea", "s"), x, {"units": "m", "long_name": "x position"}),
        # constant: worth compressing, unlike the random values
        "y": (("span", "ea", "s"), np.zeros_like(x), {"units": "m"}),
    }
    coords = {
        "span": ("span", np.array([60.0, 70.0, 80.5]), {"units": "m", "sweep_paths": "p"}),
        "ea": ("ea", np.array([1, 2]), {"units": "N"}),
        "component": ("component", np.array(["x", "y", "z"]), {"units": "1"}),
        "s": ("s", np.linspace(0.0, 1.0, 4), {"units": "m"}),
    }
    if extra_coord:
        coords["span_0"] = ("span", np.array([1.0, 2.0, 3.0]), {"units": "m"})
    attrs = {"title": "t", "study_yaml": "a: 1\n", "cases": 6, "cases_failed": 2}
    direct = write_variables_atomic(data_vars, coords, attrs, tmp_path / "direct" / "r.nc")
    ref = write_atomic(
        xr.Dataset(data_vars, coords=coords, attrs=attrs), tmp_path / "xarray" / "r.nc"
    )
    assert _netcdf_layout(direct) == _netcdf_layout(ref)
    xr.testing.assert_identical(xr.load_dataset(direct), xr.load_dataset(ref))
    assert oct(direct.stat().st_mode & 0o777) == oct(ref.stat().st_mode & 0o777)
    layout = _netcdf_layout(direct)
    if small:  # a small result is stored as is, the constant variable too
        assert not any(layout[k][4]["zlib"] for k in ("wall_time", "force_a", "x", "y"))
    else:
        assert layout["y"][4]["zlib"] and not layout["x"][4]["zlib"]
