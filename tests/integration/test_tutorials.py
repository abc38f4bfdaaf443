"""The tutorials of the user guide (docs/tutorials/), each run from its study in
configs/ through the command line (YAML -> netCDF), checked on the physics the tutorial
reads from it, and the Python code the tutorials show run as printed.

Tolerances: the static solutions are converged to ``analysis.static.tolerance``
(1e-9 relative, the default); the identities checked below hold in the exact solution,
so they are asserted to 1e-6 relative, a thousand times the solver tolerance, which
still fails on any error of a sign, a segment or a term (each of those is of order 1).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from cablestudy.cli import main

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs"
TUTORIALS = ROOT / "docs" / "tutorials"

#: the solver tolerance of the tutorials' statics, times 1000 (see the module docstring)
RTOL = 1e-6


def _run(name: str, out: Path) -> xr.Dataset:
    code = main(
        ["run", str(CONFIGS / f"{name}.yaml"), "--out", str(out), "--no-cache", "--no-progress"]
    )
    assert code == 0
    return xr.load_dataset(out / f"{name}.nc")


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The tutorials' results, written once for this module into ``results/``."""
    out = tmp_path_factory.mktemp("tutorials") / "results"
    for name in (
        "tutorial-mooring-leg",
        "tutorial-towed-cable",
        "moustafa-figs2-5",
        "tutorial-moordyn-import",
    ):
        _run(name, out)
    return out


def _segments(name: str) -> list[dict]:
    study = yaml.safe_load((CONFIGS / f"{name}.yaml").read_text())
    return study["line"]["segments"]


def test_mooring_leg_restoring_curve(results: Path) -> None:
    """Moving the fairlead away from the anchor lifts chain off the seabed (laid length
    falls) and stiffens the leg (fairlead tension and horizontal pull rise); the vertical
    force at the fairlead is the weight in water of the suspended length; the anchor
    carries the horizontal pull less the friction of the laid length, or nothing."""
    ds = xr.load_dataset(results / "tutorial-mooring-leg.nc")
    assert (ds.status == 0).all()
    laid = ds.laid_length.values
    assert np.all(np.diff(laid) < 0)
    assert np.all(np.diff(ds.tension_b.values) > 0)
    pull = -ds.force_b
    horizontal = pull.sel(component="x").values
    vertical = pull.sel(component="z").values
    assert np.all(horizontal > 0) and np.all(np.diff(horizontal) > 0)
    # the line exerts on the fairlead a force towards the anchor and downwards
    assert np.all(ds.force_b.sel(component="x").values < 0)
    assert np.all(ds.force_b.sel(component="z").values < 0)

    segments = _segments("tutorial-mooring-leg")
    lengths = np.array([s["length"] for s in segments])
    weights = np.array([s["weight_in_fluid"] for s in segments])
    starts = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
    # unstretched length of each segment on the seabed (the laid part starts at A)
    on_bed = np.clip(laid[:, None] - starts[None, :], 0.0, lengths[None, :])
    suspended_weight = (weights * (lengths - on_bed)).sum(axis=1)
    np.testing.assert_allclose(vertical, suspended_weight, rtol=RTOL)

    friction = yaml.safe_load((CONFIGS / "tutorial-mooring-leg.yaml").read_text())["environment"][
        "seabed"
    ]["friction"]
    held = friction * (weights * on_bed).sum(axis=1)
    anchor = np.maximum(horizontal - held, 0.0)
    # relative to the horizontal pull: the anchor tension is a difference of two such forces
    assert np.all(np.abs(ds.tension_a.values - anchor) <= RTOL * horizontal)
    # the sweep spans the regimes the tutorial reads: friction holding all, and not
    assert (anchor == 0).any() and (anchor > 0).any()


