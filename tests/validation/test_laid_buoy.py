"""A buoy on the stretch of a mooring line that would lie on the seabed: YAML -> netCDF.

900 m of chain (216 mm, 288 kg/m, EA 1.23e9 N, two segments of 300 and 600 m) from an
anchor on the seabed (200 m deep, 800 m off) to a fairlead at the surface, a 5 m^3 buoy
at s = 300 m. Its net lift F = rho V g = 50.3 kN lifts the laid chain into an arch
between two touchdowns (a W near the touchdown); every static method failed on it
("seabed-contact Newton did not converge", even 'discrete', which started from the
catenary). Now 'discrete' solves it on its own and 'catenary' and 'shooting' (one laid
stretch) refuse it by name.

References. Frictionless, the laid chain carries one tension H on both sides of the
arch, so each half of the arch is an elastic catenary with horizontal force H whose
vertical force grows from 0 at its touchdown to F / 2 at the buoy: the buoy rises
(H / w) (sqrt(1 + (F / 2H)^2) - 1) + (F / 2)^2 / (2 w EA) above the seabed (w the
chain's weight in water per metre). H itself comes from the two-line system study (the
chain cut at the buoy, a free point; each line solved by the catenary method with its
own touchdown), which the closed form checks.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

G, RHO, DEPTH, S_BUOY, VOLUME = 9.81, 1025.0, 200.0, 300.0, 5.0
EA, MASS, DIAMETER = 1232572089.6, 288.0, 0.216
W = (MASS - RHO * np.pi / 4.0 * DIAMETER**2) * G  # chain's weight in water [N/m]
LIFT = RHO * VOLUME * G  # the buoy's net lift [N]
LENGTH = 900.0

CHAIN = f"diameter: {DIAMETER}, mass_per_length: {MASS}, axial_stiffness: {EA}"
ENDS = {"anchor": "[-800.0, 0.0, -200.0]", "fair": "[0.0, 0.0, 0.0]"}


def _env(friction: float) -> str:
    return (
        f"environment:\n  fluid: {{density: {RHO}}}\n  gravity: {G}\n  depth: {DEPTH}\n"
        f"  seabed: {{friction: {friction}}}\n"
    )


def _study(name: str, method: str, axis: str, volume: float, friction: float) -> str:
    return f"""\
name: {name}
{_env(friction)}line:
  segments:
    - {{length: 300.0, {CHAIN}}}
    - {{length: 600.0, {CHAIN}}}
  attachments:
    - {{s: {S_BUOY}, volume: {volume}}}
ends:
  a: {{kind: fixed, position: {ENDS["anchor"]}}}
  b: {{kind: fixed, position: {ENDS["fair"]}}}
analysis:
  static: {{nodes: 151, method: {method}}}
sweep:
  {axis}
"""


SYSTEM = f"""\
name: laidbuoy-system
{_env(0.0)}points:
  anchor: {{kind: fixed, position: {ENDS["anchor"]}}}
  buoy: {{kind: free, position: [-500.0, 0.0, -199.0], volume: {VOLUME}}}
  fair: {{kind: fixed, position: {ENDS["fair"]}}}
lines:
  l1: {{a: anchor, b: buoy, segments: [{{length: 300.0, {CHAIN}}}]}}
  l2: {{a: buoy, b: fair, segments: [{{length: 600.0, {CHAIN}}}]}}
analysis:
  static: {{nodes: 41}}
