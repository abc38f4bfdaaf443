"""A static sweep in a current over a seabed, YAML -> netCDF: the lines that hang free
are solved by the compiled drag iteration (:mod:`cablestudy.statics.batch_drag`), equal
bit for bit to the same study without a seabed; the short spans whose sag reaches the
seabed go to the general solver, which lays them, and the dataset counts them with the
reason."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sweep_contract import run, with_sweep

#: a 300 m wire between fixed ends 50 and 100 m deep, in a sheared current turning with
#: depth, over a seabed at 200 m: at a 100 m span it sags onto the seabed, at 160 and
#: 250 m it hangs free (lowest points near -191 and -147 m)
TEXT = """name: NAME
environment:
  fluid: water
SEABED  current:
    - {z: 0.0, speed: 1.0, heading_deg: 0.0}
    - {z: -200.0, speed: 0.5, heading_deg: 60.0}
line:
  segments:
    - {length: 300.0, diameter: 0.05, mass_per_length: 10.0, weight_in_fluid: 80.0,
       axial_stiffness: 2.0e+8, drag_normal: 1.2, drag_tangential: 0.01}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -50.0]}
  b: {kind: fixed, position: [220.0, 0.0, -100.0]}
analysis:
  static: {nodes: 21, tolerance: 1.0e-10}
"""
SWEEP = {
    "zip": [
        {
            "name": "speed",
            "environment.current.0.speed": [0.2, 1.0],
            "environment.current.1.speed": [0.1, 0.5],
        }
    ],
    "ends.b.position.0": {"values": [100.0, 160.0, 250.0], "name": "span"},
}
DEPTH = 200.0


@pytest.fixture(scope="module")
def both(tmp_path_factory: pytest.TempPathFactory):  # noqa: ANN201
    folder = tmp_path_factory.mktemp("grid-current-seabed")
    seabed = TEXT.replace("NAME", "over").replace(
        "SEABED", f"  depth: {DEPTH}\n  seabed: {{friction: 0.3}}\n"
    )
    free = TEXT.replace("NAME", "free").replace("SEABED", "")
    code_s, ds_s = run(folder / "over", with_sweep(seabed, SWEEP))
    code_f, ds_f = run(folder / "free", with_sweep(free, SWEEP))
    assert code_s == 0 and code_f == 0 and ds_s is not None and ds_f is not None
    return ds_s, ds_f


def test_lines_reaching_the_seabed_are_laid_by_the_general_solver_and_counted(both) -> None:  # noqa: ANN001
    """All cases verified (status 0); the two at the 100 m span rest on the seabed (laid
    length > 0, lowest node on it) and are the only ones the general solver took, counted
    with the reason; the others hang free above the seabed."""
    ds, _ = both
    assert int((ds["status"] != 0).sum()) == 0
    assert ds.attrs["cases_fallback"] == 2
    assert ds.attrs["fallback_reasons"] == "2 x its solution touches the seabed"
    laid = ds["laid_length"].values
    assert np.all(laid[:, 0] > 0.0) and np.all(laid[:, 1:] == 0.0)
    assert np.allclose(ds["z"].min("s").values[:, 0], -DEPTH, rtol=0.0, atol=1e-6)
    assert np.all(ds["z"].min("s").values[:, 1:] > -DEPTH + 1.0)
    warned = np.char.find(ds["warning"].values.astype(str), "touches the seabed") >= 0
    assert np.array_equal(warned, laid > 0.0)


def test_a_seabed_the_line_does_not_reach_changes_nothing(both) -> None:  # noqa: ANN001
    """The free-hanging cases over the seabed equal the same cases with no seabed bit for
    bit: the compiled drag iteration runs the same steps, testing each shape against the
    seabed, and none reaches it."""
    ds, free = both
    assert free.attrs["cases_fallback"] == 0
    for name in ("x", "y", "z", "tension", "force_a", "force_b", "static_iterations"):
        a = ds[name].isel(span=slice(1, None)).values
        b = free[name].isel(span=slice(1, None)).values
        assert np.array_equal(a, b), name
    # the current is there: it sets the wire off the x-z plane
    assert float(np.max(np.abs(ds["y"].values))) > 1.0
