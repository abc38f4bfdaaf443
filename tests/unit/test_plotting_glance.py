"""Plots that read at a glance, through the real CLI (YAML -> netCDF -> PNG): several
variables on one axes, ``--units``, labelled sweep axes as coordinates and in legends,
and no text outside the figure. The figure drawn is caught at ``savefig``."""

from __future__ import annotations

import math
import struct
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.text import Text

from cablestudy.cli import main
from cablestudy.plotting import UNITS, unit_scale
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid

LINE = """
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 21}
"""
#: a labelled swept vector: the case-by-case writer (run/dataset.py)
PLACES = (
    "name: places\n"
    + LINE
    + (
        "sweep:\n"
        "  ends.b.position: {values: [[80.0, 0.0, -8.6], [90.0, 0.0, -8.6]], name: place%s}\n"
        "  line.segments.0.axial_stiffness: [1.0e6, 6.283e7]\n"
    )
)
#: labelled scalars on fixed-end positions and stiffnesses: the array grid (analyses/static_grid.py)
SPANS = (
    "name: spans\n"
    + LINE
    + (
        "sweep:\n"
        "  ends.b.position.0: {values: [80.0, 85.0, 90.0], name: span,\n"
        "                      labels: [short, mid, long]}\n"
        "  line.segments.0.axial_stiffness: {values: [1.0e6, 6.283e7], labels: [soft, stiff]}\n"
    )
)
#: a swept excitation direction (frequency domain: a few ms per case once compiled)
MOTIONS = """
name: %s
environment: {fluid: water}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e+6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
analysis:
  static: {method: analytic, nodes: 21}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.01, frequency: 0.5}
    method: frequency
sweep:
  analysis.dynamic.excitation.direction: {values: [[1, 0, 0], [0, 0, 1]], name: motion%s}
  analysis.dynamic.excitation.frequency: {start: 0.2, stop: 1.0, num: 3}
"""


def _run(folder: Path, text: str, name: str) -> Path:
    (folder / f"{name}.yaml").write_text(text)
    assert main(["run", str(folder / f"{name}.yaml"), "--out", str(folder), "--no-progress"]) == 0
    return folder / f"{name}.nc"


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("glance")
    return {
        "places": _run(folder, PLACES % ", labels: [near, far]", "places"),
        "places-plain": _run(
            folder, (PLACES % "").replace("places", "places-plain"), "places-plain"
        ),
        "spans": _run(folder, SPANS, "spans"),
        "motions": _run(folder, MOTIONS % ("motions", ", labels: [surge, heave]"), "motions"),
        "motions-plain": _run(folder, MOTIONS % ("motions-plain", ""), "motions-plain"),
    }


@pytest.fixture
def drawn(monkeypatch: pytest.MonkeyPatch) -> list[Figure]:
    """The figures `cablestudy plot` saves, in order."""
    figures: list[Figure] = []
    save = Figure.savefig

    def keep(self: Figure, *args: Any, **kwargs: Any) -> Any:
        figures.append(self)
        return save(self, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", keep)
    return figures


def _plot(result: Path, out: Path, *args: str) -> None:
    assert main(["plot", str(result), *args, "--out", str(out)]) == 0


def _outside(fig: Figure) -> list[str]:
    """Drawn texts whose rendered extent leaves the figure (more than half a pixel), by
    the Agg renderer at the resolution of the PNG (layout included). A text counts as
    drawn if the figure's tight bounding box (what ``bbox_inches="tight"`` keeps, made of
    the drawn artists only: tick labels beyond the axis limits are not) reaches it."""
    fig.set_dpi(120)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    box = fig.bbox
    tight = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    if (
        tight.x0 >= box.x0 - 0.5
        and tight.y0 >= box.y0 - 0.5
        and tight.x1 <= box.x1 + 0.5
        and tight.y1 <= box.y1 + 0.5
    ):
        return []
    bad = []
    for text in fig.findobj(Text):
        if not text.get_visible() or not text.get_text().strip():
            continue
        ext = text.get_window_extent(renderer)
        if not (box.x0 - 0.5 <= ext.x0 and ext.x1 <= box.x1 + 0.5) or not (
            box.y0 - 0.5 <= ext.y0 and ext.y1 <= box.y1 + 0.5
        ):
            bad.append(text.get_text())
    return bad or ["(an artist that is not text)"]


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def test_clipping_check_sees_clipped_text(tmp_path: Path) -> None:
    """The check below is not vacuous: an unwrapped 200-character label leaves a 7 in
    figure (10 pt text is about 0.08 in a character, so 16 in wide)."""
    fig = Figure(figsize=(7.0, 4.5), layout="constrained")
    fig.add_subplot().set_xlabel("x" * 200)
    fig.savefig(tmp_path / "bad.png", dpi=120)
    assert _outside(fig) == ["x" * 200]


def test_two_variables_in_kilonewtons(
    results: dict[str, Path], tmp_path: Path, drawn: list[Figure]
) -> None:
    out = tmp_path / "ab.png"
    _plot(results["places"], out, "tension_a", "tension_b", "--units", "kN", "--x", "place")
    ax = drawn[-1].axes[0]
    with xr.open_dataset(results["places"]) as ds:
        # 2 variables x 2 stiffnesses; colours for stiffness, line styles for variables
        assert len(ax.get_lines()) == 4
        texts = [t.get_text() for t in ax.get_legend().get_texts()]
        assert texts == [
            "tension at end A",
            "tension at end B",
            "axial_stiffness = 1e+06 N",
            "axial_stiffness = 6.283e+07 N",
        ]
        assert ax.get_ylabel().replace("\n", " ") == "tension at end A / B [kN]"
        # the labels are the x ticks, in file order
        assert [t.get_text() for t in ax.get_xticklabels()] == ["near", "far"]
        # kN is N times 1e-3: one rounding each, so equal to a relative 1e-15
        for line, (name, k) in zip(
            ax.get_lines(),
            [("tension_a", 0), ("tension_a", 1), ("tension_b", 0), ("tension_b", 1)],
            strict=True,
        ):
            expected = 1e-3 * ds[name].isel(axial_stiffness=k).values
            np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-15)
    assert _outside(drawn[-1]) == []
    width, height = _png_size(out)
    # nothing widened the tight bbox beyond the figure and its 0.05 in pads
    assert width <= (7 + 0.1) * 120 and height <= (4.5 + 0.1) * 120


