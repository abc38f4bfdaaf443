"""Static settings swept as arrays (cablestudy.study.grid_lines.STATIC_SETTING): the node
count, the drag elements of a line in a current, the tolerance, the iteration limit.

The array chunk solves its cases per group of equal settings, each with its own
settings (cablestudy.analyses.static_grid_settings); the dataset must be the
case-by-case one bit for bit (the same kernels get the same numbers: no tolerance),
with the outputs along the line padded to the largest node count (then ``s`` is the node
index and ``arc_length`` a variable). Physics: the catenary is exact at any point, so
the tension at the points that several node counts share is the same; the end force of
a line in a current converges as the drag elements are refined, at the order of the
element load's quadrature. Invalid swept values are refused before any work, named."""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import static as static_analysis
from cablestudy.analyses.variables import KEPT_STATUSES
from cablestudy.run.runner import run_study
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid
from cablestudy.study.loader import StudyError
from tests.grid_bits import same_bits

#: a chain and a wire anchored on the seabed at A (the contact kernel) or hanging free
#: (the fairlead's offsets take it off the seabed at the short end), the node count
#: swept with the fairlead's offset; 100 m of line, so 11, 21 and 41 nodes share the
#: points at every 10 m exactly (linspace steps 10, 5 and 2.5 m are exact in binary)
NODES = """\
name: gn
environment: {fluid: water, depth: 30.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 60.0, diameter: 0.05, weight_in_fluid: 60.0, axial_stiffness: 2.0e8}
    - {length: 40.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
  attachments:
    - {s: 70.0, mass: 30.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 21}
sweep:
  analysis.static.nodes: [11, 21, 41]
  ends.b.position.0: {start: 84.0, stop: 96.0, num: 4, name: span}
"""
#: the node count on the second axis (a chunk's rows then hold every node count)
NODES_INNER = NODES.replace(
    "  analysis.static.nodes: [11, 21, 41]\n  ends.b.position.0: {start: 84.0, stop: 96.0, "
    "num: 4, name: span}\n",
    "  ends.b.position.0: {start: 84.0, stop: 96.0, num: 4, name: span}\n"
    "  analysis.static.nodes: [41, 11, 21]\n",
)
#: a wire in a current (the compiled drag iteration), its drag elements swept
DRAG = """\
name: gd
environment:
  fluid: water
  current: [{z: 0.0, speed: 1.0, heading_deg: 60.0}]
line:
  segments:
    - {length: 300.0, diameter: 0.05, weight_in_fluid: 80.0, axial_stiffness: 2.0e8,
       drag_normal: 1.2, drag_tangential: 0.01}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -50.0]}
  b: {kind: fixed, position: [200.0, 0.0, -200.0]}
analysis:
  static: {nodes: 21}
sweep:
  analysis.static.drag_elements: [5, 10, 20, 40, 80, 160]
  ends.b.position.0: [180.0, 220.0]
"""
#: the tolerance and the iteration limit swept with the node count (zipped axes)
TOLERANCE = NODES.replace(
    "  analysis.static.nodes: [11, 21, 41]\n",
    "  analysis.static.tolerance: [1.0e-6, 1.0e-9, 1.0e-12]\n"
    "  analysis.static.max_iterations: [3, 100]\n",
)


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


