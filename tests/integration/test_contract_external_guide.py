"""The user guide read from outside, as a mooring engineer new to cablestudy reads it:
README.md and docs/guide/*.md tried as printed (their YAML blocks taken from the pages),
and a first day's studies (tests/guide_contract.py) checked by hand physics: closed-form
catenary, force balance, symmetry, a static limit, MoorPy on the same line. Every
study goes YAML -> ``cablestudy run`` / ``validate`` -> netCDF read with xarray.

Defects found this way and fixed (each test below failed before its fix):
- docs/guide/sweeps.md's first example swept ``ends.b.position.0`` and the vector
  ``ends.b.position`` on two axes, which validation (rightly) refuses;
- that refusal read "the path is overlaps the swept path ...";
- README said the air of its example gives "no buoyancy": the 2417.9 N it quotes is the
  weight less the air's buoyancy (0.38 N);
- a study sweeping ``analysis.dynamic.method`` (or ``auto`` picking per case) wrote bare
  NaN, with status 0 and no ``nan_means``, in each method's own outputs for the cases of
  the other method (``dynamic_steps``, ``tension_amplitude_b``, ...);
- a system sweep run as arrays failed every case of a chunk as "LinAlgError: Singular
  matrix" (status 2) when one case's free points had a singular stiffness, instead of
  handing that case to the general solver (its own message, naming the line);
- the system frequency domain left ``steady_converged`` a bare NaN in a study mixing
  methods;
- results.md called ``elongation`` "the integral of T / EA": it is the strain by
  trapezoids between output points (O(h^2) off for a non-linear law);
- cli.md said `validate` imports none of the solvers (it loads no numba nor scipy);
- a study imported from a MoorPy design YAML described itself as "MoorDyn v2".
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from tests import guide_contract as gc

# ------------------------------------------------------------------ README


def test_readme_study_as_printed(tmp_path):
    """README's study block, copied as printed: its end tensions (printed to 0.1 N) and
    the supports' forces adding up to the weight in air (weight less the air's
    buoyancy: the analytic elastic catenary at tolerance 1e-12 balances to round-off,
    1e-9 relative allows the solver's tolerance times the line's tension scale)."""
    block = next(b for b in gc.yaml_blocks("README.md") if b.startswith("name: catenary-in-air"))
    ds = gc.run(tmp_path, block)
    assert abs(float(ds.tension_a) - 2164.8) <= 0.05
    assert abs(float(ds.tension_b) - 1956.9) <= 0.05
    weight = (2.466 - gc.RHO_AIR * math.pi * 0.02**2 / 4) * gc.G * 100.0
    total = (ds.force_a + ds.force_b).values
    np.testing.assert_allclose(total, [0.0, 0.0, -weight], rtol=0, atol=1e-9 * weight)
    assert abs(weight - 2417.9) <= 0.05  # the number README prints
    readme = (gc.ROOT / "README.md").read_text()
    assert "so no buoyancy" not in readme  # the air's buoyancy is counted (0.38 N here)
    # README's dataset table: every name it lists for a static study, with units
    table = {
        "s": "m", "x": "m", "y": "m", "z": "m", "tension": "N", "tension_wall": "N",
        "elevation": "rad", "azimuth": "rad", "force_a": "N", "force_b": "N",
        "tension_a": "N", "tension_b": "N", "laid_length": "m", "status": "1",
        "message": "1", "wall_time": "s", "static_status": "1", "warning": "1",
    }  # fmt: skip
    for name, units in table.items():
        assert ds[name].attrs["units"] == units, name
        assert ds[name].attrs.get("long_name"), name
    assert ds.x.dims == ("s",) and ds.force_a.dims == ("component",)
    for key in ("study_yaml", "study_sha256", "cablestudy_version", "solver_settings"):
        assert ds.attrs[key]


# ------------------------------------------------------------------ studies.md


def test_studies_guide_refusals_as_printed(tmp_path):
    """docs/guide/studies.md's first `validate` output: each fault it prints (field,
    value, allowed) is what validation says of a file with those faults."""
    printed = next(b for b in gc.text_blocks("docs/guide/studies.md") if "lenght" in b)
    expected = [m.group(1) for m in re.finditer(r"study\.yaml:\d+: (.*)", printed)]
    assert len(expected) == 3
    study = """\
