"""``method: auto`` for a mooring system (issue 24), from the study file to the dataset.

auto solves the system's frequency domain and applies the single line's checks to
every line (:mod:`cablestudy.dynamics.system_validity`): the frequency domain answers
only when every line passes, and ``dynamic_method_reason`` names the line that
decided. Checked through the command line on MoorPy's case8 (spar, bridles, free
junctions) and MoorDyn's lines.txt (three chains partly laid on the seabed)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

ROOT = Path(__file__).parents[2]
CASE8 = ROOT / "configs" / "system-case8-surge.yaml"


def _run(tmp: Path, text: str, name: str) -> xr.Dataset:
    cfg = tmp / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp / name
    args = ["run", str(cfg), "--out", str(out), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    (nc,) = out.glob("*.nc")
    return xr.load_dataset(nc)


def _case8(dynamic: str) -> str:
    text = CASE8.read_text()
    return text[: text.index("  dynamic:")] + dynamic


@pytest.fixture(scope="module")
def case8_auto(tmp_path_factory: pytest.TempPathFactory) -> tuple[xr.Dataset, xr.Dataset]:
    """case8 surged at 0.1 Hz by auto (0.1 m and 2 m) and by the time domain (0.1 m),
    at 16 elements a line (not the config's 20: the system frequency domain's model
    cache is per process, and test_system_frequency counts the assemblies of 20) and
    the config's time step (128 a period)."""
    tmp = tmp_path_factory.mktemp("case8auto")
    head = """\
  dynamic:
    excitation: {body: body1, dof: surge, amplitude: 0.1, frequency: 0.1}
    elements: 16
"""
    auto = _run(
        tmp,
        _case8(
            head
            + "    method: auto\n    points_per_period: 128\n"
            + "sweep:\n  analysis.dynamic.excitation.amplitude: [0.1, 2.0]\n"
        ),
        "auto",
    )
    time = _run(tmp, _case8(head + "    method: time\n    points_per_period: 128\n"), "time")
    return auto, time


def test_case8_small_motion_picks_the_frequency_domain(
    case8_auto: tuple[xr.Dataset, xr.Dataset],
) -> None:
    auto, time = case8_auto
    assert np.all(auto.status.values == 0), auto.message.values
    assert list(auto.dynamic_method.values) == ["frequency", "time"]
    small, large = (str(r) for r in auto.dynamic_method_reason.values)
    assert small.startswith("auto: linear") and "line '" in small, small
    # at 2 m the taut bridles' shape changes by 0.2 to 2.8 of their 3 cm sag
    assert large.startswith("auto: line '") and "large motion: amplitude/sag" in large, large
    # decided before the frequency domain by the quasi-static shape change (0.31 of the
    # 3 cm sag on line 1, the first over twice the limit; analyses.system_prejudge)
    assert "quasi-static" in large and "before the frequency domain" in large, large
    assert np.all(np.isfinite(auto.tension_amplitude_a.values[0]))


def test_case8_frequency_domain_agrees_with_the_time_domain_at_small_motion(
    case8_auto: tuple[xr.Dataset, xr.Dataset],
) -> None:
    """The issue's "frequency domain against time domain at small amplitude within
    0.5 %": each line's end tension amplitude (the time domain's half range) within
    0.5 % of the largest. What separates them at 0.1 m: the dropped second-order terms
    (amplitude/sag 0.03 on the worst line: its square, 1e-3) and the time step's
    phase error at 128 a period (about (2 pi / 128)^2 / 12 = 2e-4); the drag fit's
    and the steady window's tolerances are below 1e-4."""
    auto, time = case8_auto
    fd = auto.isel(**{auto.tension_amplitude_a.dims[0]: 0})
    assert str(fd.dynamic_method.values) == "frequency"
    assert str(time.dynamic_method.values) == "time"
    big = 0.0
    worst = 0.0
    for end in ("a", "b"):
        a_fd = fd[f"tension_amplitude_{end}"].values
        a_td = 0.5 * (time[f"tension_max_{end}"].values - time[f"tension_min_{end}"].values)
        big = max(big, float(np.max(a_td)))
        worst = max(worst, float(np.max(np.abs(a_fd - a_td))))
    assert big > 1e4  # a real response (13 kN on the legs)
    assert worst <= 5e-3 * big, (worst / big, worst, big)


