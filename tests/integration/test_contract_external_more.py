"""The study-file contract checked from outside where no other outside test looks: modal
analysis, the quasi-static database, springs and pulleys, cable laying, time tables,
MoorDyn export and import, and the figures. Each study (tests/contract_more.py) is
written as an OrcaFlex or MoorPy user writes it from DESIGN.md and docs/, run through
``cablestudy run CONFIG --out DIR`` and checked against a closed form, an invariance, a
balance of forces or a direct static solve, and against the dataset conventions (units,
dims, no NaN at status 0). Small meshes and few cases: the file runs in seconds once the
kernels are compiled."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from tests.contract_more import (
    CATENARY_PULLEY,
    DATABASE_GRID,
    DATABASE_PAST_MAX_STRAIN,
    DATABASE_SPRING,
    DATABASE_TURNED,
    EXPORT_LEG,
    HANGING_CHAIN,
    LAYING,
    MODES_SWEPT,
    RHO,
    SPRING_PULLEY,
    SPRING_SLACK,
    SPRING_TABLE,
    SPRINGS,
    TABLE_PULL,
    TENDON_TABLE,
    hanging_chain_frequencies,
    taut_beam,
)
from tests.guide_contract import validate, write
from tests.integration.test_contract_external_line import run

ROOT = Path(__file__).resolve().parents[2]


def ok_cases(ds: xr.Dataset, names: list[str]) -> None:
    """Every case solved (status 0, no message) and ``names`` finite, each with units."""
    assert np.all(ds["status"].values == 0), ds["message"].values
    assert np.all(ds["message"].values == "")
    for name in names:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
        assert np.all(np.isfinite(ds[name].values)), name


# ------------------------------------------------------------------ modal analysis


def test_a_hanging_chain_has_the_bessel_frequencies(tmp_path: Path) -> None:
    """A chain hanging free from a hook in vacuum: omega_n = (j_0n / 2) sqrt(g / L), each
    mode twice (x and y). The modal model's 200 bar elements err as (n pi / N)^2 (about
    4e-4 on the third mode; EA 1e10 N adds a stretch of 1e-7): rtol 2e-3."""
    ds = run(tmp_path, HANGING_CHAIN)
    ok_cases(ds, ["natural_frequency", "mode_shape"])
    f = ds["natural_frequency"]
    assert f.dims == ("mode",) and f.attrs["units"] == "Hz"
    np.testing.assert_array_equal(ds["mode"].values, np.arange(1, 7))
    assert ds["mode_shape"].dims == ("mode", "s", "component")
    np.testing.assert_allclose(
        f.values, np.repeat(hanging_chain_frequencies(50.0, 3), 2), rtol=2e-3
    )


def test_a_taut_umbilical_is_the_tensioned_pinned_beam_and_keeps_it_turned(
    tmp_path: Path,
) -> None:
    """A neutrally buoyant umbilical (weight in water 0) pinned 100.1 m apart, T = 1e5 N,
    on a heading of 30 deg: f_n = n / (2 L) sqrt(T / m) sqrt(1 + (n pi / L)^2 EI / T),
    m the mass and the added mass per stretched length; without bending (the key
    switched off) the string. 200 elements: rtol 1e-3 (the mesh error (n pi / N)^2 / 24
    is 1e-4 on the fourth mode). The ends exchanged give the same frequencies to
    round-off (1e-9)."""
    ds = run(tmp_path, taut_beam())
    ok_cases(ds, ["natural_frequency"])
    tension = float(ds["tension"].sel(include_bending=False).isel(s=20))
    assert tension == pytest.approx(1.0e5, rel=1e-6)
    span, ei = 100.1, 2.0e6
    mass = (20.0 + RHO * math.pi * 0.1**2 / 4.0) / (1.0 + tension / 1.0e8)
    n = np.arange(1, 5)
    string = n / (2.0 * span) * math.sqrt(tension / mass)
    beam = string * np.sqrt(1.0 + (n * math.pi / span) ** 2 * ei / tension)
    for flag, theory in ((True, beam), (False, string)):
        f = ds["natural_frequency"].sel(include_bending=flag).values
        np.testing.assert_allclose(f, np.repeat(theory, 2), rtol=1e-3)
    swapped = run(tmp_path / "swap", taut_beam(swap=True))
    np.testing.assert_allclose(
        swapped["natural_frequency"].values, ds["natural_frequency"].values, rtol=1e-9
    )


def test_a_sweep_over_the_number_of_modes_explains_its_padding(tmp_path: Path) -> None:
    """Two and four modes in one study: the mode dimension holds four, the two-mode case
    is NaN beyond its second mode with status 0, and the NaN is explained by a
    ``nan_means`` (a bare NaN means a failed analysis); the modes both cases hold are the
    same numbers (one model)."""
    ds = run(tmp_path, MODES_SWEPT)
    assert np.all(ds["status"].values == 0) and np.all(ds["modal_status"].values == 0)
    f = ds["natural_frequency"]
    assert f.sizes["mode"] == 4
    assert np.all(np.isnan(f.sel(modes=2).values[2:]))
    assert np.all(np.isfinite(f.sel(modes=4).values))
    np.testing.assert_array_equal(f.sel(modes=2).values[:2], f.sel(modes=4).values[:2])
    for name in ("natural_frequency", "mode_shape"):
        assert "analysis.modal.modes" in ds[name].attrs["nan_means"], name


# ------------------------------------------------------------------ database


def test_a_turned_database_on_a_slope_in_a_current_holds_direct_solves(
    tmp_path: Path,
) -> None:
    """The database's plane runs from A towards +y (heading pi/2), the seabed rises
    along it and the current crosses it: the grid point at 210 m, 90 m is the static
    solve of end B placed there, 3D forces included, to the solver's tolerance."""
    db = run(tmp_path, DATABASE_TURNED.format(name="db", what="", yb=200.0, database=DATABASE_GRID))
    direct = run(
        tmp_path,
        DATABASE_TURNED.format(name="direct", what=", B at 210 m", yb=210.0, database=""),
    )
    ok_cases(direct, ["force_a", "force_b", "laid_length"])
    assert float(db["database_heading"]) == pytest.approx(math.pi / 2, abs=1e-15)
    assert db["database_force_a"].dims == ("horizontal_distance", "height_difference", "component")
    assert db["horizontal_distance"].attrs["units"] == "m"
    point = {"horizontal_distance": 210.0, "height_difference": 90.0}
    assert int(db["database_status"].sel(point)) == 0
    scale = float(direct["tension_b"])
    for name in ("force_a", "force_b"):
        np.testing.assert_allclose(
            db[f"database_{name}"].sel(point).values, direct[name].values, atol=1e-7 * scale
        )
    # the current across the plane pushes the line along +x: both ends feel it
    assert float(direct["force_a"].sel(component="x")) > 1.0
    assert float(db["database_laid_length"].sel(point)) == pytest.approx(
        float(direct["laid_length"]), abs=1e-6
    )


