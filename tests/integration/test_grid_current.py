"""A static sweep in a current, YAML -> netCDF: the drag iteration runs per case inside the
compiled batch (:mod:`cablestudy.statics.batch_drag`), so no case falls back to the
general solver; every case equals the same case run alone, bit for bit; and the end
forces balance the drag integrated over the line the dataset holds."""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from cablestudy.physics.current import current_velocity
from cablestudy.physics.hydro import drag_per_length
from tests.sweep_contract import alone_faults, run, set_path, study_text, with_sweep

#: still water among them: that case goes to the still-water kernel in the same batch
SPEEDS = [0.0, 0.75, 1.5]
SPANS = [100.0, 119.0]

#: a sheared current turning with depth (heading 90 deg at the surface, 30 at -100 m),
#: its two speeds swept together, by the fairlead's horizontal position
SWEEP = {
    "zip": [
        {
            "name": "speed",
            "environment.current.0.speed": SPEEDS,
            "environment.current.1.speed": [0.4 * v for v in SPEEDS],
        }
    ],
    "ends.b.position.0": {"values": SPANS, "name": "span"},
}


def _text(name: str) -> str:
    text = study_text("current", None, name).replace(
        "{z: -100.0, speed: 0.5, heading_deg: 90.0}", "{z: -100.0, speed: 0.2, heading_deg: 30.0}"
    )
    return text.replace("static: {nodes: 21}", "static: {nodes: 21, tolerance: 1.0e-10}")


@pytest.fixture(scope="module")
def swept(tmp_path_factory: pytest.TempPathFactory):  # noqa: ANN201
    folder = tmp_path_factory.mktemp("grid-current")
    text = with_sweep(_text("gc"), SWEEP)
    code, ds = run(folder, text)
    assert code == 0 and ds is not None
    return folder, text, ds


def test_a_current_sweep_runs_in_the_drag_kernel_with_no_fallback(swept) -> None:  # noqa: ANN001
    """Every case of the current-speed x span sweep is solved (status 0) by the compiled
    drag iteration: the dataset counts no case handed to the general solver."""
    _, _, ds = swept
    assert ds.sizes["speed"] == 3 and ds.sizes["span"] == 2
    assert int((ds["status"] != 0).sum()) == 0
    assert ds.attrs["cases_fallback"] == 0 and ds.attrs["fallback_reasons"] == ""


@pytest.mark.parametrize(("i", "j"), [(0, 0), (2, 1)])
def test_a_swept_current_case_equals_the_case_run_alone(swept, i: int, j: int) -> None:  # noqa: ANN001
    """Case (speed i, span j) of the grid against the same study written out with those
    values and run alone through ``cablestudy run``: every result bit for bit (speed 0:
    the still-water kernel's case inside the current's batch)."""
    folder, text, ds = swept
    alone = _text(f"gc-alone-{i}-{j}")
    alone = set_path(alone, "environment.current.0.speed", SPEEDS[i])
    alone = set_path(alone, "environment.current.1.speed", 0.4 * SPEEDS[i])
    alone = set_path(alone, "ends.b.position.0", SPANS[j])
    code, one = run(folder / f"alone-{i}-{j}", alone)
    assert code == 0 and one is not None
    assert alone_faults(ds.isel(span=j), one, "speed", i) == []


def test_the_end_forces_balance_the_drag_integrated_along_the_line(swept) -> None:  # noqa: ANN001
    """The whole line in equilibrium, horizontally: the forces it exerts on its two end
    attachments sum to the drag on it, force_a + force_b = integral of the drag per
    length (its weight is vertical). The drag is integrated here from the dataset's
    nodes: per interval the drag law on its chord at the current of its mid-height, times
    its stretched length -- the solver's drag elements are these intervals (20 of them,
    the nodes' spacing). The solver's shape carries the drag of the previous iterate of
    its drag loop, which differs from this one by at most the load tolerance (1e-10 of
    the line's loads); allowed: 10x that, plus round-off of the tensions."""
    _, text, ds = swept
    data = yaml.safe_load(text)
    seg = data["line"]["segments"][0]
    rho = 1025.0
    for i, v in enumerate(SPEEDS):
        rows = [(0.0, v, 90.0), (-100.0, 0.4 * v, 30.0)]
        z = np.array([-100.0, 0.0])
        vel = np.array(
            [[r[1] * np.cos(np.radians(r[2])), r[1] * np.sin(np.radians(r[2])), 0.0] for r in rows]
        )[::-1]
        for j in range(len(SPANS)):
            case = ds.isel(speed=i, span=j)
            r = np.stack([case[c].values for c in ("x", "y", "z")], axis=1)
            chord = np.diff(r, axis=0)
            lc = np.linalg.norm(chord, axis=1)
            t = chord / lc[:, None]
            U = current_velocity(0.5 * (r[:-1, 2] + r[1:, 2]), z, vel)
            n = len(lc)
            f = drag_per_length(
                U,
                t,
                density=rho,
                diameter=np.full(n, seg["diameter"]),
                drag_normal=np.full(n, 1.2),
                drag_tangential=np.full(n, 0.01),
            )
            drag = np.sum(f * lc[:, None], axis=0)
            ends = (case["force_a"] + case["force_b"]).values
            weight = 9.80665 * seg["mass_per_length"] * seg["length"]
            scale = weight + float(np.sum(np.linalg.norm(f, axis=1) * lc))
            allowed = 10 * 1e-10 * scale + 1e-12 * float(case["tension"].max())
            assert np.max(np.abs(ends[:2] - drag[:2])) <= allowed, (v, SPANS[j])
            assert np.hypot(*drag[:2]) >= 0.01 * v**2 * seg["length"]  # the drag is there
