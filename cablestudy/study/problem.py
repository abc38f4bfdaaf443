"""Conversion of a validated :class:`~cablestudy.study.Study` into the plain inputs of
the physics solvers (frozen dataclasses of arrays, SI units)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..statics import EndCondition, LineModel, Medium, StaticProblem
from ..statics.limits import StaticLimits
from . import FixedEnd, ForceEnd, MooringEnd, Study
from .analysis import Installation
from .ends import End


def line_model(study: Study) -> LineModel:
    """Segments and attachments as arrays. Weight in the fluid is taken as given, or
    as (mass - density * area) * gravity; mass, where not given, as
    weight / gravity + density * area."""
    env = study.environment
    rho, g = env.density, env.gravity
    segs = study.line.segments
    area = np.array([s.area for s in segs])
    mass = np.array(
        [
            s.mass_per_length if s.mass_per_length is not None else s.weight_in_fluid / g + rho * a  # type: ignore[operator]
            for s, a in zip(segs, area, strict=True)
        ]
    )
    weight = np.array(
        [
            s.weight_in_fluid if s.weight_in_fluid is not None else (m - rho * a) * g
            for s, m, a in zip(segs, mass, area, strict=True)
        ]
    )
    atts = study.line.attachments

    def col(name: str) -> np.ndarray:
        return np.array([getattr(s, name) for s in segs], dtype=float)

    att_force = np.array(
        [
            np.asarray(a.force, dtype=float) + np.array([0.0, 0.0, -(a.mass - rho * a.volume) * g])
            for a in atts
        ]
    ).reshape(len(atts), 3)
    return LineModel(
        length=col("length"),
        weight=weight,
        mass=mass,
        axial_stiffness=np.array([s.elastic_stiffness for s in segs], dtype=float),
        diameter=col("diameter"),
        drag_normal=col("drag_normal"),
        drag_tangential=col("drag_tangential"),
        added_mass_normal=col("added_mass_normal"),
        added_mass_tangential=col("added_mass_tangential"),
        bending_stiffness=col("bending_stiffness"),
        damping_ratio=col("damping_ratio"),
        attachment_s=np.array([a.s for a in atts], dtype=float),
        attachment_force=att_force,
        attachment_mass=np.array([a.mass for a in atts], dtype=float),
        attachment_volume=np.array([a.volume for a in atts], dtype=float),
        axial_law=_laws(segs),
        attachment_drag_area=np.array([a.drag_area for a in atts], dtype=float),
    )


def _laws(segs: list[Any]) -> tuple:
    """Per segment its non-linear axial law, None where it is T = EA e (``axial_stiffness``,
    ``{law: linear}`` or a polynomial with only its first coefficient); () when all are
    linear, so linear lines keep the closed-form and compiled paths."""
    laws = tuple(s.axial_law() if s.is_nonlinear else None for s in segs)
    return laws if any(law is not None for law in laws) else ()


def static_limits(study: Study) -> StaticLimits:
    """Break limits per segment (a segment's own ``failure``, else ``line.failure``) and the
    strain range each non-linear law was checked on."""
    from .line import DEFAULT_MAX_STRAIN

    line = study.line
    if line.is_spring:
        brk = line.failure
        return StaticLimits(
            segment_ends=np.array([0.0, line.total_length]),
            break_tension=np.array([brk.limit if brk else np.inf]),
            break_source=(_break_source(brk, "line.failure"),),
        )
    tension, source = [], []
    for i, seg in enumerate(line.segments):
        brk = seg.failure or line.failure
        key = f"line.segments.{i}.failure" if seg.failure else "line.failure"
        tension.append(brk.limit if brk else np.inf)
        source.append(_break_source(brk, key))
    return StaticLimits(
        segment_ends=np.concatenate(([0.0], np.cumsum([s.length for s in line.segments]))),
        break_tension=np.array(tension, dtype=float),
        break_source=tuple(source),
        # a law's range is checked where it is non-linear, or where max_strain is given
        law=tuple(
            s.axial_law()
            if s.is_nonlinear or (s.axial is not None and s.axial.max_strain is not None)
            else None
            for s in line.segments
        ),
        max_strain=tuple(
            float((s.axial.max_strain if s.axial else None) or DEFAULT_MAX_STRAIN)
            for s in line.segments
        ),
    )


def _break_source(brk: Any, key: str) -> str:
    if brk is None or not math.isfinite(brk.limit):  # none, or a failure time only
        return ""
    if brk.tension is not None:
        return f"{key}.tension"
    mbl, sf = brk.minimum_breaking_load, brk.safety_factor or 1.0
    return f"{key}: minimum_breaking_load {mbl:g} N / safety_factor {sf:g}"


def medium(study: Study) -> Medium:
    env = study.environment
    if env.current:
        pts = sorted(env.current, key=lambda p: p.z)
        z = np.array([p.z for p in pts])
        heading = np.radians([p.heading_deg for p in pts])
        speed = np.array([p.speed for p in pts])
        vel = np.stack([speed * np.cos(heading), speed * np.sin(heading), np.zeros_like(speed)], 1)
    else:
        z, vel = np.zeros(0), np.zeros((0, 3))
    return Medium(
        density=env.density,
        gravity=env.gravity,
        depth=env.depth,
        seabed_slope=math.radians(env.seabed.slope_deg),
        seabed_heading=math.radians(env.seabed.slope_heading_deg),
        friction=env.seabed.friction,
        current_z=z,
        current_velocity=vel,
    )


def end_condition(end: End) -> EndCondition:
    if isinstance(end, FixedEnd):
        return EndCondition(kind="fixed", position=np.asarray(end.position, dtype=float))
    if isinstance(end, ForceEnd):
        return EndCondition(kind="force", force=np.asarray(end.force, dtype=float))
    if isinstance(end, MooringEnd):
        return EndCondition(kind="mooring", force=np.array([*end.force, 0.0]), z=end.z)
    raise TypeError(f"unknown end {end!r}")


def static_problem(study: Study) -> StaticProblem:
    settings = study.analysis.static
    return StaticProblem(
        line=line_model(study),
        medium=medium(study),
        end_a=end_condition(study.ends.a),
        end_b=end_condition(study.ends.b),
        n_nodes=settings.nodes,
        tolerance=settings.tolerance,
        max_iterations=settings.max_iterations,
        drag_elements=settings.drag_elements or 0,
        stretched_drag_diameter=settings.drag_diameter == "stretched",
        seabed_stiffness=study.environment.seabed.stiffness,
        friction_lateral=study.environment.seabed.friction_lateral,
        **_installation(settings.installation),
    )


def _installation(inst: Installation | None) -> dict[str, Any]:
    """Pay-out speed [m/s] and laying-frame velocity [m/s] of a steady cable laying."""
    if inst is None:
        return {}
    vx, vy = inst.touchdown_velocity
    return {"payout_speed": float(inst.payout_speed), "touchdown_velocity": np.array([vx, vy, 0.0])}