def test_long_labels_are_wrapped_inside_the_figure(
    results: dict[str, Path], tmp_path: Path, drawn: list[Figure]
) -> None:
    """The stiffness axis' long name (about 100 characters) and two joined variable names
    would leave the figure unwrapped; every text stays in."""
    out = tmp_path / "long.png"
    _plot(results["places-plain"], out, "tension_a", "tension_b", "--sel", "place=1")
    fig = drawn[-1]
    ax = fig.axes[0]
    assert "\n" in ax.get_xlabel() and ax.get_xlabel().replace("\n", " ").startswith(
        "axial stiffness EA"
    )
    assert ax.get_xlabel().endswith("[N]")
    assert _outside(fig) == []
    # the swept vector picked by index reads as its value in the title
    assert ax.get_title() == "place = [90, 0, -8.6]"


def test_labelled_coordinates_on_both_writers(results: dict[str, Path]) -> None:
    grid = expand_grid(parse_study_text(SPANS, "spans.yaml"))
    assert grid.chunked  # the spans study is written by the array grid
    assert not expand_grid(parse_study_text(PLACES % ", labels: [near, far]", "p.yaml")).chunked
    with xr.open_dataset(results["spans"]) as ds:
        assert ds["span"].values.tolist() == ["short", "mid", "long"]
        assert ds["span_value"].values.tolist() == [80.0, 85.0, 90.0]
        assert ds["span_value"].attrs["units"] == "m"
        assert ds["axial_stiffness"].values.tolist() == ["soft", "stiff"]
        a = ds.tension_a.sel(span="long", axial_stiffness="stiff").item()
    with xr.open_dataset(results["places"]) as ds, xr.open_dataset(results["places-plain"]) as p:
        assert ds["place"].values.tolist() == ["near", "far"]
        assert p["place"].values.tolist() == [0, 1]
        assert ds["place_value"].values.tolist() == p["place_value"].values.tolist()
        # labels name the cases, they change no number
        np.testing.assert_array_equal(ds.tension_a.values, p.tension_a.values)
        # the same line and end positions on both writers give the same tension; the
        # writers' solvers differ, so agree to their static tolerance (1e-9 relative)
        b = ds.tension_a.sel(place="far", axial_stiffness=6.283e7).item()
        assert b == pytest.approx(a, rel=1e-8)


def test_sel_by_label_and_legend_of_labels(
    results: dict[str, Path], tmp_path: Path, drawn: list[Figure]
) -> None:
    _plot(
        results["motions"],
        tmp_path / "m.png",
        "tension_max",
        "tension_min",
        "--sel",
        "motion=heave",
    )
    ax = drawn[-1].axes[0]
    assert ax.get_title() == "motion = heave"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [
        "maximum tension at the excited end,\nsteady window",
        "minimum tension at the excited end,\nsteady window",
    ]
    with xr.open_dataset(results["motions"]) as ds:
        heave = ds.sel(motion="heave")
        np.testing.assert_array_equal(ax.get_lines()[0].get_ydata(), heave.tension_max.values)
        np.testing.assert_array_equal(ax.get_lines()[1].get_ydata(), heave.tension_min.values)
        # a heave of the end oscillates the tension about its static value
        assert np.all(heave.tension_max.values >= heave.tension_static.values)
        assert np.all(heave.tension_min.values <= heave.tension_static.values)
    _plot(results["motions"], tmp_path / "h.png", "tension_max")
    texts = [t.get_text() for t in drawn[-1].axes[0].get_legend().get_texts()]
    assert texts == ["motion = surge", "motion = heave"]
    assert _outside(drawn[-1]) == []


