"""A static sweep in a current with the towed end as end A (end B fixed), YAML -> netCDF:
the compiled drag iteration solves it from B (:mod:`cablestudy.statics.batch_drag`), so
no case falls back to the general solver, and the study written from the other end (ends
swapped, segments and clump in reverse order) gives the mirrored answer to round-off."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sweep_contract import run, with_sweep

SPEEDS = [0.5, 1.5]
PULLS = [-2000.0, -6000.0]

#: a two-segment tow cable with a clump, in a sheared current turning with depth;
#: written from the towed body (end A) to the stern (end B)
TOWED_A = """name: NAME
environment:
  fluid: water
  current:
    - {z: 0.0, speed: 1.0, heading_deg: 180.0}
    - {z: -100.0, speed: 0.5, heading_deg: 150.0}
line:
  segments:
SEGMENTS
  attachments:
    - {s: S_CLUMP, force: [0.0, 0.0, -800.0]}
ends:
END_A
END_B
analysis:
  static: {nodes: 21, tolerance: 1.0e-10}
"""
HEAVY = (
    "    - {length: 120.0, diameter: 0.04, mass_per_length: 5.0, weight_in_fluid: 40.0,"
    " axial_stiffness: 8.0e+7, drag_normal: 1.5, drag_tangential: 0.01}"
)
LIGHT = (
    "    - {length: 180.0, diameter: 0.03, mass_per_length: 3.0, weight_in_fluid: 22.0,"
    " axial_stiffness: 5.0e+7, drag_normal: 1.2, drag_tangential: 0.01}"
)
BODY = "{kind: force, force: [-1000.0, 0.0, -5000.0]}"
STERN = "{kind: fixed, position: [0.0, 0.0, 0.0]}"


def _texts() -> tuple[str, str]:
    """(end A towed, the same written from the stern: end A fixed, end B towed)."""
    towed_a = (
        TOWED_A.replace("NAME", "towed-a")
        .replace("SEGMENTS", f"{HEAVY}\n{LIGHT}")
        .replace("S_CLUMP", "100.0")
        .replace("END_A", f"  a: {BODY}")
        .replace("END_B", f"  b: {STERN}")
    )
    towed_b = (
        TOWED_A.replace("NAME", "towed-b")
        .replace("SEGMENTS", f"{LIGHT}\n{HEAVY}")
        .replace("S_CLUMP", "200.0")
        .replace("END_A", f"  a: {STERN}")
        .replace("END_B", f"  b: {BODY}")
    )
    sweep = {
        "zip": [
            {
                "name": "speed",
                "environment.current.0.speed": SPEEDS,
                "environment.current.1.speed": [0.5 * v for v in SPEEDS],
            }
        ],
    }
    a = with_sweep(towed_a, {**sweep, "ends.a.force.0": {"values": PULLS, "name": "pull"}})
    b = with_sweep(towed_b, {**sweep, "ends.b.force.0": {"values": PULLS, "name": "pull"}})
    return a, b


@pytest.fixture(scope="module")
def both(tmp_path_factory: pytest.TempPathFactory):  # noqa: ANN201
    folder = tmp_path_factory.mktemp("grid-current-reversed")
    a, b = _texts()
    code_a, ds_a = run(folder / "a", a)
    code_b, ds_b = run(folder / "b", b)
    assert code_a == 0 and code_b == 0 and ds_a is not None and ds_b is not None
    return ds_a, ds_b


def test_a_towed_end_a_sweep_runs_in_the_drag_kernel_with_no_fallback(both) -> None:  # noqa: ANN001
    """Every case of both studies is solved and verified (status 0) by the compiled drag
    iteration: no case handed to the general solver."""
    for ds in both:
        assert ds.sizes["speed"] == 2 and ds.sizes["pull"] == 2
        assert int((ds["status"] != 0).sum()) == 0
        assert ds.attrs["cases_fallback"] == 0 and ds.attrs["fallback_reasons"] == ""


def test_swapping_the_ends_in_the_yaml_mirrors_the_dataset(both) -> None:  # noqa: ANN001
    """The same cable written from either end: tension and node positions mirrored along
    s, the forces on the end attachments swapped, the end tensions swapped. The two
    studies reach the kernel as the same numbers but for the sample points (L - s
    against s) and the clump's arc length (L - (L - 200) against 100), one ulp of L each:
    the answers differ by round-off of the iteration (1e-12 of the largest tension and of
    the length, as the kernel against the general solver in the unit tests)."""
    ds_a, ds_b = both
    F = float(ds_b["tension"].max())
    L = 300.0
    assert float(np.max(np.abs(ds_a["tension"].values[..., ::-1] - ds_b["tension"].values))) <= (
        1e-12 * F
    )
    for name in ("x", "y", "z"):
        gap = np.abs(ds_a[name].values[..., ::-1] - ds_b[name].values)
        assert float(np.max(gap)) <= 1e-12 * L, name
    for one, other in (("force_a", "force_b"), ("tension_a", "tension_b")):
        assert float(np.max(np.abs(ds_a[one].values - ds_b[other].values))) <= 1e-12 * F
    # the drag is there: the body's pull and the current set the cable off the x-z plane
    assert float(np.max(np.abs(ds_b["y"].values))) > 1.0
