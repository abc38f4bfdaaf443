"""A static sweep of a chain anchored on the seabed in a current, YAML -> netCDF: every
case rests on the seabed and is solved by the compiled drag iteration with seabed
contact (:mod:`cablestudy.statics._drag_inner`), none by the general solver; each case
equals the same case run alone through ``cablestudy run`` bit for bit; and the records
are the case-by-case path's (the general solver's) to round-off."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.study.loader import load_study
from cablestudy.study.problem import static_problem
from tests.sweep_contract import alone_faults, run, set_path, with_sweep

#: a studless chain from an anchor on a seabed 100 m deep sloping 1 deg (friction 0.5)
#: to a fairlead 10 m deep, in a current sheared and turning with depth
TEXT = """name: NAME
environment:
  fluid: water
  depth: 100.0
  seabed: {slope_deg: 1.0, slope_heading_deg: 20.0, friction: 0.5}
  current:
    - {z: 0.0, speed: 1.0, heading_deg: 30.0}
    - {z: -100.0, speed: 0.4, heading_deg: 80.0}
line:
  segments:
    - {length: 300.0, diameter: 0.076, mass_per_length: 126.0, axial_stiffness: 5.0e+8,
       drag_normal: 2.4, drag_tangential: 0.4}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [250.0, 0.0, -10.0]}
analysis:
  static: {nodes: 21, tolerance: 1.0e-10}
"""
SPEEDS = [0.3, 1.2]
OFFSETS = [230.0, 260.0]
SWEEP = {
    "zip": [
        {
            "name": "speed",
            "environment.current.0.speed": SPEEDS,
            "environment.current.1.speed": [0.4 * v for v in SPEEDS],
        }
    ],
    "ends.b.position.0": {"values": OFFSETS, "name": "offset"},
}


def _alone(i: int, j: int) -> str:
    text = TEXT.replace("NAME", f"anchored-{i}-{j}")
    text = set_path(text, "environment.current.0.speed", SPEEDS[i])
    text = set_path(text, "environment.current.1.speed", 0.4 * SPEEDS[i])
    return set_path(text, "ends.b.position.0", OFFSETS[j])


@pytest.fixture(scope="module")
def swept(tmp_path_factory: pytest.TempPathFactory):  # noqa: ANN201
    folder = tmp_path_factory.mktemp("grid-current-anchored")
    code, ds = run(folder, with_sweep(TEXT.replace("NAME", "anchored"), SWEEP))
    assert code == 0 and ds is not None
    return folder, ds


def test_every_case_rests_on_the_seabed_in_the_compiled_batch(swept) -> None:  # noqa: ANN001
    """All four cases verified (status 0), each with a laid part from the anchor, and
    none handed to the general solver."""
    _, ds = swept
    assert int((ds["status"] != 0).sum()) == 0
    assert ds.attrs["cases_fallback"] == 0 and ds.attrs["fallback_reasons"] == ""
    assert np.all(ds["laid_length"].values > 10.0)
    assert float(np.max(np.abs(ds["y"].values))) > 1.0  # the current moves it sideways


@pytest.mark.parametrize(("i", "j"), [(0, 1), (1, 0)])
def test_a_case_equals_the_case_run_alone(swept, i: int, j: int) -> None:  # noqa: ANN001
    """Case (speed i, offset j) of the grid against the same study written out with those
    values and run alone through ``cablestudy run``: every result bit for bit."""
    folder, ds = swept
    code, one = run(folder / f"alone-{i}-{j}", _alone(i, j))
    assert code == 0 and one is not None
    assert alone_faults(ds.isel(offset=j), one, "speed", i) == []


def test_the_records_are_the_case_by_case_paths(swept, tmp_path) -> None:  # noqa: ANN001
    """Each case's fairlead force, laid length and shape equal the general solver's (the
    case-by-case path: :meth:`SemiAnalyticSolver.solve` with ``compiled=False``) to
    round-off, 1e-12 of the scale: the kernel runs its iteration step for step
    (:mod:`tests.unit.test_statics_batch_drag_anchored`), far inside the tolerance of
    1e-10 the study asks for."""
    _, ds = swept
    solver = SemiAnalyticSolver()
    for i in range(len(SPEEDS)):
        for j in range(len(OFFSETS)):
            path = tmp_path / f"case-{i}-{j}.yaml"
            path.write_text(_alone(i, j))
            ref = solver.solve(static_problem(load_study(path)[0]), compiled=False)
            case = ds.isel(speed=i, offset=j)
            F = float(np.max(ref.tension))
            assert np.max(np.abs(case["force_b"].values - ref.force_b)) <= 1e-12 * F
            assert abs(float(case["laid_length"]) - ref.laid_length) <= 1e-12 * 300.0
            pos = np.stack([case[k].values for k in ("x", "y", "z")], axis=1)
            assert np.max(np.abs(pos - ref.position)) <= 1e-12 * 300.0