def _both(text: str, tmp_path: Path) -> tuple[xr.Dataset, xr.Dataset]:
    """The dataset of the array grid and that of every case solved alone."""
    src = parse_study_text(text, "gn.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays  # the compiled array route, not case by case
    fast = xr.load_dataset(
        run_study(src, grid, tmp_path / "g", scheduler="synchronous", use_cache=False).path
    )
    slow = xr.load_dataset(  # every case as a validated study, through evaluate_case
        run_study(
            src, replace(grid, chunked=False), tmp_path / "c", scheduler="synchronous",
            use_cache=False,
        ).path
    )  # fmt: skip
    return fast, slow


@pytest.mark.parametrize("text", [NODES, NODES_INNER], ids=["outer", "inner"])
def test_a_node_count_sweep_runs_as_arrays_with_the_case_datasets_bits(
    tmp_path: Path, text: str
) -> None:
    fast, slow = _both(text, tmp_path)
    kept = np.isin(slow["status"].values, KEPT_STATUSES)
    assert kept.all()
    assert float(slow["laid_length"].max()) > 0.0  # the contact kernel did run
    # the layout of a swept node count: s the node index, each case's arc lengths
    assert slow["s"].attrs["units"] == "1" and slow.sizes["s"] == 41
    assert "arc_length" in slow.data_vars
    same_bits(fast, slow)
    # padded beyond each case's own node count, by NaN
    n11 = fast.sel(nodes=11)
    assert np.isnan(n11["tension"].isel(s=slice(11, None))).all()
    assert np.isfinite(n11["tension"].isel(s=slice(0, 11))).all()
    # the catenary is exact at any point: the same end forces (the Newton iteration on
    # the ends does not see the output points) and the same tension at the shared points
    # (every 10 m), to round-off of the piece-wise closed forms: 1e-12 of the largest
    # tension (sums of a few dozen terms of that size, each exact to 1e-16 relative)
    t = {k: fast["tension"].sel(nodes=k).values for k in (11, 21, 41)}
    scale = float(np.nanmax(np.abs(t[41])))
    for k, step in ((21, 2), (41, 4)):
        assert np.max(np.abs(t[k][:, ::step][:, :11] - t[11][:, :11])) <= 1e-12 * scale
        for name in ("force_a", "force_b"):
            a = fast[name].sel(nodes=k).values
            assert np.max(np.abs(a - fast[name].sel(nodes=11).values)) <= 1e-12 * scale


def test_drag_elements_run_as_arrays_and_converge_at_second_order(tmp_path: Path) -> None:
    fast, slow = _both(DRAG, tmp_path)
    # five elements are too coarse for the whole-line check (its drag balance): recorded
    # as not verified, with the check's numbers, the same in both paths (below)
    status = slow["status"].values
    assert np.all(status[0] == 11) and "not verified" in str(slow["message"].values[0, 0])
    assert np.all(status[1:] == 0)
    assert int(slow["drag_iterations"][1:].min()) > 1  # the drag iteration ran
    same_bits(fast, slow)
    # the fairlead's tension against the element count (10 to 160): successive
    # differences fall by 2^p per halving, p the method's order. Each element carries the
    # drag of its chord's direction (a midpoint rule): p = 2, ratio 4; the next term of
    # the error (h^4) and the solver's tolerance (1e-9, far below the differences of
    # 1e-2 N and up) keep it within 4 +- 0.5 from 10 elements on (measured 3.93-4.04)
    tb = fast["tension_b"].values[1:]  # (elements, span)
    diff = np.abs(np.diff(tb, axis=0))
    ratio = diff[:-1] / diff[1:]
    assert np.all((ratio > 3.5) & (ratio < 4.5)), ratio


def test_tolerance_and_iteration_limit_sweeps_run_as_arrays_with_the_case_bits(
    tmp_path: Path,
) -> None:
    fast, slow = _both(TOLERANCE, tmp_path)
    same_bits(fast, slow)
    # three iterations do not settle the seabed contact: those cases fail (or go to the
    # general solver, which also stops at three), the others solve
    ok = slow["status"] == 0
    assert bool(ok.sel(max_iterations=100).all())
    assert not bool(ok.sel(max_iterations=3).all())
    # a tighter tolerance moves the fairlead tension by no more than the looser one's
    # allowance: 1e-6 relative (the solver's stopping test on the ends' misfit)
    tb = slow["tension_b"].sel(max_iterations=100)
    assert float(np.abs(tb.isel(tolerance=0) - tb.isel(tolerance=-1)).max()) <= 1e-6 * float(
        tb.max()
    )


@pytest.mark.parametrize(
    ("sweep", "path", "value"),
    [
        ("analysis.static.nodes: [1, 21]", "analysis.static.nodes", "1"),
        ("analysis.static.tolerance: [1.0e-9, 0.5]", "analysis.static.tolerance", "0.5"),
    ],
)
def test_an_invalid_swept_setting_is_refused_before_any_work(
    sweep: str, path: str, value: str
) -> None:
    text = NODES.replace("analysis.static.nodes: [11, 21, 41]", sweep)
    with pytest.raises(StudyError) as exc:
        expand_grid(parse_study_text(text, "gn.yaml"))
    msg = str(exc.value)
    assert path in msg and value in msg, msg


def test_drag_elements_swept_without_a_current_are_refused_by_name(tmp_path: Path) -> None:
    """Without a current no case uses drag elements: the grid leaves the arrays (whose
    support check reads the template only) and each swept value is refused, named."""
    from cablestudy import cli

    still = DRAG.replace("  current: [{z: 0.0, speed: 1.0, heading_deg: 60.0}]\n", "")
    assert not expand_grid(parse_study_text(still, "gd.yaml")).arrays
    path = tmp_path / "gd.yaml"
    path.write_text(still)
    with pytest.raises(StudyError) as exc:
        cli._load(str(path))
    msg = str(exc.value)
    assert "analysis.static.drag_elements" in msg and "no environment.current" in msg, msg


#: a wire in a current, its normal drag coefficient and added mass swept (each
#: combination one line, as for its loads)
HYDRO = DRAG.replace(
    "  analysis.static.drag_elements: [5, 10, 20, 40, 80, 160]\n",
    "  line.segments.0.drag_normal: [0.0, 0.6, 1.2, 2.4]\n"
    "  line.segments.0.added_mass_normal: [0.5, 1.0]\n",
).replace("drag_tangential: 0.01", "drag_tangential: 0.0")


def test_drag_and_added_mass_coefficient_sweeps_run_as_arrays_with_the_case_bits(
    tmp_path: Path,
) -> None:
    fast, slow = _both(HYDRO, tmp_path)
    assert (slow["status"] == 0).all()
    same_bits(fast, slow)
    # no static solver reads the added mass: equal cases, bit for bit
    for name in ("tension", "x", "y", "z", "force_a", "force_b"):
        a = fast[name].isel(added_mass_normal=0).values
        assert a.tobytes() == fast[name].isel(added_mass_normal=1).values.tobytes(), name
    # the whole line's balance across the plane of its ends (y): the ends hold what the
    # drag pushes, F_a,y + F_b,y = the line's drag in y (weight has none). Without drag
    # (C_N = 0, C_T = 0) it is zero to the solver's tolerance (1e-9 of the line's weight
    # of 24 kN: 1e-5 N allowed), and it grows with C_N
    fy = (fast["force_a"] + fast["force_b"]).sel(component="y").isel(added_mass_normal=0)
    drag_y = fy.values  # (drag_normal, span)
    assert np.max(np.abs(drag_y[0])) <= 1e-9 * 80.0 * 300.0
    assert np.all(np.diff(np.abs(drag_y), axis=0) > 0.0)
    # and without drag the line is the still-water one: its fairlead tension that of the
    # same study without a current, to the tolerance (1e-9 relative)
    still = HYDRO.replace("  current: [{z: 0.0, speed: 1.0, heading_deg: 60.0}]\n", "").replace(
        "  line.segments.0.drag_normal: [0.0, 0.6, 1.2, 2.4]\n"
        "  line.segments.0.added_mass_normal: [0.5, 1.0]\n",
        "",
    )
    src = parse_study_text(still, "gs.yaml")
    ref = xr.load_dataset(
        run_study(src, expand_grid(src), tmp_path / "s", scheduler="synchronous",
                  use_cache=False).path
    )  # fmt: skip
    t0 = fast["tension_b"].isel(drag_normal=0, added_mass_normal=0).values
    assert np.max(np.abs(t0 - ref["tension_b"].values)) <= 1e-9 * float(ref["tension_b"].max())
