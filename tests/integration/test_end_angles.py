"""End to end (YAML -> netCDF) for the static ``elevation`` and ``azimuth`` at a line's
ends: for a line without bending stiffness the tangent there is the direction of the
end's tension vector, T(0) = force_a at A and T(L) = -force_b at B
(:func:`cablestudy.physics.profile.end_pulls`), exact, where the one-sided second-order
differences of the positions err most (a coarse mesh on a sharp bend); with bending
stiffness the end force carries shear, and the ends keep the differences."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr
from scipy.optimize import brentq

from cablestudy.cli import main

#: a symmetric elastic catenary between two points at equal height
W, L, SPAN, EA = 200.0, 100.0, 80.0, 1.0e8  # N/m in water, m, m, N

SYMMETRIC = f"""\
name: symmetricNODES
environment: {{fluid: water}}
line:
  segments:
    - {{length: {L}, diameter: 0.05, weight_in_fluid: {W}, axial_stiffness: {EA}}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -20.0]}}
  b: {{kind: fixed, position: [{SPAN}, 0.0, -20.0]}}
analysis:
  static: {{method: catenary, nodes: NODES}}
"""

#: random study seed 508 (tests/stress_studies.py) without its dynamics: a light
#: segment then a heavier one, both ends fixed, 11 nodes; the one-sided differences
#: put end B's elevation 0.27 rad off the end force's direction
SEED_508 = """\
name: {name}
environment: {{fluid: water}}
line:
  segments:
{segments}
ends:
  a: {{kind: fixed, position: [{a}]}}
  b: {{kind: fixed, position: [{b}]}}
analysis:
  static: {{method: {method}, nodes: 11}}
