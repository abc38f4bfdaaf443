"""A chain anchored on a sloped seabed, its laid part across the slope, in a current,
YAML -> netCDF (the general solver's drag iteration with seabed contact).

The seabed rises at 5 deg towards +x; the chain runs from the anchor at (0, 0, -30) to
end B near (0, 190, -15), so its laid part lies across the slope and friction must hold
the weight's part down the slope across it, w c per metre. Before the laid part took
that share of Coulomb's cone (:func:`cablestudy.statics.seabed.along_friction`) it
mobilised the full mu w n_z along the line on top of it, and the whole-line check refused
the state (status 11) at B 195 m out with friction 0.1. Now those cases solve and verify;
without friction no straight laid line holds, and that is refused by name."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from tests.sweep_contract import run, with_sweep

TEXT = """name: NAME
environment:
  fluid: water
  depth: 30.0
  seabed: {slope_deg: 5.0, slope_heading_deg: 0.0, friction: 0.1}
CURRENTline:
  segments:
    - {length: 200.0, diameter: 0.1533, mass_per_length: 141.0, axial_stiffness: 6.0e+8,
       drag_normal: 2.4, drag_tangential: 1.15}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [0.0, 190.0, -15.0]}
analysis:
  static: {nodes: 41}
"""
#: end B over a grid around (0, 190, -15) [m]; the friction 0.1 cases at 195 m failed
SWEEP = {
    "ends.b.position.0": [-10.0, -5.0, 0.0, 5.0, 10.0],
    "ends.b.position.1": [190.0, 195.0],
    "environment.seabed.friction": [0.0, 0.1],
}
#: submerged weight of the chain [N/m]: mass less displaced water, times g
WEIGHT = (141.0 - 1025.0 * math.pi / 4.0 * 0.1533**2) * 9.80665
SLOPE = math.radians(5.0)


def current(speed: float, heading: float) -> str:
    return f"  current:\n    - {{z: 0.0, speed: {speed}, heading_deg: {heading}}}\n"


def study(name: str, current_text: str, sweep: dict) -> str:
    return with_sweep(TEXT.replace("NAME", name).replace("CURRENT", current_text), sweep)


@pytest.fixture(scope="module")
def runs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, xr.Dataset]:
    """The grid in a 0.5 m/s current at heading 60 deg; its mirror in the vertical xz
    plane (B at -y, heading -60 deg); the friction 0.1 cases in a 1e-4 m/s current and
    in still water (the compiled seabed-contact kernel)."""
    folder = tmp_path_factory.mktemp("slope-cross")
    mirrored = dict(SWEEP, **{"ends.b.position.1": [-190.0, -195.0]})
    rough = dict(SWEEP, **{"environment.seabed.friction": [0.1]})
    texts = {
        "cross": study("cross", current(0.5, 60.0), SWEEP),
        "mirror": study("mirror", current(0.5, -60.0), mirrored),
        "calm": study("calm", current(1.0e-4, 60.0), rough),
        "still": study("still", "", rough),
    }
    out = {}
    for name, text in texts.items():
        code, ds = run(folder / name, text)
        assert ds is not None, (name, code)
        out[name] = ds
    return out


def test_the_former_failures_solve_and_verify_and_frictionless_ones_are_refused(runs) -> None:  # noqa: ANN001
    ds = runs["cross"]
    rough = ds.sel(friction=0.1)
    assert np.all(rough["status"] == 0), rough["message"].values
    assert np.all(rough["laid_length"] > 100.0)  # the laid part is long: the case tested
    smooth = ds.sel(friction=0.0)
    laid = np.isfinite(smooth["laid_length"].values)
    for status, message in zip(
        smooth["status"].values.ravel(), smooth["message"].values.ravel(), strict=True
    ):
        assert status == 4
        assert "sliding sideways" in str(message) or "slack" in str(message), message
    assert not np.any(laid)
    assert np.all(np.isnan(smooth["tension"].values))


def test_the_laid_part_holds_the_cross_slope_weight_within_coulombs_cone(runs) -> None:  # noqa: ANN001
    """Along the laid part, where it is tensioned, the tension grows towards the
    touchdown by w (sqrt((mu n_z)^2 - c^2) + e_z) per metre of unstretched length: the
    seabed's tangential reaction, friction, is then exactly mu times its normal one
    (c = |n_x e_y - n_y e_x| from the laid line's direction e). The laid tension is linear
    in s, so the difference quotient is exact; the solver's tolerance (1e-9 of the
    forces) leaves a relative error near 1e-9 / (1 - T_anchor / T_td), allowed 1e-6."""
    ds = runs["cross"].sel(friction=0.1)
    n = np.array([-math.sin(SLOPE), 0.0, math.cos(SLOPE)])
    s = ds["s"].values
    checked = 0
    for x in ds["position_0"].values:
        for y in ds["position_1"].values:
            case = ds.sel(position_0=x, position_1=y)
            r = np.stack([case[k].values for k in ("x", "y", "z")], axis=1)
            t = case["tension"].values
            on = s <= float(case["laid_length"])
            both = on[:-1] & on[1:] & (t[:-1] > 0.0) & (t[1:] > 0.0)
            for i in np.flatnonzero(both):
                e = (r[i + 1] - r[i]) / np.linalg.norm(r[i + 1] - r[i])
                c = n[0] * e[1] - n[1] * e[0]
                rate = WEIGHT * (math.sqrt((0.1 * n[2]) ** 2 - c * c) + e[2])
                got = (t[i + 1] - t[i]) / (s[i + 1] - s[i])
                assert got == pytest.approx(rate, rel=1e-6)
                checked += 1
    assert checked > 50


def test_mirroring_the_current_heading_mirrors_the_solution(runs) -> None:  # noqa: ANN001
    """B at -y and the current at -60 deg is the xz mirror image (the seabed's slope
    along x is its own mirror): y and the forces' y component change sign, the rest is
    equal to the solver's tolerance (1e-9 relative, allowed 1e-7 of the scale)."""
    a, b = runs["cross"], runs["mirror"]
    ok = a["status"].values == 0
    assert np.array_equal(ok, b["status"].values == 0)
    for name, sign in (("x", 1.0), ("y", -1.0), ("z", 1.0), ("tension", 1.0)):
        va, vb = a[name].values, b[name].values
        scale = np.nanmax(np.abs(va))
        np.testing.assert_allclose(sign * vb[ok], va[ok], rtol=0.0, atol=1e-7 * scale)
    fa, fb = a["force_b"].values[ok], b["force_b"].values[ok]
    np.testing.assert_allclose(fb * [1.0, -1.0, 1.0], fa, rtol=0.0, atol=1e-7 * np.abs(fa).max())


