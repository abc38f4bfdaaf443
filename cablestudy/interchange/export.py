"""Writing one case of a study as a MoorDyn version 2 input file.

The line becomes a chain of MoorDyn lines: one line type per segment, the line split
at segment joints and at attachments, which become free points with their mass and
volume. End A is MoorDyn's anchor end and end B the fairlead end. A fixed end is a
``Fixed`` point; the end an excitation moves (end B without dynamics) is ``Coupled``,
so a coupling program drives it. Ends given by a force (towing, mooring) are written
at the static position our solver finds for them.

MoorDyn integrates explicitly, so its time step must resolve the fastest mode of the
discretised line: the axial mode of its shortest segment, omega_max = 2 c / l with
c = sqrt(EA / (m + rho A Ca_ax)) (a lumped-mass chain's highest frequency is twice
that of one segment). We take dtM = T_min / 20 = pi l / (10 c), rounded down to
1, 2 or 5 times a power of ten: about 20 steps per shortest period.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..physics.contact import default_seabed_stiffness
from ..study import FixedEnd, Study
from ..study.problem import line_model
from .moordyn_format import InterchangeError
from .seabed import to_moordyn


@dataclass(frozen=True)
class ExportedCase:
    """A MoorDyn input file, the files it reads beside it, and what could not be kept."""

    text: str
    extra_files: dict[str, str]
    warnings: list[str]
    coupled: dict[int, np.ndarray]  # point ID -> position [m] to pass to MoorDyn's Init
    time_step: float  # dtM [s]


def current_table(study: Study, opts: list[str]) -> dict[str, str]:
    """MoorDyn's steady current of ``study`` (a one-line or a system study): the option
    row ``Currents 1`` appended to ``opts`` and the table file beside the input file
    (name -> text); nothing without a current."""
    env = study.environment
    if not env.current:
        return {}
    opts.append("1  Currents   ! steady current table in current_profile.txt")
    rows = []
    for p in sorted(env.current, key=lambda p: p.z):
        h = math.radians(p.heading_deg)
        rows.append(f"{_num(p.z)} {_num(p.speed * math.cos(h))} {_num(p.speed * math.sin(h))} 0")
    return {
        "current_profile.txt": (
            "--------------------- MoorDyn steady currents File ----------------------\n"
            f"written by cablestudy for {study.name}\n"
            "z (m), ux (m/s), uy (m/s), uz (m/s)\n" + "\n".join(rows) + "\n"
        )
    }


def _num(v: float) -> str:
    return (
        np.format_float_positional(v, unique=True, trim="-")
        if 1e-4 <= abs(v) < 1e6
        else (np.format_float_scientific(v, unique=True, trim="-") if v != 0.0 else "0")
    )


def _floor125(x: float) -> float:
    """Largest 1, 2 or 5 times a power of ten not above ``x``."""
    e = math.floor(math.log10(x))
    for m in (5.0, 2.0, 1.0):
        if m * 10.0**e <= x * (1 + 1e-12):
            return m * 10.0**e
    return 10.0**e


def type_row(name: str, seg: Any, mass: float) -> str:
    """The LINE TYPES row ``name`` of segment ``seg`` with mass ``mass`` [kg/m] in the
    fluid's terms (internal damping as MoorDyn's -zeta)."""
    ba = -seg.damping_ratio if seg.damping_ratio > 0.0 else 0.0
    return (
        f"{name}  {_num(seg.diameter)}  {_num(mass)}  {_num(seg.elastic_stiffness)}  "
        f"{_num(ba)}  {_num(seg.bending_stiffness)}  {_num(seg.drag_normal)}  "
        f"{_num(seg.added_mass_normal)}  {_num(seg.drag_tangential)}  "
        f"{_num(seg.added_mass_tangential)}"
    )


def time_options(dt: float) -> list[str]:
    """The OPTIONS rows of the time step (``dt`` [s] the axial stability limit, rounded
    down to 1-2-5) and the initial-condition settings."""
    return [
        f"{_num(_floor125(dt))}  dtM   ! explicit RK2: about 20 steps per period of the "
        f"fastest (axial) segment mode, pi l / (10 c) = {dt:.3g} s rounded down",
        "0.001  threshIC",
        "300  TmaxIC",
    ]


def file_text(
    front: list[str],
    type_rows: list[str],
    body_rows: list[str],
    point_rows: list[str],
    line_rows: list[str],
    opts: list[str],
    outputs: list[str],
) -> str:
    """A MoorDyn v2 input file of these sections' rows (no BODIES section without
    ``body_rows``)."""
    rows = [
        "--------------------- MoorDyn Input File ------------------------------------",
        *front,
        "---------------------- LINE TYPES ------------------------------------------",
        "TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx",
        "(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)",
        *type_rows,
    ]
    if body_rows:
        rows += [
            "---------------------- BODIES ----------------------------------------------",
            "ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*",
            "(#) (-) (m) (m) (m) (deg) (deg) (deg) (kg) (m) (kg-m^2) (m^3) (m^2) (-)",
            *body_rows,
        ]
    rows += [
        "---------------------- POINTS ----------------------------------------------",
        "ID Attachment X Y Z Mass Volume CdA Ca",
        "(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)",
        *point_rows,
        "---------------------- LINES -----------------------------------------------",
        "ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs",
        "(#) (name) (#) (#) (m) (-) (-)",
        *line_rows,
        "---------------------- OPTIONS ---------------------------------------------",
        *opts,
        "---------------------- OUTPUTS ---------------------------------------------",
        *outputs,
        "END",
        "------------------------- need this line -----------------------------------",
    ]
    return "\n".join(rows) + "\n"


def check_exportable(study: Study) -> None:
    """Raise :class:`InterchangeError` for a one-line study the MoorDyn file cannot hold
    (before its statics are solved: a spring line has no segments to solve)."""
    segs = study.line.segments
    if study.line.is_spring:
        raise InterchangeError(
            "line.kind: spring (a massless spring) has no MoorDyn line equivalent; "
            "export a kind: catenary line"
        )
    if study.line.pulleys:
        raise InterchangeError(
            "line.pulleys: a line over fixed pulleys has no MoorDyn line equivalent (a "
            "MoorDyn point holds the line, it does not let it slide); export the line "
            "without pulleys"
        )
    for i, seg in enumerate(segs):
        if seg.axial is not None and seg.axial.law != "linear":
            raise InterchangeError(
                f"line.segments.{i}.axial: the {seg.axial.law} law is not exported (the "
                "MoorDyn file takes a linear EA here); give axial_stiffness to export"
            )


def not_written(study: Study) -> list[str]:
    """Warnings naming what the study models and the MoorDyn file does not hold: the
    file is the line at rest, a MoorDyn run of it does without them."""
    out = []
    static = study.analysis.static
    if static.installation is not None:
        out.append(
            "analysis.static.installation: MoorDyn has no cable laying (pay-out along the "
            "line, moving frame): the file holds the line at rest, whose tension and shape "
            "differ from the laying solution the end positions come from"
        )
    if study.line.failure is not None or any(g.failure is not None for g in study.line.segments):
        out.append(
            "failure: the break condition is not written (no FAILURE section): the line "
            "does not part in MoorDyn"
        )
    if study.line.winch is not None:
        out.append("line.winch: not written: MoorDyn's line keeps its unstretched length")
    return out


def moordyn_input(
    study: Study,
    *,
    end_positions: tuple[np.ndarray, np.ndarray],
    position_at: np.ndarray,
    s_nodes: np.ndarray,
    coupled_ends: set[str],
    title: str,
) -> ExportedCase:
    """A MoorDyn v2 input file of ``study`` (one case, already resolved).

    Parameters
    ----------
    study : the case's study
    end_positions : static positions of ends A and B [m]
    position_at : static positions (n, 3) at ``s_nodes`` [m], for free points' initial guess
    s_nodes : unstretched arc lengths of ``position_at`` [m]
    coupled_ends : ends written as Coupled points ('a', 'b')
    title : front-matter line
    """
    env = study.environment
    rho, g = env.density, env.gravity
    segs = study.line.segments
    check_exportable(study)
    warnings: list[str] = not_written(study)
    bounds = np.concatenate([[0.0], np.cumsum([s.length for s in segs])])
    total = float(bounds[-1])
    for i, att in enumerate(study.line.attachments):
        if any(att.force):
            raise InterchangeError(
                f"line.attachments.{i}.force: a steady force {att.force} N has no MoorDyn v2 "
                "equivalent (points carry mass and volume only); give it as mass or volume"
            )
    # break points: segment joints and attachments; point masses/volumes at each
    cuts = {float(b): [0.0, 0.0, 0.0, 0.0] for b in bounds}  # mass, volume, added mass, CdA
    for i, att in enumerate(study.line.attachments):
        if att.s <= 0.0 or att.s >= total:
            warnings.append(
                f"line.attachments.{i} at s = {att.s:g} m sits on an end point: MoorDyn passes "
                "its load straight to the support, as does a fixed end here"
            )
        key = min(cuts, key=lambda c, s=att.s: abs(c - s))
        if abs(key - att.s) > 1e-9 * total:
            key = float(att.s)
            cuts[key] = [0.0, 0.0, 0.0, 0.0]
        cuts[key][0] += att.mass
        cuts[key][1] += att.volume
        cuts[key][2] += att.added_mass
        cuts[key][3] += att.drag_area
    positions = sorted(cuts)
    # line types: one per segment
    type_rows = []
    for i, seg in enumerate(segs):
        m = seg.mass_in(rho, g)
        if seg.weight_in_fluid is not None and seg.mass_per_length is not None:
            implied = (m - rho * seg.area) * g
            if abs(implied - seg.weight_in_fluid) > 1e-9 * max(abs(implied), 1.0):
                warnings.append(
                    f"line.segments.{i}: weight_in_fluid {seg.weight_in_fluid:g} N/m differs "
                    f"from (mass - rho A) g = {implied:g} N/m; MoorDyn uses mass and diameter"
                )
        type_rows.append(type_row(f"seg{i + 1}", seg, m))
    dyn = study.analysis.dynamic
    n_total = dyn.elements if dyn is not None else study.analysis.static.nodes - 1
    # points
    point_rows, coupled = [], {}
    end_a, end_b = end_positions
    for k, s in enumerate(positions):
        pid = k + 1
        if k == 0 or k == len(positions) - 1:
            label = "a" if k == 0 else "b"
            end = study.ends.a if k == 0 else study.ends.b
            pos = (
                np.asarray(end.position)
                if isinstance(end, FixedEnd)
                else (end_a if k == 0 else end_b)
            )
            kind = "Coupled" if label in coupled_ends else "Fixed"
            if kind == "Coupled":
                coupled[pid] = np.asarray(pos, dtype=float)
            note = f"end {label}" + (
                "" if isinstance(end, FixedEnd) else f" ({end.kind} end, at its static position)"
            )
        else:
            kind = "Free"
            pos = np.array([np.interp(s, s_nodes, position_at[:, j]) for j in range(3)])
            note = f"s = {s:g} m"
        mass, vol, added, cda = cuts[s]
        # MoorDyn's point added mass is Ca rho V: a body with added mass and no volume
        # has no Ca that gives it
        ca = added / (rho * vol) if vol > 0.0 and rho > 0.0 else 0.0
        if added > 0.0 and ca == 0.0:
            warnings.append(
                f"point {pid} (s = {s:g} m): added mass {added:g} kg with no displaced volume "
                "has no MoorDyn Ca (MoorDyn's point added mass is Ca rho V); written as 0"
            )
        point_rows.append(
            f"{pid}  {kind}  {_num(pos[0])}  {_num(pos[1])}  {_num(pos[2])}  {_num(mass)}  "
            f"{_num(vol)}  {_num(cda)}  {_num(ca)}   ! {note}"
        )
    # lines between consecutive points
    line_rows = []
    dt = math.inf
    for k in range(len(positions) - 1):
        s0, s1 = positions[k], positions[k + 1]
        iseg = int(np.searchsorted(bounds, 0.5 * (s0 + s1)) - 1)
        seg = segs[iseg]
        length = s1 - s0
        nseg = max(1, round(n_total * length / total))
        c = math.sqrt(
            seg.elastic_stiffness
            / (seg.mass_in(rho, g) + rho * seg.area * seg.added_mass_tangential)
        )
        dt = min(dt, math.pi * (length / nseg) / (10.0 * c))
        line_rows.append(f"{k + 1}  seg{iseg + 1}  {k + 1}  {k + 2}  {_num(length)}  {nseg}  -")
    dtm = _floor125(dt)
    # options
    lowest = min(end_a[2], end_b[2], float(position_at[:, 2].min()))
    opts = [f"{_num(g)}  g", f"{_num(rho)}  rho"]
    if env.depth is not None:
        opts.append(f"{_num(env.depth)}  WtrDpth")
        ref = max(range(len(segs)), key=lambda i: segs[i].diameter)
        seg = segs[ref]
        m_n = seg.mass_in(rho, g) + rho * seg.area * seg.added_mass_normal
        stiffness = (
            env.seabed.stiffness
            if env.seabed.stiffness is not None
            else default_seabed_stiffness(line_model(study).weight)
        )
        kbot, cbot = to_moordyn(
            stiffness, env.seabed.damping_ratio, diameter=seg.diameter, mass=m_n
        )
        opts.append(
            f"{_num(kbot)}  kBot   ! the study's contact stiffness {stiffness:.6g} N/m^2 over "
            f"the diameter of segment {ref + 1}"
        )
        opts.append(
            f"{_num(cbot)}  cBot   ! damping ratio {env.seabed.damping_ratio:g} of that "
            "segment's contact spring"
        )
        if len({sg.diameter for sg in segs}) > 1:
            warnings.append(
                "MoorDyn's seabed stiffness scales with each line type's diameter; kBot is "
                f"the study's contact stiffness over segment {ref + 1}'s diameter, so the "
                "thinner segments rest on a softer seabed in MoorDyn"
            )
        if env.seabed.slope_deg != 0.0:
            warnings.append(
                f"environment.seabed.slope_deg = {env.seabed.slope_deg:g}: MoorDyn's seabed "
                "here is flat at WtrDpth (a bathymetry file is not written)"
            )
        if env.seabed.friction > 0.0:
            opts.append(f"{_num(env.seabed.friction)}  FrictionCoefficient")
    else:
        deep = math.ceil(-lowest + 10.0 * total)
        opts.append(
            f"{deep}  WtrDpth   ! the study has no seabed: placed 10 line lengths below the "
            "lowest point, out of reach"
        )
    opts += time_options(dt)
    extra = current_table(study, opts)
    front = [f"MoorDyn v2 input file written by cablestudy: {title}"]
    if dyn is not None:
        for e in dyn.excitations:
            front.append(
                f"! excitation: end {e.end} moved along {list(e.direction)} "
                + (
                    f"(amplitude {e.amplitude:g} m, {e.frequency:g} Hz)"
                    if hasattr(e, "amplitude")
                    else "(a time table)"
                )
                + ": drive the Coupled point through MoorDyn's Step"
            )
    n_lines = len(line_rows)
    text = file_text(
        front, type_rows, [], point_rows, line_rows, opts, [f"FairTen{n_lines}", "AnchTen1"]
    )
    return ExportedCase(text, extra, warnings, coupled, dtm)