"""


def _run(tmp_path: Path, name: str, text: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / name
    main(["run", str(cfg), "--out", str(out), "--no-cache", "--no-progress"])
    return xr.load_dataset(out / f"{name}.nc")


def _line(tmp_path: Path, name: str, method: str, axis: str, friction: float = 0.0) -> xr.Dataset:
    return _run(tmp_path, name, _study(name, method, axis, VOLUME, friction))


def _arch_height(H: float, lift: float) -> float:
    """Rise [m] of the buoy above a flat seabed: each half of the arch an elastic
    catenary of horizontal force H [N] from vertical force 0 to lift / 2 [N]."""
    V = 0.5 * lift
    return H / W * (np.sqrt(1.0 + (V / H) ** 2) - 1.0) + V * V / (2.0 * W * EA)


def _seabed_reaction(r: xr.Dataset, lift: float) -> float:
    """The seabed's vertical reaction on the line [N]: what the whole-line balance
    leaves (the supports pull with -force_a, -force_b; weight down, lift up)."""
    fz = float(r["force_a"].sel(component="z") + r["force_b"].sel(component="z"))
    return fz + W * LENGTH - lift


def test_discrete_arch_converges_to_the_exact_arch_and_the_two_line_system(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    ref = _run(tmp_path, "laidbuoy-system", SYSTEM)
    assert int(ref["status"]) == 0, ref["message"].values
    H = float(ref["force_a"].sel(line="l1", component="x"))
    rise = float(ref["point_position"].sel(point="buoy", component="z")) + DEPTH
    # the system (each line a catenary solved to 1e-9) against the closed form on its
    # own H: both exact, so equal to the solver's tolerance on positions (1e-9 of
    # the line lengths, ~1e-6 m)
    assert abs(rise - _arch_height(H, LIFT)) < 1e-6, (rise, _arch_height(H, LIFT))
    assert 0.3 < rise < 0.6  # an arch of 0.44 m: 20 m of chain lifted by 50 kN

    # 150 and 600 elements (6 m and 1.5 m, the buoy on a node, equal elements on
    # both sides of it)
    ds = _line(tmp_path, "laidbuoy", "discrete", "analysis.static.nodes: [151, 601]")
    capsys.readouterr()
    assert np.all(ds["status"] == 0), ds["message"].values
    errors = []
    for n in (151, 601):
        r = ds.sel(nodes=n)
        h = LENGTH / (n - 1)
        # the laid chain's tension: the force on the anchor, horizontal
        fa = r["force_a"].values
        errors.append(abs(fa[0] - H))
        # within the discretisation's resolution, one element's weight (the whole-line
        # verification's allowance for a lumped line)
        assert errors[-1] < W * h, (n, fa[0], H)
        keep = np.isfinite(r["arc_length"].values)  # the longest node sweep sets s
        z, s = r["z"].values[keep] + DEPTH, r["arc_length"].values[keep]
        i = int(np.argmin(np.abs(s - S_BUOY)))
        # lifted clear of the seabed: the seabed does not hold the buoy down
        assert s[i] == S_BUOY and z[i] > 0.3
        # the arch is symmetric about the buoy (frictionless: H on both sides), to the
        # Newton tolerance (positions of 1e-9 relative over 900 m)
        k = np.arange(1, 20)
        np.testing.assert_allclose(z[i - k], z[i + k], rtol=0, atol=1e-6)
        # the vertical balance: the seabed carries the laid chain (its reaction pushes,
        # never pulls) to within the weight of the elements at the two touchdowns of
        # the arch and the main touchdown (each within one element of a node)
        R = _seabed_reaction(r, LIFT)
        assert R > 0.0
        assert abs(R - W * float(r["laid_length"])) < 3.0 * W * h, (R, float(r["laid_length"]))
        # the buoy's rise against the exact arch on the reference H: to the lumped
        # line's O(h^2) sag error, one element's sag under its weight h^2 w / (8 H)
        # times the arch's elements (the rise is their sum), plus 1 mm of penetration
        arch = LIFT / W
        allow = arch / h * h * h * W / (8.0 * H) + 1e-3
        assert abs(z[i] - rise) < allow, (n, z[i], rise, allow)
    # convergence under refinement: lumped loads on straight elements converge as h^2
    # (16x closer for 4x finer), the touchdowns on nodes cost some of it: at least 8x
    # (measured 53 N then 4.1 N, 13x)
    assert errors[1] < errors[0] / 8.0, errors


def test_discrete_arch_on_a_rough_seabed_balances_with_coulomb_friction(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """With friction 0.5 and a 20 m^3 buoy (lift 201 kN, an arch of 82 m), which Newton
    takes by continuation on the lift: the equilibrium of the whole line."""
    lift = RHO * 20.0 * G
    ds = _line(
        tmp_path, "laidbuoy-rough", "discrete", "line.attachments.0.volume: [20.0]", friction=0.5
    )
    capsys.readouterr()
    r = ds.isel(volume=0)
    assert int(r["status"]) == 0, r["message"].values
    R = _seabed_reaction(r, lift)
    # the seabed pushes, with the laid chain's weight (3 elements' resolution, above)
    h = LENGTH / 150
    assert R > 0.0 and abs(R - W * float(r["laid_length"])) < 3.0 * W * h
    # what the supports do not balance horizontally is friction: at most mu R
    fx = float(r["force_a"].sel(component="x") + r["force_b"].sel(component="x"))
    assert abs(fx) <= 0.5 * R
    z = r["z"].values + DEPTH
    assert float(z[int(np.argmin(np.abs(r["s"].values - S_BUOY)))]) > 1.0


@pytest.mark.parametrize("method", ["catenary", "shooting"])
def test_one_laid_stretch_methods_refuse_the_arch_by_name(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], method: str
) -> None:
    """Over a sweep (the batch kernels first for 'catenary'): without the buoy the line
    solves; with any lift, status 4 and a message naming the buoy, never a status-0
    answer with the buoy laid flat (as 'shooting' gave before)."""
    axis = "line.attachments.0.volume: [0.0, 0.5, 5.0]"
    ds = _line(tmp_path, f"laidbuoy-{method}", method, axis, friction=0.5)
    capsys.readouterr()
    assert int(ds["status"].sel(volume=0.0)) == 0, ds["message"].values
    for v in (0.5, 5.0):
        r = ds.sel(volume=v)
        assert int(r["status"]) == 4
        assert str(r["message"].values) == (
            "a buoy at s = 300 m lifts the line off the seabed between two touchdowns; "
            f"method '{method}' models one laid stretch; method 'discrete' models it"
        )


def test_moorpy_case6_w_solves_with_discrete(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """MoorPy's tests/case6.dat as one chain (a 200 m^3 buoy in the middle of 1320 m of
    chain between two fixed ends at the surface, a W; MoorPy's own equilibrium fails on
    it): 'discrete' solves it; the file is symmetric (ends at (-400, 0, 0) and
    (0, 400, 0), the buoy at mid-length), and so is the answer."""
    data = Path(__file__).parents[1] / "data" / "moorpy" / "tests" / "case6.dat"
    assert main(["import", "moordyn", str(data)]) == 0
    text = capsys.readouterr().out.replace("  static:\n", "  static:\n    method: discrete\n")
    ds = _run(tmp_path, "case6", text)
    capsys.readouterr()
    assert int(ds["status"]) == 0, ds["message"].values
    z = ds["z"].values
    # symmetric to the Newton tolerance on positions (1e-9 relative of 1320 m)
    np.testing.assert_allclose(z, z[::-1], rtol=0, atol=1e-5)
    w = (500.0 - 1025.0 * np.pi / 4.0 * 0.2**2) * 9.80665
    lift = 1025.0 * 200.0 * 9.80665
    held = -float(ds["force_a"].sel(component="z") + ds["force_b"].sel(component="z"))
    R = w * 1320.0 - lift - held
    h = 1320.0 / 40
    # lifted clear in the middle, laid on both sides (two laid stretches), the seabed
    # carrying them (within the resolution at the four touchdowns)
    assert z[20] > -300.0 + 100.0 and float(ds["laid_length"]) > 0.0
    assert R > 0.0 and abs(R - w * float(ds["laid_length"])) < 4.0 * w * h


def test_a_buoyant_piece_on_the_laid_stretch(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """20 m of 1 m float (300 kg/m: 5.0 kN/m of lift in water) at s = 290 to 310 m in
    place of chain: 'catenary' laid it flat (status 11, the seabed pulling it down) and
    'shooting' too; both now refuse it by name, and 'discrete' lifts it."""
    float_piece = "{length: 20.0, diameter: 1.0, mass_per_length: 300.0, axial_stiffness: 1.0e9}"
    text = (
        _study(
            "laidfloat",
            "catenary",
            "analysis.static.method: [catenary, shooting, discrete]",
            0.0,
            0.0,
        )
        .replace("    - {length: 300.0,", "    - {length: 290.0,", 1)
        .replace("    - {length: 600.0,", f"    - {float_piece}\n    - {{length: 590.0,")
        .replace("  attachments:\n    - {s: 300.0, volume: 0.0}\n", "")
    )
    ds = _run(tmp_path, "laidfloat", text)
    capsys.readouterr()
    for method in ("catenary", "shooting"):
        r = ds.sel({"method": method})
        assert int(r["status"]) == 4 and str(r["message"].values).startswith(
            "a buoyant piece at s = 290 to 310 m lifts the line off the seabed"
        ), r["message"].values
    r = ds.sel({"method": "discrete"})
    assert int(r["status"]) == 0, r["message"].values
    s, z = r["s"].values, r["z"].values + DEPTH
    assert np.all(z[(s > 290.0) & (s < 310.0)] > 0.1)
    lift = (RHO * np.pi / 4.0 - 300.0) * G * 20.0 + W * 20.0  # the float less the chain
    R = _seabed_reaction(r, lift)
    h = LENGTH / 150
    assert R > 0.0 and abs(R - W * float(r["laid_length"])) < 3.0 * W * h