def test_results_are_continuous_over_the_grid_of_end_positions(runs) -> None:  # noqa: ANN001
    """Across end B's x (-10 to 10 m in 5 m steps) the tension at B and the laid length
    are smooth: the second difference about x = 0 over 10 m steps is four times that over
    5 m steps (h^2 f'' each, to a relative O(h^2 / l^2), l the scale over which f'' varies:
    allowed 3 to 5.5), where a jump of size J between two solution branches would make
    both about J."""
    ds = runs["cross"].sel(friction=0.1)
    for values in (ds["tension_b"].values, ds["laid_length"].values):
        fine = values[1] - 2.0 * values[2] + values[3]
        coarse = values[0] - 2.0 * values[2] + values[4]
        ratio = coarse / fine
        assert np.all((ratio >= 3.0) & (ratio <= 5.5)), values


def test_the_zero_current_limit_is_the_still_water_solution(runs) -> None:  # noqa: ANN001
    """At 1e-4 m/s the drag per metre, 0.5 rho C_d d v^2 = 1.9e-5 N/m, is 1.5e-8 of the
    chain's weight: the general solver's drag iteration with seabed contact then gives
    the still-water contact kernel's state to well within 1e-6 of the forces (and
    1e-6 m), the solvers' own tolerance being 1e-9."""
    calm, still = runs["calm"], runs["still"]
    assert np.all(calm["status"] == 0) and np.all(still["status"] == 0)
    for name in ("x", "y", "z", "laid_length"):
        np.testing.assert_allclose(calm[name].values, still[name].values, rtol=0.0, atol=1e-6)
    for name in ("tension", "force_a", "force_b"):
        va, vb = calm[name].values, still[name].values
        np.testing.assert_allclose(va, vb, rtol=0.0, atol=1e-6 * np.abs(vb).max())