def test_towed_cable(results: Path) -> None:
    """The line's force on the towed body is the opposite of the force the study applies
    at the force end (the sign convention); as the tow speed rises, the body rises and
    trails further astern and the horizontal pull at the stern grows."""
    ds = xr.load_dataset(results / "tutorial-towed-cable.nc")
    assert (ds.status == 0).all()
    study = yaml.safe_load((CONFIGS / "tutorial-towed-cable.yaml").read_text())
    (group,) = study["sweep"]["zip"]
    applied = np.array(
        [[fx, 0.0, study["ends"]["b"]["force"][2]] for fx in group["ends.b.force.0"]]
    )
    scale = np.linalg.norm(applied, axis=1)[:, None]
    assert np.all(np.abs(ds.force_b.values + applied) <= 1e-12 * scale)
    np.testing.assert_allclose(ds.tension_b.values, scale[:, 0], rtol=1e-12)

    speed = ds.tow_speed_environment_current_1_speed.values
    assert np.all(np.diff(speed) > 0)
    body_z = ds.z.isel(s=-1).values
    body_x = ds.x.isel(s=-1).values
    assert np.all(np.diff(body_z) > 0)  # rises
    assert np.all(np.diff(body_x) < 0)  # trails further astern (-x)
    pull = -ds.force_a.sel(component="x").values
    assert np.all(pull > -applied[:, 0])  # more than the body's drag: the cable's adds
    assert np.all(np.diff(pull) > 0)


def test_tension_against_frequency_auto(results: Path) -> None:
    """Figs. 2-5 with method auto: every case ran; maximum >= static >= minimum; where
    the frequency domain answered, the response is symmetric about the static tension
    (linear); each reason's measures and the default thresholds agree with the method
    that ran (the reasons mean what the tutorial says)."""
    ds = xr.load_dataset(results / "moustafa-figs2-5.nc")
    assert (ds.status == 0).all()
    static = ds.tension_static.values
    assert np.all(ds.tension_max.values >= static) and np.all(ds.tension_min.values <= static)
    # larger motion, wider range at every frequency
    assert np.all(np.diff(ds.tension_max.values, axis=0) > 0)
    assert np.all(np.diff(ds.tension_min.values, axis=0) < 0)

    method = ds.dynamic_method.values
    reason = ds.dynamic_method_reason.values
    linear = method == "frequency"
    assert 0 < linear.sum() < linear.size
    up = ds.tension_max.values - static
    down = static - ds.tension_min.values
    # linear response: static +/- amplitude, to round-off of the tension (100 N * 1e-12)
    np.testing.assert_allclose(up[linear], down[linear], rtol=0, atol=1e-9)
    assert np.all(np.abs(up[~linear] - down[~linear]) > 1e-6 * static[~linear])

    number = r"(-?[0-9.e+-]+)"
    for m, r in zip(method.ravel(), reason.ravel(), strict=True):
        if m == "frequency":
            found = re.fullmatch(
                rf"auto: linear \(min/static tension {number}, amplitude/sag {number}\)", r
            )
            assert found, r
            assert float(found[1]) >= 0.7 and float(found[2]) <= 0.075
        else:
            assert m == "time" and r.startswith("auto: "), r
            slack = re.search(rf"near slack: min/static tension {number} < 0.7", r)
            large = re.search(rf"large motion: amplitude/sag {number} > 0.075", r)
            assert slack or large, r
            if slack:
                assert float(slack[1]) < 0.7
            if large:
                assert float(large[1]) > 0.075


