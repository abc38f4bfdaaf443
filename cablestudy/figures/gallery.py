"""The checked gallery: every number a seed prints that we can compute, our value and
the difference, and the statements its text makes about its figures, checked on our
results. ``make figures`` writes it to ``docs/validation.md`` beside the figures.

Each :class:`Row` states the tolerance it is held to (a test recomputes every row from
the studies and fails when a value leaves it); a difference over 2 % carries a
sentence saying why.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from .statics_figures import TABLE1, table1_chord_excess

Data = dict[str, xr.Dataset]

#: differences above this (relative) need a sentence saying why
EXPLAIN_ABOVE = 0.02


@dataclass(frozen=True)
class Row:
    """One printed number of a seed against ours.

    ``tolerance`` is absolute, in ``units``: the test requires
    ``|ours - printed| <= tolerance``; ``why`` says where the number comes from and, for
    a difference over 2 %, why it differs."""

    seed: str
    what: str
    printed: float
    units: str
    studies: tuple[str, ...]
    compute: Callable[[Data], float]
    tolerance: float
    why: str

    def relative(self, ours: float) -> float:
        scale = abs(self.printed) if self.printed != 0.0 else 1.0
        return abs(ours - self.printed) / scale


@dataclass(frozen=True)
class Claim:
    """A statement of a seed's text about its figures, checked on our results: ``check``
    returns (holds, our numbers as text). ``differs``, when given, says why the statement
    does not hold on our reading of the seed: the check must then fail (a test requires
    it), so a difference is recorded rather than hidden, and noticed if it goes away."""

    seed: str
    statement: str
    studies: tuple[str, ...]
    check: Callable[[Data], tuple[bool, str]]
    differs: str = ""


# ------------------------------------------------------------------ dodaran-park

#: Table 1's interior points lie off any curve a line hanging under its own weight can
#: take: such a curve is convex (z'' = w / H sqrt(1 + z'^2) > 0), so every point lies on
#: or below the chord of its neighbours; see :func:`table1_chord_excess`.
TABLE1_WHY = (
    "the seed's Table 1 is not a hanging-line shape: a line under its own weight is convex "
    "(every point on or below the chord of its neighbours), but the printed point at "
    "x = 82.91 m lies {excess:.2f} m above the chord of its neighbours and the one at "
    "x = 65.85 m {excess2:.2f} m above; no catenary passes through all the points, and "
    "ours (which agrees with the exact solution to 1e-9 m) misses them by {rms} m rms; "
    "the best-fitting catenary between the same supports (length 96.7 m instead of 100 m, "
    "found by a length sweep in tests/validation/test_gallery.py) still misses them by "
    "1.2 m rms"
)


def _z_at(ds: xr.Dataset, x: float) -> float:
    xs, zs = ds["x"].values.ravel(), ds["z"].values.ravel()
    return float(np.interp(x, xs, zs))


def _table1_rms(data: Data) -> float:
    ds = data["catenary-in-air"]
    return float(np.sqrt(np.mean([(_z_at(ds, x) - z) ** 2 for x, z in TABLE1])))


def _table1_rows() -> list[Row]:
    rows = []
    excess = table1_chord_excess()
    for k, (x, z) in enumerate(TABLE1):
        end = k in (0, len(TABLE1) - 1)
        rows.append(
            Row(
                seed="dodaran-park",
                what=f"Table 1: z at x = {x:g} m (L = 100 m steel catenary in air)",
                printed=float(z),
                units="m",
                studies=("catenary-in-air",),
                compute=lambda d, x=float(x): _z_at(d["catenary-in-air"], x),
                tolerance=1e-9 if end else 4.5,
                why=(
                    "a support: the study places it there"
                    if end
                    else TABLE1_WHY.format(excess=excess[5], excess2=excess[3], rms="{rms:.2f}")
                ),
            )
        )
    return rows


def _fig4_claim(data: Data) -> tuple[bool, str]:
    exact, semi = data["catenary-in-air"], data["dodaran-fig4-semi-analytic"]
    gap = max(float(np.abs(semi[v].values - exact[v].values).max()) for v in ("x", "y", "z"))
    dt = float(np.abs(semi["tension"].values - exact["tension"].values).max())
    return gap < 1e-9 and dt < 1e-6 * float(exact["tension"].max()), (
        f"semi-analytic (method catenary) against the exact elastic catenary at 101 points: "
        f"positions within {gap:.1e} m, tension within {dt:.1e} N"
    )


# ----------------------------------------------------------------------- moustafa


def _sag_ratio(data: Data) -> float:
    ds = data["moustafa-figs2-5"]
    z = ds["z"].isel({d: 0 for d in ds["z"].dims if d != "s"}).values
    x = ds["x"].isel({d: 0 for d in ds["x"].dims if d != "s"}).values
    return float(-z.min() / (x[-1] - x[0]))


def _fig7_claim(data: Data) -> tuple[bool, str]:
    ds = data["moustafa-fig7"]
    tmax = ds["tension_max"]
    ea = ds["axial_stiffness"].values
    lo, hi = float(ea.min()), float(ea.max())
    out = []
    effects = []
    for f in (0.1, 1.0):
        t = tmax.sel(frequency=f, method="nearest")
        a, b = float(t.sel(axial_stiffness=lo)), float(t.sel(axial_stiffness=hi))
        effects.append(b - a)
        out.append(f"{f:g} Hz: T_max {a:.1f} N (E = 1e8 Pa) to {b:.1f} N (E = 1e11 Pa)")
    holds = effects[1] > 2.0 * effects[0] and effects[0] >= 0.0
    return holds, "; ".join(out)


def _symmetry_claim(data: Data) -> tuple[bool, str]:
    ds = data["moustafa-figs2-5"].sel(amplitude=0.025).isel(frequency=0)
    tmax, tmin, t0 = (float(ds[v]) for v in ("tension_max", "tension_min", "tension_static"))
    asym = abs(0.5 * (tmax + tmin) - t0) / t0
    return asym < 0.01, (
        f"0.025 m, {float(ds['frequency']):g} Hz: (T_max + T_min) / 2 = "
        f"{0.5 * (tmax + tmin):.2f} N against T_static = {t0:.2f} N ({100 * asym:.2f} %)"
    )


def _slack_claim(data: Data) -> tuple[bool, str]:
    ds = data["moustafa-figs2-5"]
    small = ds.sel(amplitude=0.025)
    large = ds.sel(amplitude=0.1)
    i = int(np.argmin(large["tension_min"].values))
    f = float(large["frequency"][i])
    ratio_large = float(large["tension_max"][i] / large["tension_static"][i])
    ratio_small = float(
        small["tension_max"].sel(frequency=f) / small["tension_static"].sel(frequency=f)
    )
    holds = float(large["tension_min"][i]) < 0.1 * float(large["tension_static"][i])
    holds = holds and ratio_large > 2.0 * ratio_small
    return holds, (
        f"0.1 m, {f:g} Hz: T_min = {float(large['tension_min'][i]):.2f} N (slack), "
        f"T_max = {ratio_large:.2f} T_static; 0.025 m there: T_max = {ratio_small:.2f} T_static"
    )


# --------------------------------------------------------------------------- ajayi


def _umbilical_period(data: Data) -> float:
    ds = data["umbilical-frequency-tension"]
    f = ds["natural_frequency"].isel(mode=0)
    f = f.isel({d: 0 for d in f.dims if d != "bending_stiffness"})
    return float(1.0 / f.isel(bending_stiffness=-1))


UMBILICAL_TIME = "umbilical-time-response"


def _response_period(data: Data, component: str) -> float:
    """Period [s] of our free response (Figs. 4 and 8) at a quarter of the length."""
    from .umbilical_figures import free_period, local_motion

    ds = data[UMBILICAL_TIME]
    s = float(local_motion(ds)["s"].max()) / 4.0
    return free_period(ds, component, s)[0]


def _beam_claim(data: Data) -> tuple[bool, str]:
    ds = data[UMBILICAL_TIME]
    modal = 1.0 / ds["natural_frequency"].isel(mode=slice(0, 2)).values
    ours = {c: _response_period(data, c) for c in ("normal", "transverse")}
    worst = max(abs(p - m) / m for p in ours.values() for m in modal)
    return worst < 0.03, (
        f"free periods of our time response at L/4: normal {ours['normal']:.1f} s, "
        f"transverse {ours['transverse']:.1f} s; lowest natural periods of the same line "
        f"(modal analysis, EI, in the same study) {modal[0]:.1f} and {modal[1]:.1f} s; "
        f"largest difference {100 * worst:.1f} % (held to 3 %: the damped period is "
        "1/sqrt(1 - zeta^2) = 0.9 % longer at our zeta = 0.13, the second mode in the "
        "record and the 4 kN the offset adds to the tension shift the fit by about 1 %)"
    )


TENSION_STUDIES = (
    "umbilical-frequency-tension",
    "umbilical-frequency-tension-30kg",
    "umbilical-frequency-tension-60kg",
)


def _lowest_with_bending(ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """Bottom tension [N] and lowest natural frequency [Hz] with EI, in tension order."""
    sub = ds.isel(bending_stiffness=-1)
    tension = sub["tension_a"].values
    order = np.argsort(tension)
    return tension[order], sub["natural_frequency"].isel(mode=0).values[order]


def _tension_claim(data: Data) -> tuple[bool, str]:
    out, holds = [], True
    for name in TENSION_STUDIES:
        tension, freq = _lowest_with_bending(data[name])
        holds = holds and bool(np.all(np.diff(freq) > 0.0))
        mass = yaml.safe_load(data[name].attrs["study_yaml"])["line"]["segments"][0]
        out.append(
            f"{mass['mass_per_length']:g} kg/m: {freq[0]:.4f} Hz at {tension[0] / 1e3:.0f} kN "
            f"to {freq[-1]:.4f} Hz at {tension[-1] / 1e3:.0f} kN"
        )
    return holds, "lowest natural frequency with EI, " + "; ".join(out) + " (rising throughout)"


def _mass_claim(data: Data) -> tuple[bool, str]:
    t30, f30 = _lowest_with_bending(data["umbilical-frequency-tension-30kg"])
    t60, f60 = _lowest_with_bending(data["umbilical-frequency-tension-60kg"])
    same = bool(np.allclose(t30, t60, rtol=1e-4))  # the lengths set them to ~1e-6
    ratio = f60 / f30
    return same and bool(np.all(ratio > 1.0)), (
        f"at each of the same bottom tensions the 60 kg/m line's lowest frequency is "
        f"{ratio.min():.3f} to {ratio.max():.3f} times the 30 kg/m line's: the seed's tension "
        "T0 + m g s grows with m faster than the inertia m + the 515 kg/m added mass"
    )


def _peak_positions(data: Data) -> tuple[float, float, float]:
    """Length and the arc lengths [m] where the normal displacement and the normal
    velocity are largest over the record."""
    from .umbilical_figures import local_motion

    motion = local_motion(data[UMBILICAL_TIME])
    s = motion["s"].values
    disp = np.abs(motion["normal_displacement"]).max("time").values
    vel = np.abs(motion["normal_velocity"]).max("time").values
    return float(s[-1]), float(s[np.argmax(disp)]), float(s[np.argmax(vel)])


def _normal_peak_claim(data: Data) -> tuple[bool, str]:
    length, s_disp, s_vel = _peak_positions(data)
    holds = s_disp < length / 3.0 and s_vel <= s_disp
    return holds, (
        f"largest normal displacement at s = {s_disp:.0f} m ({s_disp / length:.3f} L), "
        f"largest normal velocity at s = {s_vel:.0f} m ({s_vel / length:.3f} L); the seed's "
        "1500 m and 1000 m are 0.15 L and 0.10 L of its 10 000 m: both in the lower part "
        "of the line, where the tension is least"
    )


def _tangential_decay_claim(data: Data) -> tuple[bool, str]:
    from .umbilical_figures import local_motion, ramp_end

    ds = data[UMBILICAL_TIME]
    v = np.abs(local_motion(ds)["tangential_velocity"])
    start = ramp_end(ds) + 20.0
    t_end = float(v["time"].max())
    early = float(v.sel(time=slice(start, start + 100.0)).max())
    late = float(v.sel(time=slice(t_end - 100.0, t_end)).max())
    return late < 0.25 * early, (
        f"largest tangential velocity {early:.2e} m/s from {start:g} s to {start + 100:g} s "
        f"(the offset is reached at {start - 20:g} s), {late:.2e} m/s in the last 100 s "
        "(drag and c damp the free response)"
    )


def _tangential_midpoint_claim(data: Data) -> tuple[bool, str]:
    from .umbilical_figures import local_motion

    motion = local_motion(data[UMBILICAL_TIME])
    s = motion["s"].values
    amp = np.abs(motion["tangential_displacement"]).max("time").values
    peak = float(s[np.argmax(amp)])
    return abs(peak / s[-1] - 0.5) < 0.1, (
        f"largest tangential displacement at s = {peak:.0f} m ({peak / s[-1]:.3f} L)"
    )


ROWS: list[Row] = [
    *_table1_rows(),
    Row(
        seed="moustafa",
        what="sag-span ratio of the test cable (static, in water)",
        printed=0.0812,
        units="1",
        studies=("moustafa-figs2-5",),
        compute=_sag_ratio,
        tolerance=0.0005,
        why="our static shape of the printed length 10.9774 m and span 10.792 m (E = 1e11 "
        "Pa); the ratio is sensitive to the slack L - S = 0.185 m: a line 1.9 mm (0.017 %) "
        "longer gives the printed 0.0812 (tests/validation/test_gallery.py), a difference "
        "of the order of a measured test cable's length; the tolerance covers 2 mm",
    ),
    Row(
        seed="vaz-patel",
        what="Table 1: weight in air minus weight in sea of the HA cable (26.49 - 17.76)",
        printed=26.49 - 17.76,
        units="N/m",
        studies=(),
        compute=lambda d: 1025.0 * 9.80665 * math.pi * 0.0332**2 / 4.0,
        tolerance=0.035,
        why="the buoyancy rho g pi d^2 / 4 of sea water from the printed d = 0.0332 m; d "
        "printed to 3 digits carries +-0.15 % (0.3 % in the area, 0.026 N/m)",
    ),
    Row(
        seed="ajayi",
        what="period of the normal oscillation (text under Fig. 4: 'about 200 seconds')",
        printed=200.0,
        units="s",
        studies=("umbilical-frequency-tension",),
        compute=_umbilical_period,
        tolerance=150.0,
        why="our lowest natural period of the umbilical standing in the printed 1200 m of "
        "water at the printed 10 kN bottom tension, with EI; the seed's Table 1 also gives "
        "a 10 000 m length, which cannot stand in 1200 m of water, and does not say how "
        "the line lies or how it is excited, so only the order of magnitude compares "
        "(the tolerance says so)",
    ),
    Row(
        seed="ajayi",
        what="period of the normal oscillation in Fig. 4 (text: 'about 200 seconds')",
        printed=200.0,
        units="s",
        studies=(UMBILICAL_TIME,),
        compute=lambda d: _response_period(d, "normal"),
        tolerance=150.0,
        why="the period of our Fig. 4: a damped oscillation fitted to the normal "
        "displacement at L/4 of the umbilical standing in 1200 m of water, after a sudden "
        "0.5 m vessel offset (configs/umbilical-time-response.yaml says why this reading); "
        "it is the line's lowest natural period (the statement checked below), so it "
        "differs from the seed's as the row above does: the seed's line is 10 000 m long "
        "and driven by a current it does not give (its 1000 m/s cannot be)",
    ),
    Row(
        seed="ajayi",
        what="period of the transverse oscillation in Fig. 8 (text: 'about 5 seconds')",
        printed=5.0,
        units="s",
        studies=(UMBILICAL_TIME,),
        compute=lambda d: _response_period(d, "transverse"),
        tolerance=60.0,
        why="the seed's transverse equation (its section 2.2.3) is its normal equation "
        "with the same m, c, EI, T and pinned ends, less the weight, so their free "
        "periods are the same: the printed 5 s and 200 s cannot both be free periods of "
        "its equations (a string's period goes as T^-1/2: 5 s against 200 s would need "
        "1600 times the tension). Ours "
        "is the transverse displacement at L/4 fitted as the row above: the same lowest "
        "natural period in and out of the plane (modal analysis: they differ by less than 1 %)",
    ),
]

CLAIMS: list[Claim] = [
    Claim(
        "dodaran-park",
        "Fig. 4: the present (semi-analytic) method and the exact analytic solution "
        "(Irvine, 1981) agree very well",
        ("catenary-in-air", "dodaran-fig4-semi-analytic"),
        _fig4_claim,
    ),
    Claim(
        "moustafa",
        "Figs. 2-5: under mild excitation the maximum and minimum tension are symmetric "
        "about the static tension",
        ("moustafa-figs2-5",),
        _symmetry_claim,
    ),
    Claim(
        "moustafa",
        "Figs. 4-5: as the minimum tension reaches zero (taut-slack) the maximum tension "
        "increases significantly",
        ("moustafa-figs2-5",),
        _slack_claim,
    ),
    Claim(
        "moustafa",
        "Fig. 7: at low frequency the catenary stiffness resists the excitation; as the "
        "frequency grows the elastic stiffness (Young's modulus) becomes more important",
        ("moustafa-fig7",),
        _fig7_claim,
    ),
    Claim(
        "ajayi",
        "Figs. 9-12: an increase in tension results in an increase in the frequency of "
        "oscillation in the normal and transverse directions",
        TENSION_STUDIES,
        _tension_claim,
    ),
    Claim(
        "ajayi",
        "Figs. 11-12: increasing the mass (30 to 60 kg/m) increases the frequency of oscillation",
        TENSION_STUDIES[1:],
        _mass_claim,
    ),
    Claim(
        "ajayi",
        "Fig. 5: the normal response conforms with the oscillatory motion of a vibrating "
        "tensioned beam",
        (UMBILICAL_TIME,),
        _beam_claim,
    ),
    Claim(
        "ajayi",
        "Figs. 4-5: the normal displacement is largest around s = 1500 m and the normal "
        "velocity around s = 1000 m (of 10 000 m, from the bottom)",
        (UMBILICAL_TIME,),
        _normal_peak_claim,
    ),
    Claim(
        "ajayi",
        "Fig. 7: the amplitude of the tangential velocity reduces with time",
        (UMBILICAL_TIME,),
        _tangential_decay_claim,
    ),
    Claim(
        "ajayi",
        "Figs. 6-7: in the tangential direction the mid-point of the umbilical is the most "
        "responsive",
        (UMBILICAL_TIME,),
        _tangential_midpoint_claim,
        differs="the seed's tangential equation is a string in p with p = 0 at both ends, "
        "driven along its length by tangential current drag, whose response peaks at "
        "mid-length; ours is driven by the top end, which moves across the line, so the "
        "motion along the line is the stretch and slide of its curved static shape, "
        "largest low on the line where the current bends it most and the tension is least",
    ),
]


def studies_needed() -> list[str]:
    """Every study the rows and claims read."""
    names = {s for r in ROWS for s in r.studies} | {s for c in CLAIMS for s in c.studies}
    return sorted(names)


def gallery_markdown(data: Data, figures: list[Path], image_dir: str) -> str:
    """The text of ``docs/validation.md``: the figures, the table of printed numbers and
    the checked statements."""
    lines = [
        "# Gallery: the seeds' figures, regenerated and checked",
        "",
        "Written by `make figures` (`cablestudy figures --docs docs`); do not edit. Every "
        "row is recomputed by `tests/validation/test_gallery.py`, which fails when a value "
        "leaves the tolerance stated here.",
        "",
        "## Numbers the seeds print",
        "",
        "| seed | quantity | seed | ours | difference | tolerance | why |",
        "|---|---|---|---|---|---|---|",
    ]
    rms = _table1_rms(data) if "catenary-in-air" in data else float("nan")
    whys = [row.why.format(rms=rms) if "{rms" in row.why else row.why for row in ROWS]
    repeated = [w for w in dict.fromkeys(whys) if whys.count(w) > 1]
    notes = {w: chr(ord("a") + i) for i, w in enumerate(repeated)}
    for row, why in zip(ROWS, whys, strict=True):
        ours = row.compute(data)
        rel = row.relative(ours)
        flag = " **(over 2 %)**" if rel > EXPLAIN_ABOVE else ""
        shown = f"see note ({notes[why]})" if why in notes else why
        u = "" if row.units == "1" else f" {row.units}"
        lines.append(
            f"| {row.seed} | {row.what} | {row.printed:.6g}{u} | {ours:.6g}{u} | "
            f"{ours - row.printed:+.3g}{u} ({100 * rel:.2f} %){flag} | {row.tolerance:g}{u} "
            f"| {shown} |"
        )
    if notes:
        lines.append("")
        lines += [f"({label}) {why}." for why, label in notes.items()]
    lines += ["", "## Statements of the text, checked on our results", ""]
    lines += ["| seed | statement | holds | ours |", "|---|---|---|---|"]
    for claim in CLAIMS:
        holds, text = claim.check(data)
        if claim.differs and not holds:
            verdict = "no, as our reading expects"
            text = f"{text}; {claim.differs}"
        else:
            verdict = "yes" if holds else "NO"
        lines.append(f"| {claim.seed} | {claim.statement} | {verdict} | {text} |")
    lines += [
        "",
        "## Not yet in this gallery",
        "",
        "- axis readings of the figures (the seeds print curves, not tables, for Figs. 2-8 "
        "of the excitation and statics seeds);",
        "- the cable-types seed (aqwa) prints no figures or numbers to compare;",
        "- the umbilical seed's Figs. 4-8 as printed: its 10 000 m line in 1200 m of water "
        "and its 1000 m/s sea velocity cannot be followed, so ours are the same section "
        "standing in 1200 m under a vessel offset (umbilical-time-response, whose config "
        "states the reading), compared above by their periods and the text's statements, "
        "not point by point.",
        "",
        "## Figures",
        "",
    ]
    for path in figures:
        lines += [f"### {path.stem}", "", f"![{path.stem}]({image_dir}/{path.name})", ""]
    return "\n".join(lines) + "\n"