def test_unlabelled_vector_reads_as_its_value(
    results: dict[str, Path], tmp_path: Path, drawn: list[Figure]
) -> None:
    _plot(results["motions-plain"], tmp_path / "p.png", "tension_max", "--x", "frequency")
    ax = drawn[-1].axes[0]
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts == ["motion = [1, 0, 0]", "motion = [0, 0, 1]"]
    assert not any("index" in t.get_text() for t in drawn[-1].findobj(Text))
    # the vector written as a value picks the same case as its label in the other file
    _plot(results["motions-plain"], tmp_path / "q.png", "tension_max", "--sel", "motion=[0,0,1]")
    plain = drawn[-1].axes[0]
    assert plain.get_title() == "motion = [0, 0, 1]"
    _plot(results["motions"], tmp_path / "r.png", "tension_max", "--sel", "motion=heave")
    np.testing.assert_array_equal(
        plain.get_lines()[0].get_ydata(), drawn[-1].axes[0].get_lines()[0].get_ydata()
    )


def test_shape_in_millimetres(
    results: dict[str, Path], tmp_path: Path, drawn: list[Figure]
) -> None:
    _plot(
        results["spans"],
        tmp_path / "s.png",
        "z",
        "--shape",
        "--sel",
        "axial_stiffness=soft",
        "--units",
        "mm",
    )
    ax = drawn[-1].axes[0]
    assert ax.get_xlabel().endswith("[mm]") and ax.get_ylabel().endswith("[mm]")
    assert [t.get_text() for t in ax.get_legend().get_texts()] == [
        "span = short",
        "span = mid",
        "span = long",
    ]
    last = ax.get_lines()[2]  # span 'long': end B at x = 90 m, z = -8.6 m
    assert last.get_xdata()[-1] == pytest.approx(90e3, rel=1e-12)
    assert last.get_ydata()[-1] == pytest.approx(-8.6e3, rel=1e-12)


def test_unit_table_is_consistent() -> None:
    """Each conversion and its inverse multiply to one; the table's sizes are the SI
    definitions (1 rad/s = 1/(2 pi) Hz, 1 deg = pi/180 rad, 1 h = 3600 s)."""
    for unit, (quantity, _) in UNITS.items():
        base = next(u for u, (q, size) in UNITS.items() if q == quantity and size == 1.0)
        there, _ = unit_scale(base, unit, "v")
        back, _ = unit_scale(unit, base, "v")
        assert there * back == pytest.approx(1.0, rel=1e-15)
    assert unit_scale("Hz", "rad/s", "f")[0] == pytest.approx(2.0 * math.pi, rel=1e-15)
    assert unit_scale("rad", "deg", "a")[0] == pytest.approx(180.0 / math.pi, rel=1e-15)
    assert unit_scale("h", "s", "t")[0] == 3600.0


KNOWN = "N, kN, MN, N/m, kN/m, MN/m, m, mm, km, s, min, h, Hz, rad/s, rad, deg"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ["tension_a", "x"],
            "cannot plot: tension_a is in 'N' and x in 'm': variables drawn on one axes must "
            "share their unit; draw them in separate plots",
        ),
        (
            ["tension_a", "--units", "kPa"],
            f"cannot plot: --units 'kPa': unknown unit; known units: {KNOWN}",
        ),
        (
            ["tension_a", "--units", "mm"],
            "cannot plot: --units 'mm': tension_a is a force in 'N', which converts to N, kN, "
            "MN only (not to a length)",
        ),
        (
            ["tension_a", "tension"],
            "cannot plot: tension_a has dimensions (place, axial_stiffness) and tension "
            "(place, axial_stiffness, s) after --sel; variables drawn on one axes must share "
            "their dimensions",
        ),
        (
            ["tension_a", "--sel", "place=middle"],
            "cannot plot: --sel 'place=middle': place has no value 'middle'; values: near, far",
        ),
        (["tension_a", "tension_a"], "cannot plot: tension_a named twice; name each variable once"),
        (
            ["x", "z", "--shape"],
            "cannot plot: --shape draws one line shape; got 2 variables",
        ),
    ],
)
def test_refusals_name_the_bad_value(
    results: dict[str, Path], args: list[str], message: str, capsys: pytest.CaptureFixture
) -> None:
    assert main(["plot", str(results["places"]), *args]) == 2
    assert capsys.readouterr().err.strip() == message