def _lines_txt(dynamic: str) -> str:
    from cablestudy.interchange import import_model, imported_yaml

    rel = "moordyn/tests/Mooring/lines.txt"
    path = ROOT / "tests" / "data" / rel
    text = imported_yaml(import_model(path.read_text(), rel, folder=path.parent), rel)
    return text + dynamic


def test_lines_on_the_seabed_decided_per_line_by_touchdown_travel(tmp_path: Path) -> None:
    """lines.txt surged 0.2 m at 0.05 Hz: the touchdown travel of leg 1 (in line with
    the surge) is 1.4e-3 of its length, of legs 2 and 3 7.4e-4. With the default limit
    (0.03) every line passes; with the limit at 1e-3 leg 1 alone fails and sends the
    case to the time domain, named in the reason (the threshold is used per line)."""
    dyn = """\
  dynamic:
    excitation: {body: vessel, dof: surge, amplitude: 0.2, frequency: 0.05}
    method: auto
    elements: 20
    auto: {max_touchdown_travel: %s}
"""
    ds = _run(tmp_path, _lines_txt(dyn % "0.03"), "default")
    assert int(ds.status) == 0, str(ds.message.values)
    assert str(ds.dynamic_method.values) == "frequency"
    reason = str(ds.dynamic_method_reason.values)
    assert "nearest, line '1'" in reason, reason
    ds = _run(tmp_path, _lines_txt(dyn % "0.001"), "tight")
    assert int(ds.status) == 0, str(ds.message.values)
    assert str(ds.dynamic_method.values) == "time"
    reason = str(ds.dynamic_method_reason.values)
    assert reason.startswith("auto: line '1': touchdown travel"), reason
    assert "> 0.001 L" in reason, reason


def test_auto_at_two_elements_a_line(tmp_path: Path) -> None:
    """Two elements a line (one inner node; the frequency domain's model could not be
    solved there before: IndexError, and auto ran the time domain): at 0.1 m every line
    passes the checks and auto answers by the frequency domain, at 2 m the bridles'
    shape changes (amplitude/sag 2.8) and auto runs the time domain, saying why. The
    frequency domain's amplitudes at 0.1 m are the time domain's on the same mesh
    within the issue's 0.5 % of the largest (the reasons of the 16-element test above;
    measured 2.3e-3)."""
    head = """\
  dynamic:
    excitation: {body: body1, dof: surge, amplitude: 0.1, frequency: 0.1}
    elements: 2
    points_per_period: 128
"""
    auto = _run(
        tmp_path,
        _case8(head + "sweep:\n  analysis.dynamic.excitation.amplitude: [0.1, 2.0]\n"),
        "auto2",
    )
    assert np.all(auto.status.values == 0), auto.message.values
    assert list(auto.dynamic_method.values) == ["frequency", "time"]
    small, large = (str(r) for r in auto.dynamic_method_reason.values)
    assert small.startswith("auto: linear"), small
    assert "large motion: amplitude/sag" in large, large
    time = _run(tmp_path, _case8(head + "    method: time\n"), "time2")
    fd = auto.isel(**{auto.tension_amplitude_a.dims[0]: 0})
    big, worst = 0.0, 0.0
    for end in ("a", "b"):
        a_fd = fd[f"tension_amplitude_{end}"].values
        a_td = 0.5 * (time[f"tension_max_{end}"].values - time[f"tension_min_{end}"].values)
        big = max(big, float(np.max(a_td)))
        worst = max(worst, float(np.max(np.abs(a_fd - a_td))))
    assert big > 1e4
    assert worst <= 5e-3 * big, (worst / big, worst, big)