"""
SEG_1 = (
    "    - {length: 7.91532, diameter: 0.0128277, mass_per_length: 0.129447, "
    "axial_stiffness: 712135000.0, bending_stiffness: EI}"
)
SEG_2 = (
    "    - {length: 2.74332, diameter: 0.0234655, mass_per_length: 0.397887, "
    "axial_stiffness: 3450630000.0, bending_stiffness: EI}"
)
#: a bending stiffness the discrete method converges with on this line (50 N m^2 does not)
EI_BENT = 1.0
L_508 = 7.91532 + 2.74332
A_508, B_508 = "0.0, 0.0, -12.7282", "3.08653, 0.0, -3.86889"


def _run(tmp_path: Path, name: str, text: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / "out"
    assert main(["run", str(cfg), "--out", str(out), "--no-cache"]) == 0
    ds = xr.load_dataset(out / f"{name}.nc")
    assert np.all(np.asarray(ds["status"]) == 0), np.asarray(ds["message"])
    return ds


def _seed_508(tmp_path: Path, name: str, *, swapped: bool, ei: float, method: str) -> xr.Dataset:
    segs = [SEG_1, SEG_2][::-1] if swapped else [SEG_1, SEG_2]
    a, b = (B_508, A_508) if swapped else (A_508, B_508)
    text = SEED_508.format(
        name=name, segments="\n".join(segs).replace("EI", repr(ei)), a=a, b=b, method=method
    )
    return _run(tmp_path, name, text)


def _one_sided(ds: xr.Dataset, length: float) -> np.ndarray:
    """The old end elevations (A, B): second-order one-sided differences of the
    positions, as :func:`cablestudy.physics.profile.profile_quantities` takes inside."""
    r = np.stack([ds[c].values for c in "xyz"], axis=-1)
    s = np.linspace(0.0, length, r.shape[-2])  # the solvers' equally spaced nodes
    d = np.gradient(r, s, axis=-2, edge_order=2)
    elev = np.arctan2(d[..., 2], np.hypot(d[..., 0], d[..., 1]))
    return elev[..., [0, -1]]


def _direction(force: np.ndarray) -> float:
    return math.atan2(float(force[2]), math.hypot(float(force[0]), float(force[1])))


def test_a_symmetric_catenarys_end_angles_are_the_closed_form(tmp_path: Path) -> None:
    # the elastic catenary: half the span is (H / w) asinh(w L / (2 H)) + H L / (2 EA),
    # and by symmetry each end carries half the weight, V = w L / 2: the end slope is
    # atan(V / H), going down from A and up to B
    def half_span(h: float) -> float:
        return h / W * math.asinh(W * L / (2.0 * h)) + h * L / (2.0 * EA) - SPAN / 2.0

    h = brentq(half_span, 1.0, 1.0e7, xtol=1e-12, rtol=1e-15)
    slope = math.atan(W * L / (2.0 * h))
    for n, old_error in ((5, 0.05), (11, 0.008)):
        ds = _run(tmp_path, f"symmetric{n}", SYMMETRIC.replace("NODES", str(n)))
        elev, az = ds["elevation"].values, ds["azimuth"].values
        # the solver holds forces to 10 tol F (cablestudy/statics/verify.py, tol 1e-9,
        # F the total load ~ 2 |T| + w L ~ 4 |T|): the end force's direction to about
        # 4e-8 rad; 1e-7 rad allows that
        assert abs(elev[0] + slope) < 1e-7, (n, elev[0], -slope)
        assert abs(elev[-1] - slope) < 1e-7, (n, elev[-1], slope)
        assert abs(az[0]) < 1e-12 and abs(az[-1]) < 1e-12
        # the old one-sided differences, on the same positions: at 5 nodes off by
        # 0.0639 rad (3.7 deg) at each end, at 11 nodes by 0.0106 rad (measured; the new
        # values are off by 5.6e-16 rad): far outside the bound
        old = _one_sided(ds, L)
        assert abs(old[0] + slope) > old_error, (n, old[0] + slope)
        assert abs(old[1] - slope) > old_error, (n, old[1] - slope)


def test_seed_508s_end_angles_are_the_end_forces_directions(tmp_path: Path) -> None:
    ds = _seed_508(tmp_path, "s508", swapped=False, ei=0.0, method="shooting")
    fa, fb = ds["force_a"].values, ds["force_b"].values
    elev = ds["elevation"].values
    # exact to round-off by construction: what the test holds is that both callers
    # pass the end forces with the right signs (T(0) = force_a, T(L) = -force_b)
    assert abs(elev[0] - _direction(fa)) < 1e-6
    assert abs(elev[-1] - _direction(-fb)) < 1e-6
    # the difference it makes at 11 nodes on this light line's sharp bend: the one-sided
    # difference at B says -0.7994 rad, the end force -1.0683 rad (measured)
    old = _one_sided(ds, L_508)
    assert abs(old[1] - elev[-1]) > 0.2, (old, elev[[0, -1]])


def test_swapping_the_ends_mirrors_the_end_angles(tmp_path: Path) -> None:
    # the same line described from B: s' = L - s, dr/ds' = -dr/ds, so at the same
    # point the elevation changes sign and the azimuth turns by pi
    one = _seed_508(tmp_path, "fwd", swapped=False, ei=0.0, method="catenary")
    two = _seed_508(tmp_path, "rev", swapped=True, ei=0.0, method="catenary")
    e1, e2 = one["elevation"].values, two["elevation"].values
    a1, a2 = one["azimuth"].values, two["azimuth"].values
    # both solved to tol 1e-9 on forces (10 tol F each, F ~ 4 |T|): 1e-7 rad
    assert abs(e2[0] + e1[-1]) < 1e-7 and abs(e2[-1] + e1[0]) < 1e-7
    for i, j in ((0, -1), (-1, 0)):
        assert abs(math.cos(a2[i]) + math.cos(a1[j])) < 1e-7
        assert abs(math.sin(a2[i]) + math.sin(a1[j])) < 1e-7


def test_a_line_with_bending_stiffness_keeps_the_differences(tmp_path: Path) -> None:
    ds = _seed_508(tmp_path, "bent", swapped=False, ei=EI_BENT, method="discrete")
    old = _one_sided(ds, L_508)
    elev = ds["elevation"].values
    # the same differences (up to the round-off of the nodes' arc lengths)
    assert abs(elev[0] - old[0]) < 1e-12 and abs(elev[-1] - old[1]) < 1e-12
    # without it, the discrete method's ends take the end forces' directions
    free = _seed_508(tmp_path, "free", swapped=False, ei=0.0, method="discrete")
    elev = free["elevation"].values
    assert abs(elev[0] - _direction(free["force_a"].values)) < 1e-12
    assert abs(elev[-1] - _direction(-free["force_b"].values)) < 1e-12


def test_a_swept_studys_cases_take_their_own_end_forces(tmp_path: Path) -> None:
    # a sweep of end B's position runs as one grid (analyses/static_grid.py
    # array_outputs, many cases at once): each case's end angles are its own end
    # forces' directions, elevation and azimuth, to round-off
    text = SYMMETRIC.replace("NODES", "5").replace("symmetric5", "swept") + (
        "sweep:\n  ends.b.position: [[80.0, 0.0, -20.0], [60.0, 30.0, -10.0], "
        "[90.0, -20.0, -40.0]]\n"
    )
    ds = _run(tmp_path, "swept", text)
    elev, az = ds["elevation"].values, ds["azimuth"].values
    for i in range(3):
        fa, tb = ds["force_a"].values[i], -ds["force_b"].values[i]
        assert abs(elev[i, 0] - _direction(fa)) < 1e-12
        assert abs(elev[i, -1] - _direction(tb)) < 1e-12
        assert abs(az[i, 0] - math.atan2(fa[1], fa[0])) < 1e-12
        assert abs(az[i, -1] - math.atan2(tb[1], tb[0])) < 1e-12
    assert elev[1, 0] < 0.0 < elev[1, -1]  # down from A, up to B (B is higher: still)


def test_an_attachment_at_an_end_keeps_that_ends_difference(tmp_path: Path) -> None:
    # a clump weight at B itself: force_b carries it (the line's tangent just before B
    # is along -force_b plus the clump's weight, not -force_b), so B keeps the one-sided
    # difference; one 3 m from A leaves T(0) = force_a along the tangent at A
    text = (
        SYMMETRIC.replace("NODES", "11")
        .replace("symmetric11", "clump")
        .replace(
            "ends:",
            "  attachments:\n    - {s: 3.0, mass: 3000.0}\n    - {s: 100.0, mass: 3000.0}\nends:",
        )
    )
    ds = _run(tmp_path, "clump", text)
    elev = ds["elevation"].values
    old = _one_sided(ds, L)
    assert abs(elev[0] - _direction(ds["force_a"].values)) < 1e-12
    assert abs(elev[-1] - old[1]) < 1e-12
    assert abs(elev[-1] - _direction(-ds["force_b"].values)) > 0.3  # 0.94 against 1.38 rad