def test_failed_grid_points_of_a_database_are_warned(tmp_path: Path) -> None:
    """A wire whose law holds to 5 % strain, tabulated out to 130 m of a 120 m line: the
    points past 126 m end distance fail (max_strain) and are NaN in the tables with
    their point status; the case keeps status 0 (its own statics solved) and says so in
    its warning, naming a point (it had none: the run reported no failure and only
    ``lookup`` refused the table)."""
    ds = run(tmp_path, DATABASE_PAST_MAX_STRAIN)
    status = ds["database_status"].values
    far = np.hypot(ds["horizontal_distance"].values[:, None], ds["height_difference"].values)
    assert int(ds["status"]) == 0
    np.testing.assert_array_equal(status != 0, far > 1.05 * 120.0 * (1 + 1e-3))
    assert set(status[status != 0].tolist()) == {4}  # as the study of such a point
    assert np.all(np.isnan(ds["database_tension_b"].values[status != 0]))
    assert np.all(np.isfinite(ds["database_tension_b"].values[status == 0]))
    warning = str(ds["warning"].values)
    assert f"{int((status != 0).sum())} of 16 grid points failed" in warning
    assert "horizontal distance 130 m" in warning


def test_a_database_of_a_spring_line_is_refused_by_name(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A massless spring's tension is closed-form in the end distance: the database is
    refused before any work, naming the key and the line kind that supports it (it ran
    with status 0 and every grid point NaN)."""
    assert validate(tmp_path, DATABASE_SPRING, "database-spring") == 2
    err = capsys.readouterr().err
    assert "analysis.database" in err and "kind: spring" in err and "kind: catenary" in err


# ------------------------------------------------------------------ springs and pulleys


def test_springs_follow_their_law_along_the_force(tmp_path: Path) -> None:
    """A steel-wire spring held by a buoy's lift (a force end): the tension is the
    force's magnitude, the spring lies along it, its extension e solves
    k (e - d (1 - exp(-e / d))) = |F|; a slack spring carries nothing, its points on
    the chord; a spring over a pulley is stretched by its path A -> P -> B."""
    from scipy.optimize import brentq

    ds = run(tmp_path, SPRINGS)
    ok_cases(ds, ["tension_a", "tension_b", "force_b", "x", "z"])
    e = brentq(lambda e: 5000.0 * (e - 0.2 * (1.0 - math.exp(-e / 0.2))) - 1000.0, 0.0, 10.0)
    np.testing.assert_allclose(ds["tension_a"].values, [1000.0, 1000.0], rtol=1e-10)
    np.testing.assert_allclose(ds["force_b"].values, [[0, 0, -1000.0], [-600.0, 0, -800.0]])
    np.testing.assert_allclose(ds["x"].isel(s=-1).values, [0.0, 0.6 * (10.0 + e)], atol=1e-9)
    np.testing.assert_allclose(
        ds["z"].isel(s=-1).values, [-20.0 + e, -30.0 + 0.8 * (10.0 + e)], atol=1e-9
    )
    slack = run(tmp_path, SPRING_SLACK)
    ok_cases(slack, ["tension", "x", "z"])
    assert float(slack["tension_a"]) == 0.0 and np.all(slack["tension"].values == 0.0)
    np.testing.assert_allclose(slack["x"].values, np.linspace(0.0, 6.0, 5), atol=1e-12)
    np.testing.assert_allclose(slack["z"].values, np.linspace(0.0, -5.0, 5), atol=1e-12)
    pulley = run(tmp_path, SPRING_PULLEY)
    ok_cases(pulley, ["pulley_force"])
    t = 5000.0 * (2.0 * math.hypot(5.0, 1.0) - 10.0)
    np.testing.assert_allclose(pulley["tension_a"].values, [t], rtol=1e-12)
    np.testing.assert_allclose(
        pulley["pulley_force"].values, [[[0.0, 0.0, -2.0 * t / math.hypot(5.0, 1.0)]]], rtol=1e-12
    )


def test_supports_and_pulley_carry_a_chain_over_a_pulley(tmp_path: Path) -> None:
    """A chain over a frictionless pulley in air: the two supports and the pulley carry
    its weight in air and no net horizontal force (to the solver's 1e-9); with the
    pulley over the middle the split is at half the length and the support forces are
    mirror images."""
    ds = run(tmp_path, CATENARY_PULLEY)
    ok_cases(ds, ["force_a", "force_b", "pulley_force", "pulley_arc_length"])
    assert ds["pulley_force"].dims == ("position_0", "pulley", "component")
    weight = 120.0 * (20.0 - 1.225 * math.pi * 0.05**2 / 4.0) * 9.80665
    total = ds["force_a"] + ds["force_b"] + ds["pulley_force"].isel(pulley=0)
    np.testing.assert_allclose(total.values, [[0, 0, -weight]] * 2, atol=1e-8 * weight)
    mid = ds.sel(position_0=50.0)
    assert float(mid["pulley_arc_length"].isel(pulley=0)) == pytest.approx(60.0, abs=1e-8)
    a, b = mid["force_a"].values, mid["force_b"].values
    np.testing.assert_allclose(a, b * [-1.0, 1.0, 1.0], atol=1e-8 * weight)


# ------------------------------------------------------------------ installation


def test_paying_out_without_tangential_drag_adds_mu_v2_to_the_tension(tmp_path: Path) -> None:
    """Cable laying (vaz-patel) with the ship at rest and no tangential drag: the cable
    running along itself at V keeps the static shape, its tension raised by
    mu V^2 everywhere (mu: mass and normal added mass per metre, EA 1e12 N: no
    stretch); shooting integrates to 1e-9."""
    ds = run(tmp_path, LAYING)
    ok_cases(ds, ["tension", "x", "z"])
    mu = 5.0 + RHO * math.pi * 0.04**2 / 4.0
    rise = ds["tension"].sel(payout_speed=2.0) - ds["tension"].sel(payout_speed=0.0)
    np.testing.assert_allclose(rise.values, mu * 4.0, rtol=1e-6)
    for name in ("x", "z"):
        moved = ds[name].sel(payout_speed=2.0) - ds[name].sel(payout_speed=0.0)
        assert float(abs(moved).max()) < 1e-6


# ------------------------------------------------------------------ time tables


def test_a_time_table_moves_the_end_as_written(tmp_path: Path) -> None:
    """A taut tether's top pulled 0.2 m along it by a ramp-and-hold table, run 120 s
    (no period): at the end of the run the top is where the table put it and its
    tension is the static one there, T0 + EA 0.2 / 100 (the straight line: exact up to
    the axially damped ringing, 1e-6 of the rise). The smooth start of the repeating
    motions (ramp_periods x the run's period, here the duration) scaled the table: the
    top reached 0.1 m and 1.2 MN."""
    ds = run(tmp_path, TABLE_PULL)
    ok_cases(ds, ["tension_max", "tension_min", "history_tension"])
    static = float(ds["tension_b"])
    rise = 2.0e8 * 0.2 / 100.0
    np.testing.assert_allclose(ds["history_displacement"].values[0, -1], [0.0, 0.0, 0.2])
    assert float(ds["history_tension"][-1]) == pytest.approx(static + rise, rel=1e-6)
    assert float(ds["tension_max"]) == pytest.approx(static + rise, rel=1e-4)


def test_a_body_heaved_by_a_time_table_moves_as_written(tmp_path: Path) -> None:
    """A system: a hull heaved 0.2 m by a ramp-and-hold table, its taut tendon (straight:
    no discretisation error) ends the 120 s run at T0 + EA 0.2 / 100, as the line's end
    does (the same motion kernel; the ramp scaled the table there too)."""
    ds = run(tmp_path, TENDON_TABLE)
    assert int(ds["status"]) == 0, str(ds["message"].values)
    static = float(ds["tension_b"].sel(line="tendon"))
    end = float(ds["history_tension_b"].sel(line="tendon")[-1])
    assert end == pytest.approx(static + 2.0e8 * 0.2 / 100.0, rel=1e-6)


def test_a_spring_pulled_by_a_time_table_reaches_the_tables_stretch(tmp_path: Path) -> None:
    """A linear spring (5000 N/m, stretched 0.2 m) pulled 0.5 m more by a ramp-and-hold
    table over a 50 s run: its tension runs from 1000 N to 5000 (0.2 + 0.5) = 3500 N
    exactly (algebraic); the ramp scaled the table, 2250 N."""
    ds = run(tmp_path, SPRING_TABLE)
    ok_cases(ds, ["tension_max", "tension_min"])
    assert str(ds["dynamic_method"].values) == "spring"
    assert float(ds["tension_static"]) == pytest.approx(1000.0, rel=1e-12)
    assert float(ds["tension_min"]) == pytest.approx(1000.0, rel=1e-12)
    assert float(ds["tension_max"]) == pytest.approx(3500.0, rel=1e-12)


def test_a_table_that_does_not_start_at_rest_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A non-periodic table moves as written from the static position: a first
    displacement other than 0 would jump; refused, naming the value and what to do."""
    text = TABLE_PULL.replace("[[0.0, 0.0], [10.0, 0.1]", "[[0.0, 0.05], [10.0, 0.1]")
    assert validate(tmp_path, text, "table-jump") == 2
    err = capsys.readouterr().err
    assert "table" in err and "must be 0, got 0.05" in err and "periodic: true" in err


# ------------------------------------------------------------------ interchange


def test_export_then_import_gives_the_same_statics(tmp_path: Path, capsys) -> None:
    """``cablestudy export moordyn`` a two-segment leg with a clump on a rough seabed in
    a current, ``cablestudy import moordyn`` it back: the same end forces, laid length
    and shape (the file carries every number at full precision)."""
    cfg = write(tmp_path, EXPORT_LEG)
    dat = tmp_path / "leg.dat"
    assert main(["export", "moordyn", str(cfg), "--out", str(dat)]) == 0
    capsys.readouterr()
    assert main(["import", "moordyn", str(dat), "--name", "leg-back"]) == 0
    back = capsys.readouterr().out
    assert back.endswith("\n")
    first = run(tmp_path / "a", EXPORT_LEG)
    second = run(tmp_path / "b", back)
    ok_cases(second, ["force_a", "force_b", "laid_length"])
    scale = float(first["tension_b"])
    for name in ("force_a", "force_b"):
        np.testing.assert_allclose(second[name].values, first[name].values, atol=1e-9 * scale)
    assert float(second["laid_length"]) == pytest.approx(float(first["laid_length"]), abs=1e-6)
    for name in ("x", "y", "z"):
        np.testing.assert_allclose(second[name].values, first[name].values, atol=1e-6)


def test_export_refuses_or_names_what_the_moordyn_file_cannot_hold(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A spring line is refused naming its kind (it failed as "the case's statics
    failed (ZeroDivisionError ...)", solved as a catenary of no segments); cable
    laying is exported as the line at rest with a warning naming the key (it was
    dropped silently: MoorDyn's line would carry mu V^2 less tension)."""

    def export(text: str, *case: str) -> int:
        cfg = write(tmp_path, text)
        return main(["export", "moordyn", str(cfg), *case, "--out", str(tmp_path / "x.dat")])

    assert export(SPRING_SLACK) == 2
    err = capsys.readouterr().err
    assert "line.kind: spring" in err and "ZeroDivision" not in err
    assert export(LAYING, "--case", "payout_speed=2.0") == 0
    assert "analysis.static.installation" in capsys.readouterr().err


# ------------------------------------------------------------------ figures


def test_figures_do_not_draw_a_result_of_an_edited_config(tmp_path: Path) -> None:
    """``cablestudy figures`` reads ``<results>/<study>.nc``: after the study's config is
    edited, a result made from the old text (its ``study_sha256``) is run again rather
    than drawn, and with ``--no-run`` refused naming it (it was drawn silently)."""
    from cablestudy.figures import MissingResult, build_all

    configs, results = tmp_path / "configs", tmp_path / "results"
    configs.mkdir()
    for name in ("catenary-in-air", "dodaran-fig4-semi-analytic"):
        shutil.copy(ROOT / "configs" / f"{name}.yaml", configs)
    build_all(results, tmp_path / "fig", configs=configs, only=["dodaran-fig4"])
    config = configs / "catenary-in-air.yaml"
    config.write_text(config.read_text().replace("[92.5, 0.0, -8.6]", "[90.0, 0.0, -8.6]"))
    with pytest.raises(MissingResult, match="another version"):
        build_all(
            results, tmp_path / "fig", configs=configs, only=["dodaran-fig4"], run_missing=False
        )
    build_all(results, tmp_path / "fig", configs=configs, only=["dodaran-fig4"])
    ds = xr.load_dataset(results / "catenary-in-air.nc")
    assert ds.attrs["study_yaml"] == config.read_text()
    assert float(ds["x"].isel(s=-1)) == pytest.approx(90.0, abs=1e-9)
