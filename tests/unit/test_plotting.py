"""Quick-look plots (`cablestudy plot`) on a small result made through the pipeline."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.plotting import PlotError, quick_look

STUDY = """
name: plot-check
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 21}
sweep:
  ends.b.position.0: {values: [80.0, 85.0, 90.0], name: span}
  line.segments.0.axial_stiffness: [1.0e6, 6.283e7]
"""


@pytest.fixture(scope="module")
def result(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("plot")
    (folder / "study.yaml").write_text(STUDY)
    assert main(["run", str(folder / "study.yaml"), "--out", str(folder), "--no-progress"]) == 0
    return folder / "plot-check.nc"


def test_sweep_plot_has_units_on_both_axes(result: Path) -> None:
    with xr.open_dataset(result) as ds:
        fig = quick_look(ds, "tension_a", x="span", hue="axial_stiffness")
        ax = fig.axes[0]
        assert ax.get_xlabel().endswith("[m]")
        assert ax.get_ylabel() == "tension at end A [N]"
        assert len(ax.get_lines()) == 2  # one curve per stiffness
        # the drawn values are the data
        line = ax.get_lines()[0]
        assert list(line.get_xdata()) == [80.0, 85.0, 90.0]
        assert list(line.get_ydata()) == pytest.approx(
            ds.tension_a.isel(axial_stiffness=0).values.tolist()
        )


def test_profile_and_shape(result: Path) -> None:
    with xr.open_dataset(result) as ds:
        fig = quick_look(ds, "tension", sel=["span=85", "axial_stiffness=1e6"])
        ax = fig.axes[0]
        assert ax.get_xlabel() == "unstretched arc length from end A [m]"
        assert ax.get_ylabel().endswith("[N]")
        assert "span = 85 m" in ax.get_title()  # the picked value with its unit
        shape = quick_look(ds, "z", shape=True, sel=["axial_stiffness=6.283e7"]).axes[0]
        assert shape.get_xlabel().endswith("[m]") and shape.get_ylabel().endswith("[m]")
        assert len(shape.get_lines()) == 3  # one shape per span
        # the shape starts at end A and ends at end B
        first = shape.get_lines()[0]
        assert first.get_xdata()[0] == pytest.approx(0.0, abs=1e-9)
        assert first.get_xdata()[-1] == pytest.approx(80.0)
        assert first.get_ydata()[-1] == pytest.approx(-8.6)


def test_cli_writes_png(result: Path, tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    out = tmp_path / "t.png"
    assert main(["plot", str(result), "tension_b", "--out", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["plot", str(result), "z", "--shape", "--sel", "span=90"]) == 0
    assert Path(capsys.readouterr().out.split()[-1]).exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["tensio"], "no variable 'tensio' in the result; variables: .*tension_a"),
        (["tension", "--x", "depth"], "no dimension 'depth'.*span, axial_stiffness, s"),
        (["tension", "--sel", "speed=1"], "no dimension 'speed'"),
        (["tension"], "pick one value of span"),
        (["tension_a", "--sel", "span=80", "--sel", "axial_stiffness=1e6"], "single value"),
        (["tension_a", "--shape"], "--shape draws profiles on s"),
    ],
)
def test_errors_name_the_bad_name_and_the_valid_ones(
    result: Path, args: list[str], message: str, capsys: pytest.CaptureFixture
) -> None:
    assert main(["plot", str(result), *args]) == 2
    err = capsys.readouterr().err
    assert re.search(message, err), err
    with xr.open_dataset(result) as ds, pytest.raises(PlotError):
        quick_look(ds, "nothing")