name: bad
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - diameter: 0.02
      mass_per_length: 2.466
      length: -100.0
      lenght: 3
      axial_stiffness: 6.283e7
ends:
  a:
    kind: fixd
    position: [0.0, 0.0, 0.0]
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
"""
    import io
    from contextlib import redirect_stderr, redirect_stdout

    buf = io.StringIO()
    with redirect_stderr(buf), redirect_stdout(buf):
        assert gc.validate(tmp_path, study) == 2
    said = buf.getvalue()
    for line in expected:
        assert line in said, (line, said)


# ------------------------------------------------------------------ sweeps.md


SWEEP_BASE = """\
name: sweep-example
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}
"""


def test_sweeps_guide_examples_validate(tmp_path, capsys):
    """Both sweep blocks of docs/guide/sweeps.md, under a study they fit, validate; the
    first counts the product of its axes (3 x 82 x 5 x 2 x 2 x 3)."""
    blocks = [b for b in gc.yaml_blocks("docs/guide/sweeps.md") if b.startswith("sweep:")]
    assert len(blocks) == 2
    for i, block in enumerate(blocks):
        assert gc.validate(tmp_path, SWEEP_BASE + block, f"example{i}") == 0, capsys.readouterr()
    out = capsys.readouterr().out
    assert "14760 cases" in out and "4 cases" in out


def test_overlapping_sweep_paths_message(tmp_path, capsys):
    """A vector and one of its components on two axes: refused, naming both paths, in
    words a reader can parse."""
    text = SWEEP_BASE + (
        "sweep:\n"
        "  ends.b.position.0: [80.0, 90.0]\n"
        "  ends.b.position: {values: [[80.0, 0.0, -8.6], [90.0, 0.0, -8.6]]}\n"
    )
    assert gc.validate(tmp_path, text) == 2
    err = capsys.readouterr().err
    assert "sweep.ends.b.position: the path overlaps the swept path 'ends.b.position.0'" in err
    assert "is overlaps" not in err


# ------------------------------------------------------------------ a first day


def test_leg_against_moorpy(tmp_path):
    """A chain leg over an offset sweep: fairlead force and laid length as MoorPy's
    catenary (both exact elastic catenaries with a frictionless seabed; 1e-9 relative is
    far above both solvers' tolerances, 1e-12)."""
    catenary = pytest.importorskip("moorpy.Catenary", reason="MoorPy (the peers extra)").catenary
    ds = gc.run(tmp_path, gc.LEG)
    assert (ds.status == 0).all()
    for off in ds.offset.values:
        d = ds.sel(offset=off)
        _, _, hb, vb, info = catenary(off, 135.0, 600.0, 4.9e8, gc.W_CHAIN, CB=0.0, Tol=1e-12)
        # MoorPy's end forces are the line's on its ends, as force_a / force_b
        assert float(d.force_b[0]) == pytest.approx(hb, rel=1e-9)
        assert float(d.force_b[2]) == pytest.approx(vb, rel=1e-9)
        assert float(d.laid_length) == pytest.approx(info["LBot"], rel=1e-9)
        # the anchor on a frictionless seabed takes the horizontal tension only
        assert float(d.force_a[0]) == pytest.approx(-hb, rel=1e-9)
        assert abs(float(d.force_a[2])) <= -1e-9 * hb


def test_pretension_with_friction(tmp_path):
    """A mooring end's horizontal force swept on a seabed with friction 0.5: the end
    force is the one given, the fairlead carries the suspended weight, and the anchor the
    horizontal force less the friction mu w (laid length) (Coulomb friction on a laid
    chain that slides towards the fairlead); MoorPy's catenary with CB = 0.5 at the span
    found agrees (1e-8: the span comes from our solve at tolerance 1e-9)."""
    catenary = pytest.importorskip("moorpy.Catenary", reason="MoorPy (the peers extra)").catenary
    ds = gc.run(tmp_path, gc.PRETENSION)
    w = gc.W_CHAIN
    for h in ds.force_0.values:
        d = ds.sel(force_0=h)
        assert int(d.status) == 0
        laid = float(d.laid_length)
        assert -float(d.force_b[0]) == pytest.approx(h, rel=1e-12)
        assert -float(d.force_b[2]) == pytest.approx(w * (600.0 - laid), rel=1e-9)
        assert float(d.force_a[0]) == pytest.approx(max(h - 0.5 * w * laid, 0.0), rel=1e-9)
        span = float(d.x[-1] - d.x[0])
        fah, _, fbh, _, info = catenary(span, 135.0, 600.0, 4.9e8, w, CB=0.5, Tol=1e-12)
        assert fbh == pytest.approx(-h, rel=1e-8)  # the line's force on the fairlead
        assert fah == pytest.approx(float(d.force_a[0]), rel=1e-8)


def test_beam_current_mirror(tmp_path):
    """The same sheared beam current towards +y and towards -y: mirror images (y and
    the y forces change sign, everything else equal), to round-off of the drag
    iteration's arithmetic (1e-9 of the line's scale)."""
    ds = gc.run(tmp_path, gc.BEAM_CURRENT)
    assert (ds.status == 0).all()
    a, b = ds.isel(heading=0), ds.isel(heading=1)
    assert float(abs(a.y).max()) > 1.0  # the current does push the line sideways
    np.testing.assert_allclose(a.y, -b.y, atol=1e-9 * 600)
    np.testing.assert_allclose(a.x, b.x, atol=1e-9 * 600)
    np.testing.assert_allclose(a.tension, b.tension, rtol=1e-9)
    mirror = np.array([1.0, -1.0, 1.0])
    np.testing.assert_allclose(a.force_a, b.force_a * mirror, rtol=1e-9, atol=1e-6)


def test_tow_line_methods_agree(tmp_path):
    """A tow line at 2 m/s by the three static methods: the towed end's force is the
    given one reversed (force of the line on the body), and the methods agree on the
    fixed end's force to 2e-4 (the discrete model's 100 elements: an O(h^2) error, h/L =
    1e-2, here measured 7e-5; catenary and shooting to their tolerances)."""
    ds = gc.run(tmp_path, gc.TOW)
    assert (ds.status == 0).all()
    np.testing.assert_allclose(ds.force_b, np.broadcast_to([3000.0, 0.0, 8000.0], (3, 3)))
    ref = ds.force_a.sel(solver="catenary").values
    scale = np.linalg.norm(ref)
    for m in ("shooting", "discrete"):
        assert np.abs(ds.force_a.sel(solver=m).values - ref).max() <= 2e-4 * scale, m
    assert np.abs(ds.force_a.sel(solver="shooting").values - ref).max() <= 1e-5 * scale


def test_vertical_line_stretch(tmp_path):
    """A wire hanging straight down with 2 kN at its lower end: by every static method,
    the top tension F + w L and the stretch (F L + w L^2 / 2) / EA, w its weight in air
    (1e-9: exact forms, solver tolerances 1e-9 or tighter)."""
    ds = gc.run(tmp_path, gc.VERTICAL)
    w = (3.0 - gc.RHO_AIR * math.pi * 0.02**2 / 4) * gc.G
    stretch = (2000.0 * 100.0 + w * 100.0**2 / 2) / 1.0e6
    for m in ds.solver.values:
        d = ds.sel(solver=m)
        assert int(d.status) == 0
        assert float(d.tension_a) == pytest.approx(2000.0 + w * 100.0, rel=1e-9)
        assert float(d.elongation[-1]) == pytest.approx(stretch, rel=1e-9)
        assert float(d.z[-1]) == pytest.approx(50.0 - 100.0 - stretch, rel=1e-9)


def test_spring_line(tmp_path):
    """A linear spring: k (distance - L) along the chord, zero when slack."""
    ds = gc.run(tmp_path, gc.SPRING)
    for x in ds.position_0.values:
        d = ds.sel(position_0=x)
        dist = math.hypot(x, 5.0)
        t = 5000.0 * max(dist - 10.0, 0.0)
        assert float(d.tension_a) == pytest.approx(t, rel=1e-12, abs=1e-9)
        np.testing.assert_allclose(d.force_a, t * np.array([x, 0.0, -5.0]) / dist, atol=1e-9)


def test_line_types_filled_as_documented(tmp_path):
    """docs/line-types.md's formulas for a 76 mm R3 studless chain and a 160 mm polyester
    rope, as recorded in the dataset's ``line_types`` attribute (exact arithmetic)."""
    import json

    ds = gc.run(tmp_path, gc.LINE_TYPES)
    chain, rope = json.loads(ds.attrs["line_types"])
    d = 0.076
    f = chain["filled"]
    assert f["diameter"] == pytest.approx(1.80 * d)
    assert f["mass_per_length"] == pytest.approx(19900 * d**2)
    assert f["axial_stiffness"] == pytest.approx(0.854e11 * d**2)
    assert f["drag_normal"] == pytest.approx(2.4 / 1.80)
    assert f["drag_tangential"] == pytest.approx(1.15 / (math.pi * 1.80))
    assert f["minimum_breaking_load"] == pytest.approx(0.0223 * 76**2 * (44 - 0.08 * 76) * 1e3)
    d = 0.16
    f = rope["filled"]
    assert rope["given_in_segment"] == ["drag_normal"] and "drag_normal" not in f
    assert f["mass_per_length"] == pytest.approx(678.75 * d**2)
    assert f["minimum_breaking_load"] == pytest.approx(308.2e6 * d**2)
    assert f["axial_stiffness"] == pytest.approx(14 * 308.2e6 * d**2)
    assert f["diameter"] == pytest.approx(math.sqrt(4 * 678.75 / (math.pi * 1380)) * d)


def test_spread_offset_curve(tmp_path):
    """Three equal legs at 120 deg, the platform surged -10..10 m: no sway force, roll or
    yaw moment at any surge (mirror symmetry about the x-z plane, to round-off); at zero
    offset no surge force and equal surge and sway stiffness (the three-fold symmetry);
    the surge stiffness is minus the slope of the surge force (central differences over
    +/- 2 m, their h^2 error term taken out); each
    leg as MoorPy's catenary between its ends (1e-9)."""
    catenary = pytest.importorskip("moorpy.Catenary", reason="MoorPy (the peers extra)").catenary
    ds = gc.run(tmp_path, gc.SPREAD)
    assert (ds.status == 0).all()
    f = ds.body_force.isel(body=0)
    k = ds.body_stiffness.isel(body=0)
    scale = float(abs(f.sel(dof="heave")).max())
    for dof in ("sway", "roll", "yaw"):
        assert float(abs(f.sel(dof=dof)).max()) <= 1e-9 * scale, dof
    assert abs(float(f.sel(surge=0.0, dof="surge"))) <= 1e-9 * scale
    k0 = k.sel(surge=0.0)
    kxx = float(k0.sel(dof="surge", dof_j="surge"))
    assert float(k0.sel(dof="sway", dof_j="sway")) == pytest.approx(kxx, rel=1e-9)
    x = ds.surge.values
    fx = f.sel(dof="surge").values
    slope = -(fx[2:] - fx[:-2]) / (x[2:] - x[:-2])
    kk = k.sel(dof="surge", dof_j="surge").values
    h = x[1] - x[0]
    # central differences of F = -integral K: slope = K + K'' h^2 / 6 + O(h^4); the
    # leading term taken from K itself, what is left is O(h^4) (measured 1.5e-4)
    corrected = kk[1:-1] + (kk[2:] - 2 * kk[1:-1] + kk[:-2]) / 6.0
    np.testing.assert_allclose(slope, corrected, rtol=5e-4)
    assert h == 2.0
    d = ds.sel(surge=0.0)
    for i in range(3):
        p = d.isel(line=i)
        n = int(np.isfinite(p.x).sum())
        ends = np.array([[float(p[c][j]) for c in "xyz"] for j in (0, n - 1)])
        span = math.hypot(*(ends[1] - ends[0])[:2])
        _, _, hb, vb, _ = catenary(
            span, ends[1, 2] - ends[0, 2], 850.0, 4.9e8, gc.W_CHAIN, CB=0.0, Tol=1e-12
        )
        fb = p.force_b.values
        assert math.hypot(fb[0], fb[1]) == pytest.approx(-hb, rel=1e-9)
        assert fb[2] == pytest.approx(vb, rel=1e-9)


def test_system_sweep_from_a_slack_start_reaches_the_taut_equilibrium(tmp_path):
    """docs/guide/systems.md's example with its segments filled in, the clump's start
    guess laying leg1 slack on the seabed: every case solves (a slack line's trial force is
    its hanging part's, statics/system_slack.py), at the equilibrium of the taut start (to
    1e-8 m: both Newtons stop at 1e-9 of the clump's weight, about 1e-10 m of its position
    with these lines' stiffness), each case verified (status 0)."""
    ds = gc.run(tmp_path, gc.SYSTEM_GUIDE_SLACK_START)
    assert (ds.status == 0).all()
    taut = gc.run(
        tmp_path / "taut",
        gc.SYSTEM_GUIDE_SLACK_START.replace(
            "position: [-60.0, 0.0, -60.0]", "position: [-70.0, 0.0, -30.0]"
        ),
    )
    np.testing.assert_allclose(
        ds.point_position.values, taut.point_position.values, rtol=0, atol=1e-8
    )


def test_methods_in_one_study_explain_their_nans(tmp_path):
    """A slow fairlead surge by both dynamic methods in one study: each method's own
    outputs are NaN in the other's case, and each such NaN in a case of status 0 is
    explained by a ``nan_means`` attribute (a bare NaN means a failed analysis). The slow
    motion is at its static limit: the time domain's extremes move from its static
    tension by what the statics moves at +/- 2 m (within 2 %: its 40 elements' O(h^2)
    error, measured 3.5e-3, plus the motion's dynamics at 0.005 Hz)."""
    ds = gc.run(tmp_path, gc.SLOW_SURGE)
    assert (ds.status == 0).all()
    bare = [
        name
        for name, v in ds.data_vars.items()
        if v.dtype.kind == "f"
        and "method" in v.dims
        and bool(np.isnan(v).any())
        and "nan_means" not in v.attrs
    ]
    assert not bare, bare
    t = ds.sel({"method": "time"})  # (sel's own keyword is method)
    assert str(t.dynamic_method.values) == "time"
    static = gc.run(
        tmp_path / "static",
        gc.LEG.replace(
            "{start: 540.0, stop: 580.0, num: 5, name: offset}", "[558.0, 560.0, 562.0]"
        ).replace("nodes: 121", "nodes: 41"),
    )
    tb = static.tension_b.values
    up = float(t.tension_max - t.tension_static)
    down = float(t.tension_static - t.tension_min)
    assert up == pytest.approx(tb[2] - tb[1], rel=0.02)
    assert down == pytest.approx(tb[1] - tb[0], rel=0.02)
    f = ds.sel({"method": "frequency"})
    assert float(f.tension_static) == pytest.approx(tb[1], rel=1e-9)


def test_results_guide_nan_means_contract(tmp_path):
    """docs/guide/results.md: a variable whose NaN is a valid result says so in
    ``nan_means``; in a static sweep whose cases all succeed, no float variable holds a
    NaN without it."""
    ds = gc.run(tmp_path, gc.LEG)
    for name, v in ds.data_vars.items():
        if v.dtype.kind == "f":
            assert not bool(np.isnan(v).any()) or "nan_means" in v.attrs, name
    assert isinstance(ds, xr.Dataset)


def test_guide_cli_refusals(tmp_path, capsys):
    """docs/guide/cli.md: --out naming a file, <name>.nc being a folder, and a missing
    study are one line each, exit 2, nothing run."""
    cfg = gc.write(tmp_path, gc.SPRING)
    afile = tmp_path / "afile"
    afile.write_text("")
    assert main(["run", str(cfg), "--out", str(afile)]) == 2
    (tmp_path / "o" / "spring.nc").mkdir(parents=True)
    assert main(["run", str(cfg), "--out", str(tmp_path / "o")]) == 2
    assert main(["run", str(tmp_path / "missing.yaml"), "--out", str(tmp_path / "p")]) == 2
    err = capsys.readouterr().err
    assert "is a file, not a folder" in err
    assert "is a folder, not a result file" in err
    assert "does not exist" in err


def test_polynomial_law_stretch(tmp_path):
    """docs/guide/cable-laws.md's polynomial law as printed, on a wire hanging straight
    down: its lower end lies at the law's exact stretch, the integral of the strain e(T)
    along s with T = F + w (L - s) (catenary and shooting to 1e-12 m, their tolerances;
    discrete to 1e-7 m, its 50 elements' O(h^2) lumping); ``elongation``, trapezoids
    over the 51 output points, within their error bound L h^2 / 12 max |e_ss| (1.6e-8
    m here, docs/guide/results.md), not exact."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    line = gc.law_line("polynomial")
    coefficients = [4.0e6, 2.0e7, 5.0e7]
    assert line == "axial: {law: polynomial, coefficients: [4.0e6, 2.0e7, 5.0e7]}"
    ds = gc.run(tmp_path, gc.hanging_wire(line, "poly-wire"))

    def law(e, k=0):  # T(e) and its derivatives
        c = np.polynomial.Polynomial([0.0, *coefficients])
        return c.deriv(k)(e) if k else c(e)

    w = (3.0 - gc.RHO_AIR * math.pi * 0.02**2 / 4) * gc.G
    force, length, h = 20000.0, 100.0, 2.0

    def strain(s):
        t = force + w * (length - s)
        return brentq(lambda e: law(e) - t, 0.0, 1.0, xtol=1e-16, rtol=1e-15)

    exact = quad(strain, 0.0, length, epsabs=1e-14, epsrel=1e-14)[0]
    # e_ss = e''(T) w^2 = -T''(e) / T'(e)^3 w^2, largest at the least tension
    e_ss = max(abs(law(strain(s), 2) / law(strain(s), 1) ** 3) * w**2 for s in (0.0, length))
    bound = length * h**2 / 12 * e_ss
    for m in ds.solver.values:
        d = ds.sel(solver=m)
        assert int(d.status) == 0
        tol = 1e-7 if m == "discrete" else 1e-12
        assert abs((50.0 - float(d.z[-1]) - length) - exact) <= tol, m
        assert abs(float(d.elongation[-1]) - exact) <= 1.05 * bound, m


def test_system_methods_in_one_study_explain_their_nans(tmp_path):
    """docs/guide/systems.md's dynamics by both methods in one study (the spread surged
    1 m at 0.002 Hz): no bare NaN in a case of status 0 (the system frequency domain
    writes no ``steady_converged``, said by ``nan_means``); legs 2 and 3, mirror images
    about the surge axis, carry equal tensions (to 1e-9); and so slow a motion is at its
    static limit, each fairlead's tension range that of the statics at -1 and +1 m:
    the frequency domain's to 3 % (measured 1.0 %: linear about the catenary at 40
    elements), the time domain's to 12 % (measured 3.3 % on leg 1, 8.4 % on legs 2 and
    3 at 40 elements: it converges at first order on a chain whose touchdown moves by
    whole elements, systems.md; 17460, 16221, 15524, 15725 N on leg 1 at 20, 40, 80,
    160 elements against 15697 N)."""
    ds = gc.run(tmp_path, gc.SPREAD_DYNAMICS)
    assert (ds.status == 0).all()
    bare = [
        name
        for name, v in ds.data_vars.items()
        if v.dtype.kind == "f" and bool(np.isnan(v).any()) and "nan_means" not in v.attrs
    ]
    assert not bare, bare
    for q in ("tension_max_b", "tension_min_b"):
        v = ds[q]
        np.testing.assert_allclose(v.isel(line=1), v.isel(line=2), rtol=1e-9)
    static = gc.run(
        tmp_path / "static",
        gc.SPREAD.replace("{start: -10.0, stop: 10.0, num: 11, name: surge}", "[-1.0, 1.0]"),
    ).tension_b
    expected = abs(static.isel(position_0=1) - static.isel(position_0=0)).values
    rng = ds.tension_max_b - ds.tension_min_b
    np.testing.assert_allclose(rng.sel({"method": "frequency"}), expected, rtol=0.03)
    np.testing.assert_allclose(rng.sel({"method": "time"}), expected, rtol=0.12)


def test_validate_and_schema_load_no_kernels(tmp_path):
    """docs/guide/cli.md: `validate` and `schema` load neither numba nor scipy (what
    makes them answer at once), checked in a fresh interpreter."""
    import subprocess
    import sys

    cfg = gc.write(tmp_path, gc.LEG)
    code = (
        "import sys, io, contextlib\n"
        "from cablestudy.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    assert main(['validate', {str(cfg)!r}]) == 0\n"
        "    assert main(['schema']) == 0\n"
        "print(sorted(m for m in ('numba', 'scipy') if m in sys.modules))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=gc.ROOT, check=True
    )
    assert out.stdout.strip() == "[]", out.stdout + out.stderr


def test_system_guide_example_from_a_taut_start(tmp_path):
    """The same example started with the clump where leg1 is taut (systems.md): every
    surge solves; the clump balances its weight less buoyancy and the two lines' pulls
    (to 1e-9 of its weight: the Newton's tolerance), and sits where the guide says at
    zero surge (printed to 0.1 m)."""
    text = gc.SYSTEM_GUIDE_SLACK_START.replace(
        "position: [-60.0, 0.0, -60.0]", "position: [-70.0, 0.0, -30.0]"
    ).replace("name: spread", "name: spread-taut")
    ds = gc.run(tmp_path, text)
    assert (ds.status == 0).all()
    weight = (3000.0 - gc.RHO_WATER * 0.2) * gc.G
    for surge in ds.surge.values:
        d = ds.sel(surge=surge)
        net = d.force_b.sel(line="leg1").values + d.force_a.sel(line="bridle").values
        np.testing.assert_allclose(net, [0.0, 0.0, weight], atol=1e-9 * weight)
    clump = ds.point_position.sel(surge=0.0, point="clump").values
    np.testing.assert_allclose(clump, [-27.9, 0.0, -76.1], atol=0.05)


MOORPY_DESIGN = """\
mooring:
  water_depth: 200
  points:
    - {name: anchor, type: fixed, location: [800, 0, -200]}
    - {name: fair, type: vessel, location: [20, 0, -14]}
  lines:
    - {name: leg, endA: anchor, endB: fair, type: chain, length: 850}
  line_types:
    - {name: chain, diameter: 0.137, mass_density: 115.0, stiffness: 4.9e8,
       transverse_drag: 1.2, tangential_drag: 0.4, transverse_added_mass: 1.0,
       tangential_added_mass: 0.5}
"""


def test_moorpy_design_yaml_imported_and_run(tmp_path, capsys):
    """docs/guide/interchange.md: `cablestudy import moorpy design.yaml > study.yaml`,
    then `cablestudy run`: the study says where it came from (a MoorPy design YAML, not
    "MoorDyn v2"), and its leg is MoorPy's catenary between the same points (1e-9),
    at MoorPy's gravity."""
    catenary = pytest.importorskip("moorpy.Catenary", reason="MoorPy (the peers extra)").catenary
    src = tmp_path / "design.yaml"
    src.write_text(MOORPY_DESIGN)
    capsys.readouterr()
    assert main(["import", "moorpy", str(src)]) == 0
    study = capsys.readouterr().out
    ds = gc.run(tmp_path, study)
    assert "(MoorPy design YAML)" in ds.attrs["study_description"]
    assert "MoorDyn v" not in ds.attrs["study_description"]
    # the design YAML gives no gravity: MoorPy's own default, 9.81
    w = gc.W_CHAIN / gc.G * 9.81
    _, _, hb, vb, _ = catenary(780.0, 186.0, 850.0, 4.9e8, w, CB=0.0, Tol=1e-12)
    fb = ds.force_b.values
    assert abs(fb[0]) == pytest.approx(abs(hb), rel=1e-9)
    assert fb[2] == pytest.approx(vb, rel=1e-9)