def _python_blocks(page: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", page.read_text(), flags=re.DOTALL)


@pytest.mark.parametrize(
    "page",
    ["xarray.md", "mooring-leg.md", "tension-frequency.md", "towed-cable.md", "moordyn-import.md"],
)
def test_tutorial_code_runs(page: str, results: Path, tmp_path: Path) -> None:
    """The Python of each tutorial page, run in order as a reader would, in a folder
    holding the results it opens; the figures it saves must be written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    blocks = _python_blocks(TUTORIALS / page)
    assert blocks
    (tmp_path / "results").symlink_to(results, target_is_directory=True)
    saved = re.findall(r'savefig\("([^"]+)"', "".join(blocks))
    here = Path.cwd()
    os.chdir(tmp_path)
    try:
        namespace: dict = {}
        for block in blocks:
            exec(compile(block, f"{page}", "exec"), namespace)  # noqa: S102
    finally:
        os.chdir(here)
        plt.close("all")
    for name in saved:
        assert (tmp_path / name).stat().st_size > 1000, name


def _within(part: object, whole: object, path: str = "") -> list[str]:
    """Where ``part`` (a YAML fragment) differs from ``whole`` (the study it is cut
    from): every key and value of the fragment must be in the study."""
    if isinstance(part, dict):
        if not isinstance(whole, dict):
            return [path or "(top)"]
        return [
            miss
            for key, value in part.items()
            for miss in (
                _within(value, whole[key], f"{path}.{key}") if key in whole else [f"{path}.{key}"]
            )
        ]
    if isinstance(part, list):
        if not isinstance(whole, list) or len(part) != len(whole):
            return [path]
        return [
            m
            for i, (p, w) in enumerate(zip(part, whole, strict=True))
            for m in _within(p, w, f"{path}.{i}")
        ]
    return [] if part == whole else [f"{path}: {part!r} != {whole!r}"]


@pytest.mark.parametrize(
    ("page", "config"),
    [
        ("mooring-leg.md", "tutorial-mooring-leg"),
        ("tension-frequency.md", "moustafa-figs2-5"),
        ("towed-cable.md", "tutorial-towed-cable"),
        ("moordyn-import.md", "tutorial-moordyn-import"),
    ],
)
def test_tutorial_yaml_is_the_study(page: str, config: str) -> None:
    """Each YAML fragment a tutorial shows is part of the study it runs, as written, so
    the page and the tested study cannot drift apart."""
    study = yaml.safe_load((CONFIGS / f"{config}.yaml").read_text())
    blocks = re.findall(r"```yaml\n(.*?)```", (TUTORIALS / page).read_text(), flags=re.DOTALL)
    assert blocks
    for block in blocks:
        fragment = yaml.safe_load(block)
        assert isinstance(fragment, dict)
        assert _within(fragment, study) == [], block


def test_moordyn_import_tutorial(results: Path, tmp_path: Path, capsys) -> None:  # noqa: ANN001
    """The MoorDyn tutorial's study is what `cablestudy import` writes from MoorDyn's own
    WD0050_Chain.txt, plus the offset sweep the page shows (so the page, the config and
    the importer cannot drift apart); the importer names what it leaves out; and the
    restoring curve is physical: moving the vessel towards the anchor slackens the chain
    (fairlead tension falls, laid length grows), the fairlead's vertical force is the
    weight in water of the suspended length, and the anchor carries the horizontal pull
    less the laid length's friction, or nothing."""
    source = "tests/data/moordyn/tests/Mooring/WD0050_Chain.txt"
    here = Path.cwd()
    os.chdir(ROOT)
    try:
        code = main(
            ["import", "moordyn", source, "--line", "1", "--name", "tutorial-moordyn-import"]
        )
    finally:
        os.chdir(here)
    assert code == 0
    out = capsys.readouterr()
    assert "not modelled by cablestudy (not imported)" in out.err and "fileIC" in out.err
    sweep = "sweep:\n  ends.b.position.0: {start: 0.0, stop: 24.0, num: 9, name: offset}\n"
    assert (CONFIGS / "tutorial-moordyn-import.yaml").read_text() == out.out + sweep

    ds = xr.load_dataset(results / "tutorial-moordyn-import.nc")
    assert (ds.status == 0).all()
    tension, laid = ds.tension_b.values, ds.laid_length.values
    assert np.all(np.diff(tension) < 0) and np.all(np.diff(laid) > 0)
    seg = _segments("tutorial-moordyn-import")[0]
    w = (seg["mass_per_length"] - 1025.0 * np.pi * seg["diameter"] ** 2 / 4.0) * 9.80665
    vertical = -ds.force_b.sel(component="z").values
    np.testing.assert_allclose(vertical, w * (seg["length"] - laid), rtol=RTOL)
    horizontal = -ds.force_b.sel(component="x").values  # the line pulls B towards +x
    anchor = np.hypot(*(ds.force_a.sel(component=c).values for c in ("x", "y")))
    expected = np.maximum(-horizontal - 0.5 * w * laid, 0.0)
    np.testing.assert_allclose(anchor, expected, rtol=RTOL, atol=RTOL * np.max(-horizontal))
