"""Assembly of case records into one labelled xarray Dataset, and atomic netCDF writes.

Every output variable is declared once in :data:`OUTPUTS` with its extra dimensions,
units and long name; solvers add variables by adding entries here.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass, field, replace
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from . import __version__
from .cases import Case, SweepAxis
from .config.loader import StudySource
from .conventions import command_line, is_status_variable, status_flag_attrs
from .line_types import line_type_attrs
from .outputs import temporary_prefix, written

if TYPE_CHECKING:  # imported where used: a sweep run as arrays writes without xarray
    import xarray as xr


@dataclass(frozen=True)
class OutputVariable:
    """One output variable: extra dims, units, long name, dtype, and the analysis
    (``static``, ``modal``, ``dynamic``) whose failure blanks it (None:
    written whatever failed, as the per-analysis status variables; set from
    :data:`ANALYSIS_OF` below). ``nan_means`` says what a NaN means where NaN is a valid
    result of a successful analysis (empty: NaN is a failure)."""

    dims: tuple[str, ...]
    units: str
    long_name: str
    dtype: str = "float64"
    analysis: str | None = "dynamic"
    nan_means: str = ""


#: status of a case whose line broke in statics (cablestudy.statics.base.STATUS_BROKEN):
#: its data are kept, it is not counted as failed
STATUS_BROKEN = 10
#: status of a case whose static result failed its verification
#: (cablestudy.statics.base.STATUS_NOT_VERIFIED): its data are kept for inspection, it is
#: counted as failed
STATUS_NOT_VERIFIED = 11
#: statuses whose case data are written (others are NaN)
KEPT_STATUSES = (0, STATUS_BROKEN, STATUS_NOT_VERIFIED)

#: every data variable a case may produce: name -> extra dims, units, long name.
#: Numeric outputs (counters included) are float64 so that a failed case is NaN in every
#: one of them (DESIGN.md); dimensionless and text variables have units "1" (CF).
OUTPUTS: dict[str, OutputVariable] = {
    "x": OutputVariable(("s",), "m", "x position along the line"),
    "y": OutputVariable(("s",), "m", "y position along the line"),
    "z": OutputVariable(("s",), "m", "z position (up) along the line"),
    "tension": OutputVariable(("s",), "N", "effective tension along the line"),
    "tension_wall": OutputVariable(
        ("s",), "N", "actual (wall) tension along the line: effective tension + rho g z A"
    ),
    "elevation": OutputVariable(("s",), "rad", "elevation of the tangent above the horizontal"),
    "azimuth": OutputVariable(
        ("s",), "rad", "azimuth of the tangent's horizontal part, from +x towards +y"
    ),
    "elongation": OutputVariable(
        ("s",), "m", "stretched minus unstretched length from end A (integral of T / EA)"
    ),
    "arc_length": OutputVariable(("s",), "m", "unstretched arc length from end A"),
    "force_a": OutputVariable(("component",), "N", "force of the line on the attachment at end A"),
    "force_b": OutputVariable(("component",), "N", "force of the line on the attachment at end B"),
    "pulley_force": OutputVariable(
        ("pulley", "component"), "N", "force of the line on each pulley"
    ),
    "pulley_arc_length": OutputVariable(
        ("pulley",), "m", "unstretched arc length from end A at each pulley (kind: catenary)"
    ),
    "pulley_arc_length_min": OutputVariable(
        ("pulley",),
        "m",
        "smallest arc length from end A at each pulley over the steady window (time domain)",
    ),
    "pulley_arc_length_max": OutputVariable(
        ("pulley",),
        "m",
        "largest arc length from end A at each pulley over the steady window (time domain)",
    ),
    "break_time": OutputVariable(
        (), "s", "time at which the line parted in the dynamics (NaN: it did not)"
    ),
    "break_s": OutputVariable(
        (),
        "m",
        "unstretched arc length from end A of the midpoint of the element that parted "
        "(time domain of a kind: catenary line; NaN: it did not part)",
    ),
    "winch_paid_out": OutputVariable(
        (), "m", "change of the unstretched length by the winch at the end of the run"
    ),
    "tension_a": OutputVariable((), "N", "tension at end A"),
    "tension_b": OutputVariable((), "N", "tension at end B"),
    "laid_length": OutputVariable((), "m", "unstretched length resting on the seabed"),
    "static_iterations": OutputVariable((), "1", "iterations of the static solver"),
    "static_residual": OutputVariable((), "1", "final relative residual of the static solver"),
    "natural_frequency": OutputVariable(
        ("mode",), "Hz", "natural frequency about the static shape"
    ),
    "mode_shape": OutputVariable(
        ("mode", "s", "component"),
        "m",
        "mode shape: node displacement scaled to a largest displacement of 1 m",
    ),
    "modal_dof": OutputVariable((), "1", "degrees of freedom of the modal model"),
    "drag_iterations": OutputVariable((), "1", "outer drag iterations of the static solver"),
    # dynamics (cablestudy.dynamics.timedomain): tensions at the excited end over the
    # steady-state window (the envelope of the last periods when steady_converged is 0)
    "tension_static": OutputVariable((), "N", "static tension at the excited end (dynamic model)"),
    "tension_max": OutputVariable((), "N", "maximum tension at the excited end, steady window"),
    "tension_min": OutputVariable((), "N", "minimum tension at the excited end, steady window"),
    "tension_mean": OutputVariable((), "N", "mean tension at the excited end, steady window"),
    "tension_max_line": OutputVariable((), "N", "maximum tension along the line, steady window"),
    "tension_max_spread": OutputVariable(
        (), "N", "range of the per-period maximum end tension over the last periods"
    ),
    "tension_min_spread": OutputVariable(
        (), "N", "range of the per-period minimum end tension over the last periods"
    ),
    "steady_converged": OutputVariable(
        (), "1", "1 if the per-period max/min tension settled within the tolerance"
    ),
    "periods": OutputVariable((), "1", "excitation periods simulated"),
    "dynamic_steps": OutputVariable((), "1", "accepted time steps"),
    "newton_iterations": OutputVariable((), "1", "Newton iterations of the time steps"),
    "rejected_steps": OutputVariable((), "1", "rejected (retried shorter) time steps"),
    "dynamic_method": OutputVariable((), "1", "dynamic method used (time | frequency)", "str"),
    "dynamic_method_reason": OutputVariable(
        (), "1", "why this dynamic method ran (method: auto records its checks)", "str"
    ),
    # the tension envelope (range graph), one definition for both methods: the time
    # domain's per-step extremes of element and end tensions over the steady window,
    # the frequency domain's static +/- harmonic amplitude (a spectrum: most probable
    # maximum); element values at element midpoints interpolated to s
    # (cablestudy.frequency_cases.tension_along)
    "tension_envelope_max": OutputVariable(
        ("s",), "N", "largest effective tension along the line over the steady motion"
    ),
    "tension_envelope_min": OutputVariable(
        ("s",), "N", "smallest effective tension along the line over the steady motion"
    ),
    "touchdown_min": OutputVariable(
        (),
        "m",
        "smallest arc length from end A of the touchdown point over the steady window",
        nan_means="the line does not touch the seabed over the steady window",
    ),
    "touchdown_max": OutputVariable(
        (),
        "m",
        "largest arc length from end A of the touchdown point over the steady window",
        nan_means="the line does not touch the seabed over the steady window",
    ),
    "tension_amplitude_a": OutputVariable((), "N", "tension amplitude at end A"),
    "tension_amplitude_b": OutputVariable((), "N", "tension amplitude at end B"),
    "tension_phase_a": OutputVariable(
        (), "deg", "phase of the tension at end A ahead of the (first) excitation"
    ),
    "tension_phase_b": OutputVariable(
        (), "deg", "phase of the tension at end B ahead of the (first) excitation"
    ),
    "linearisation_iterations": OutputVariable((), "1", "drag linearisation iterations"),
    "linearisation_converged": OutputVariable(
        (), "1", "1 if the drag linearisation converged, else 0"
    ),
    "transfer_frequency": OutputVariable(
        ("frequency",), "Hz", "frequency of the tension transfer function or spectrum"
    ),
    "tension_std_a": OutputVariable((), "N", "standard deviation of the tension at end A"),
    "tension_std_b": OutputVariable((), "N", "standard deviation of the tension at end B"),
    "tension_psd_a": OutputVariable(
        ("frequency",), "N^2/Hz", "spectral density of the tension at end A"
    ),
    "tension_psd_b": OutputVariable(
        ("frequency",), "N^2/Hz", "spectral density of the tension at end B"
    ),
    "tension_rao_a": OutputVariable(
        ("frequency",), "N/m", "tension amplitude at end A per unit excitation amplitude"
    ),
    "tension_rao_b": OutputVariable(
        ("frequency",), "N/m", "tension amplitude at end B per unit excitation amplitude"
    ),
    "tension_rao_phase_a": OutputVariable(
        ("frequency",), "deg", "phase of the end-A tension ahead of the excitation"
    ),
    "tension_rao_phase_b": OutputVariable(
        ("frequency",), "deg", "phase of the end-B tension ahead of the excitation"
    ),
    "tension_rao_line": OutputVariable(
        ("frequency", "s"), "N/m", "tension amplitude along the line per unit excitation amplitude"
    ),
    "history_time": OutputVariable(("time",), "s", "time of the history samples"),
    "history_tension": OutputVariable(("time",), "N", "tension at the excited end"),
    "history_point_s": OutputVariable(("point",), "m", "arc length of the history points"),
    "history_displacement": OutputVariable(
        ("point", "time", "component"), "m", "displacement of the point from its static position"
    ),
    "history_velocity": OutputVariable(
        ("point", "time", "component"), "m/s", "velocity of the point"
    ),
    "history_acceleration": OutputVariable(
        ("point", "time", "component"), "m/s^2", "acceleration of the point"
    ),
    "history_line_position": OutputVariable(
        ("time", "s", "component"), "m", "position along the whole line (history)"
    ),
    "history_line_velocity": OutputVariable(
        ("time", "s", "component"), "m/s", "velocity along the whole line (history)"
    ),
    "history_line_tension": OutputVariable(
        ("time", "s"), "N", "effective tension along the whole line (history)"
    ),
}


@dataclass(frozen=True)
class DatabaseLayout:
    """Where a quasi-static database grid kind (``analysis.database.grid``) puts its
    tables: the prefix of its variables in the study dataset, its two grid dimensions,
    and the study-dataset variables holding the grid values (coordinates of those
    dimensions when every case shares them)."""

    prefix: str
    dims: tuple[str, str]
    grid_variables: tuple[str, str]
    #: (units, long name) of each grid dimension
    grid_attrs: tuple[tuple[str, str], tuple[str, str]]


#: per grid kind of ``analysis.database``
DATABASE_LAYOUTS: dict[str, DatabaseLayout] = {
    "cartesian": DatabaseLayout(
        "database_",
        ("horizontal_distance", "height_difference"),
        ("database_distance_grid", "database_height_grid"),
        (("m", "horizontal distance from end A to end B"), ("m", "height of end B above end A")),
    ),
    "radial": DatabaseLayout(
        "database_radial_",
        ("distance", "angle"),
        ("database_radial_distance_grid", "database_radial_angle_grid"),
        (
            ("m", "distance from end A to end B"),
            ("rad", "angle of the chord from end A to end B above the horizontal"),
        ),
    ),
}

#: the tabulated quantities of a database: name -> (vector?, units, long name)
DATABASE_QUANTITIES: dict[str, tuple[bool, str, str]] = {
    "force_a": (True, "N", "force of the line on end A"),
    "force_b": (True, "N", "force of the line on end B"),
    "tension_a": (False, "N", "tension at A"),
    "tension_b": (False, "N", "tension at B"),
    "tension_max": (False, "N", "largest tension along the line"),
    "laid_length": (False, "m", "unstretched length on the seabed"),
    "status": (False, "1", "static status per grid point (0 ok)"),
}


def _database_outputs() -> dict[str, OutputVariable]:
    """The study-dataset variables of every database layout (``database_*``)."""
    out = {}
    for lay in DATABASE_LAYOUTS.values():
        for q, (vector, units, long_name) in DATABASE_QUANTITIES.items():
            out[f"{lay.prefix}{q}"] = OutputVariable(
                lay.dims + (("component",) if vector else ()),
                units,
                f"quasi-static database: {long_name}",
            )
        for dim, var, (units, long_name) in zip(
            lay.dims, lay.grid_variables, lay.grid_attrs, strict=True
        ):
            out[var] = OutputVariable((dim,), units, long_name)
    return out


OUTPUTS.update(_database_outputs())
OUTPUTS["database_heading"] = OutputVariable(
    (), "rad", "heading of the database plane from end A (from +x towards +y)"
)

#: the analyses a case may run, each with a ``<name>_status`` where the study asks for it
ANALYSES = ("static", "modal", "dynamic")

#: the analysis each output belongs to, where not the dynamic one (the default): its
#: failure blanks the output. The quasi-static database (analysis.database: static
#: solves on its own grid) counts as part of the static analysis.
ANALYSIS_OF: dict[str, str] = {
    **dict.fromkeys(
        (
            "x",
            "y",
            "z",
            "tension",
            "tension_wall",
            "elevation",
            "azimuth",
            "elongation",
            "arc_length",
            "force_a",
            "force_b",
            "tension_a",
            "tension_b",
            "laid_length",
            "static_iterations",
            "static_residual",
            "drag_iterations",
            "pulley_force",
            "pulley_arc_length",
        ),
        "static",
    ),
    **dict.fromkeys(("natural_frequency", "mode_shape", "modal_dof"), "modal"),
    **{k: "static" for k in OUTPUTS if k.startswith("database_")},
}
OUTPUTS = {k: replace(v, analysis=ANALYSIS_OF.get(k, "dynamic")) for k, v in OUTPUTS.items()}
OUTPUTS["break_time"] = replace(OUTPUTS["break_time"], nan_means="the line did not part")
OUTPUTS["break_s"] = replace(OUTPUTS["break_s"], nan_means="the line did not part")
OUTPUTS.update(
    {
        f"{name}_status": OutputVariable(
            (),
            "1",
            f"{name} analysis status: 0 ok, nonzero failed (5: not run, the static "
            "analysis failed)",
            "int64",
            None,
        )
        for name in ANALYSES
    }
)

#: the outputs of a system study (lines joined at points, bodies;
#: cablestudy.system_cases): the one-line names gain a ``line`` dimension, and points and
#: bodies have their own variables
SYSTEM_OUTPUTS: dict[str, OutputVariable] = {
    **{
        k: replace(OUTPUTS[k], dims=("line", *OUTPUTS[k].dims))
        for k in (
            "x",
            "y",
            "z",
            "tension",
            "arc_length",
            "force_a",
            "force_b",
            "tension_a",
            "tension_b",
            "laid_length",
        )
    },
    **{k: OUTPUTS[k] for k in ("static_iterations", "static_residual", "static_status")},
    "point_position": OutputVariable(
        ("point", "component"), "m", "position of each free point in equilibrium", analysis="static"
    ),
    "body_position": OutputVariable(
        ("body", "dof"),
        "m, rad",
        "position of each body's reference point: surge, sway, heave [m], roll, pitch, yaw [rad]",
        analysis="static",
    ),
    "body_force": OutputVariable(
        ("body", "dof"),
        "N, N m",
        "force [N] and moment [N m] of all lines on each body about its reference point",
        analysis="static",
    ),
    "body_stiffness": OutputVariable(
        ("body", "dof", "dof_j"),
        "N/m, N/rad, N, N m/rad",
        "mooring stiffness of each body: minus d body_force[dof] / d body_position[dof_j], "
        "free points re-equilibrated (in a current: with the lines' drag loads held at "
        "their equilibrium values)",
        analysis="static",
    ),
}
# the system time domain (cablestudy.system_dynamic_cases): per line over the steady
# window, per body the lines' force and moment
SYSTEM_OUTPUTS.update(
    {
        **{
            f"tension_{q}_{end}": OutputVariable(
                ("line",),
                "N",
                f"{what} tension at end {end.upper()} of each line over the steady motion",
            )
            for q, what in (("max", "largest"), ("min", "smallest"), ("mean", "mean"))
            for end in ("a", "b")
        },
        **{
            k: replace(OUTPUTS[k], dims=("line", "s"))
            for k in ("tension_envelope_max", "tension_envelope_min")
        },
        "body_force_max": OutputVariable(
            ("body", "dof"),
            "N, N m",
            "largest force and moment of all lines on each body "
            "about its reference point over the steady motion",
        ),
        "body_force_min": OutputVariable(
            ("body", "dof"),
            "N, N m",
            "smallest force and moment of all lines on each body "
            "about its reference point over the steady motion",
        ),
        **{  # the system frequency domain (issue 24)
            f"tension_amplitude_{end}": OutputVariable(
                ("line",),
                "N",
                f"amplitude of the harmonic tension variation at end {end.upper()} of each "
                "line (frequency domain)",
            )
            for end in ("a", "b")
        },
        "history_tension_a": OutputVariable(
            ("line", "time"), "N", "tension at end A of each line (history)"
        ),
        "history_tension_b": OutputVariable(
            ("line", "time"), "N", "tension at end B of each line (history)"
        ),
        **{
            k: OUTPUTS[k]
            for k in (
                "dynamic_method",
                "dynamic_method_reason",
                "steady_converged",
                "periods",
                "dynamic_steps",
                "newton_iterations",
                "rejected_steps",
                "linearisation_iterations",
                "history_time",
                "dynamic_status",
            )
        },
    }
)
SYSTEM_OUTPUTS["x"] = replace(SYSTEM_OUTPUTS["x"], long_name="x position along each line")
SYSTEM_OUTPUTS["arc_length"] = replace(
    SYSTEM_OUTPUTS["arc_length"], long_name="unstretched arc length from end A of each line"
)

#: the six degrees of freedom of a body (coordinate of ``dof`` and ``dof_j``)
BODY_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")

#: per-case bookkeeping variables (always present)
CASE_VARIABLES: dict[str, OutputVariable] = {
    "status": OutputVariable(
        (),
        "1",
        "case status: 0 ok, 10 line broken (data kept), 11 static result not verified "
        "(failed, data kept), other nonzero failed",
        "int64",
    ),
    "message": OutputVariable((), "1", "why the case failed (empty when ok)", "str"),
    "warning": OutputVariable(
        (),
        "1",
        "why the case's results, though kept, are implausible or risky (strain, slack, "
        "unsettled, fallback; empty when none)",
        "str",
    ),
    "wall_time": OutputVariable(
        (), "s", "wall time of the case (cases solved together as arrays share their time equally)"
    ),
}

COORDINATES: dict[str, tuple[str, str]] = {
    "s": ("m", "unstretched arc length from end A"),
    "component": ("1", "vector component"),
    "mode": ("1", "mode number, by increasing natural frequency"),
    "line": ("1", "name of the line"),
    "point": ("1", "name of the free point"),
    "body": ("1", "name of the body"),
    "dof": ("1", "degree of freedom of the body"),
    "dof_j": ("1", "degree of freedom of the body (stiffness column)"),
}


@dataclass
class CaseRecord:
    """What one case produced: data arrays by output name, status, message, wall time."""

    hash: str
    index: tuple[int, ...]
    status: int
    message: str
    wall_time: float
    data: dict[str, np.ndarray] = field(default_factory=dict)
    settings: dict[str, Any] = field(default_factory=dict)
    #: why the kept results are implausible or risky (cablestudy.plausibility; '' if not)
    warning: str = ""


def analysis_ok(record: CaseRecord, analysis: str | None) -> bool:
    """Whether the data of ``analysis`` in ``record`` are written: its
    ``<analysis>_status`` is one of :data:`KEPT_STATUSES`. A record without one (a lost
    task, the database) counts by the case's ``status``."""
    if analysis is None:
        return True
    status = record.data.get(f"{analysis}_status") if analysis in ANALYSES else None
    if status is None:
        return record.status in KEPT_STATUSES
    return int(status) in KEPT_STATUSES


def _fill(dtype: str) -> Any:
    return {"int64": -1, "str": ""}.get(dtype, np.nan)


def _fill_rows(
    arr: np.ndarray, rows: list[tuple[tuple[int, ...], Any]], tail: tuple[int, ...]
) -> None:
    """Put each case's value at its sweep index; values of the full extent in one
    vectorised assignment, shorter ones (fewer nodes) padded by the fill value."""
    full = [(idx, v) for idx, v in rows if np.shape(v) == tail]
    if full and len(full[0][0]) > 0:
        where = tuple(
            np.array(col, dtype=np.intp) for col in zip(*(i for i, _ in full), strict=True)
        )
        values = [v for _, v in full]
        arr[where] = values if arr.dtype == object else np.asarray(values, dtype=arr.dtype)
    else:
        for idx, v in full:
            arr[idx] = v
    for idx, v in rows:
        if np.shape(v) != tail:
            arr[idx + tuple(slice(0, n) for n in np.shape(v))] = v


def sweep_coordinates(axes: list[SweepAxis]) -> dict[str, Any]:
    """The coordinates of the sweep dimensions (and, for axes of non-scalar values, zip
    groups or labels, their value coordinates), with units and long names. An axis with
    labels has them as its coordinate; its values go to ``<dim>_value``."""
    coords: dict[str, Any] = {}
    for a in axes:
        numeric = a.coordinate().dtype.kind in "iuf"
        indexed = len(a.paths) > 1 or not all(
            isinstance(v, int | float | str | bool) for v in a.values[0]
        )
        attrs = {
            "units": (a.units or "1") if numeric else "1",
            "long_name": a.long_name,
            "sweep_paths": ", ".join(a.paths),
        }
        if a.labels is not None:
            attrs["units"] = "1"
            attrs["long_name"] = a.long_name or f"label of the swept value of {a.paths[0]}"
        elif indexed:
            attrs["units"] = "1"
            if len(a.paths) == 1:
                attrs["long_name"] = f"index of the swept value of {a.paths[0]}"
        coords[a.name] = (a.name, a.coordinate(), attrs)
        if len(a.paths) == 1 and a.labels is not None and not indexed:
            # labelled scalars: the values themselves beside the labels
            values = np.asarray(a.values[0])
            scalar_units = (a.units or "1") if values.dtype.kind in "iuf" else "1"
            coords[f"{a.name}_value"] = (
                a.name,
                values.astype(object) if values.dtype.kind == "U" else values,
                {"long_name": a.long_name, "units": scalar_units},
            )
        if len(a.paths) == 1 and indexed:
            # values that are not scalars (vectors, mappings): keep them as text
            coords[f"{a.name}_value"] = (
                a.name,
                np.array([json.dumps(v) for v in a.values[0]], dtype=object),
                {"long_name": f"swept value of {a.paths[0]} (JSON)", "units": "1"},
            )
        if len(a.paths) > 1:
            for path, vals in zip(a.paths, a.values, strict=True):
                cname = f"{a.name}_{path.split('.')[-1]}"
                if cname in coords or cname == a.name:
                    cname = f"{a.name}_{path.replace('.', '_')}"
                units, long_name = _path_info(path)
                if all(isinstance(v, int | float) and not isinstance(v, bool) for v in vals):
                    coords[cname] = (
                        a.name,
                        np.asarray(vals, dtype=float),
                        {"long_name": long_name, "units": units or "1"},
                    )
                else:
                    coords[cname] = (
                        a.name,
                        np.array([json.dumps(v) for v in vals], dtype=object),
                        {"long_name": f"{long_name} (JSON)", "units": "1"},
                    )
    return coords


def assemble(
    axes: list[SweepAxis],
    cases: list[Case],
    records: dict[str, CaseRecord],
    src: StudySource,
    *,
    solver_settings: dict[str, Any] | None = None,
) -> xr.Dataset:
    """One Dataset on the sweep axes. A failed analysis is NaN (or -1, or "") in its own
    data variables (:attr:`OutputVariable.analysis`), the others are kept; a failed case
    is never dropped."""
    import xarray as xr

    data_vars, coords, attrs = assembled_variables(
        axes, cases, records, src, solver_settings=solver_settings
    )
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def assembled_variables(
    axes: list[SweepAxis],
    cases: list[Case],
    records: dict[str, CaseRecord],
    src: StudySource,
    *,
    solver_settings: dict[str, Any] | None = None,
) -> tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]]:
    """The (data variables, coordinates, attributes) of :func:`assemble`'s dataset, in
    the form ``xarray.Dataset`` takes and :func:`write_variables_atomic` writes."""
    shape = tuple(a.size for a in axes)
    dims = tuple(a.name for a in axes)
    by_index = {c.index: records[c.hash] for c in cases}
    present = sorted({k for r in by_index.values() for k in r.data})
    system = bool(cases) and cases[0].study.is_system
    registry = SYSTEM_OUTPUTS if system else OUTPUTS
    unknown = [k for k in present if k not in registry]
    if unknown:
        raise KeyError(f"output variables not declared in results.OUTPUTS: {unknown}")

    # lengths of extra dims: the largest any case produced
    extent: dict[str, int] = {"component": 3}
    for rec in by_index.values():
        for name, arr in rec.data.items():
            for d, n in zip(registry[name].dims, np.shape(arr), strict=True):
                extent[d] = max(extent.get(d, 0), n)

    data_vars: dict[str, Any] = {}
    for name, spec in {**CASE_VARIABLES, **{k: registry[k] for k in present}}.items():
        tail = tuple(extent[d] for d in spec.dims)
        dtype = object if spec.dtype == "str" else spec.dtype
        arr = np.full(shape + tail, _fill(spec.dtype), dtype=dtype)
        if name in CASE_VARIABLES:
            rows = [(idx, getattr(rec, name)) for idx, rec in by_index.items()]
        else:
            rows = [
                (idx, np.asarray(rec.data[name]))
                for idx, rec in by_index.items()
                if name in rec.data and analysis_ok(rec, spec.analysis)
            ]
        if spec.dtype == "str":
            # text as Python str (not 0-d arrays), so that netCDF sees one type when
            # failed cases hold the fill value ""
            rows = [
                (idx, str(v.item()) if isinstance(v, np.ndarray) and v.ndim == 0 else v)
                for idx, v in rows
            ]
        _fill_rows(arr, rows, tail)
        data_vars[name] = (
            dims + spec.dims,
            arr,
            {"units": spec.units, "long_name": spec.long_name},
        )

    coords: dict[str, Any] = sweep_coordinates(axes)
    if "component" in extent and any("component" in registry[k].dims for k in present):
        coords["component"] = (
            "component",
            np.array(["x", "y", "z"]),
            {"units": COORDINATES["component"][0], "long_name": COORDINATES["component"][1]},
        )
    if "mode" in extent and any("mode" in registry[k].dims for k in present):
        coords["mode"] = (
            "mode",
            np.arange(1, extent["mode"] + 1),
            {"units": COORDINATES["mode"][0], "long_name": COORDINATES["mode"][1]},
        )
    if system:
        study = cases[0].study
        named = {
            "line": list(study.lines),
            "point": [k for k, p in study.points.items() if p.kind == "free"],
            "body": list(study.bodies),
            "dof": list(BODY_DOFS),
            "dof_j": list(BODY_DOFS),
        }
        for dim, names in named.items():
            if dim in extent and any(dim in registry[k].dims for k in present):
                coords[dim] = (
                    dim,
                    np.array(names),
                    {"units": "1", "long_name": COORDINATES[dim][1]},
                )
        # s is the node index; each line's arc length is the variable arc_length beside it
    if "s" in extent and not system:
        arcs = [
            np.asarray(r.data["arc_length"])
            for r in by_index.values()
            if "arc_length" in r.data and analysis_ok(r, "static")
        ]
        if arcs and all(len(a) == extent["s"] and np.array_equal(a, arcs[0]) for a in arcs):
            coords["s"] = ("s", arcs[0], {"units": "m", "long_name": COORDINATES["s"][1]})
            data_vars.pop("arc_length", None)
    if "transfer_frequency" in data_vars and "frequency" not in coords:
        # the transfer function's frequencies: a coordinate when every case has the same
        freqs = [
            np.asarray(r.data["transfer_frequency"])
            for r in by_index.values()
            if "transfer_frequency" in r.data and analysis_ok(r, "dynamic")
        ]
        if freqs and all(np.array_equal(f, freqs[0]) for f in freqs):
            spec = registry["transfer_frequency"]
            coords["frequency"] = (
                "frequency",
                freqs[0],
                {"units": spec.units, "long_name": spec.long_name},
            )
            data_vars.pop("transfer_frequency")
    for grid, dim in (
        (g, d)
        for lay in DATABASE_LAYOUTS.values()
        for g, d in zip(lay.grid_variables, lay.dims, strict=True)
    ):
        # the quasi-static database's grid: a coordinate when every case has the same
        if grid in data_vars and dim not in coords:
            grids = [
                np.asarray(r.data[grid])
                for r in by_index.values()
                if grid in r.data and analysis_ok(r, "static")
            ]
            if grids and all(np.array_equal(g, grids[0]) for g in grids):
                spec = registry[grid]
                coords[dim] = (dim, grids[0], {"units": spec.units, "long_name": spec.long_name})
                data_vars.pop(grid)
    if "arc_length" in data_vars and "s" not in coords:
        coords["s"] = ("s", np.arange(extent["s"]), {"units": "1", "long_name": "node index"})

    _flag_statuses(data_vars)
    attrs = provenance(src, solver_settings or {})
    status = np.asarray(data_vars["status"][1])
    n_failed = int(np.count_nonzero((status != 0) & (status != STATUS_BROKEN)))
    attrs["cases"] = int(np.prod(shape)) if shape else 1
    attrs["cases_failed"] = n_failed
    attrs["cases_warned"] = int(np.count_nonzero(data_vars["warning"][1] != ""))
    if np.any(status == STATUS_BROKEN):
        attrs["cases_broken"] = int(np.count_nonzero(status == STATUS_BROKEN))
    return data_vars, coords, attrs


def _flag_statuses(data_vars: dict[str, Any]) -> None:
    """Add the CF status flags (:func:`status_flag_attrs`) to the status variables among
    ``data_vars`` (name -> (dims, values, attrs)), in place."""
    for name, (dims, values, var_attrs) in list(data_vars.items()):
        dtype = getattr(values, "dtype", None)
        if is_status_variable(name) and dtype is not None and dtype.kind in "if":
            data_vars[name] = (dims, values, {**var_attrs, **status_flag_attrs(dtype)})


def _path_info(path: str) -> tuple[str, str]:
    from .cases import _field_info

    return _field_info(tuple(path.split(".")))


def provenance(src: StudySource, solver_settings: dict[str, Any]) -> dict[str, Any]:
    """Global attributes that trace a dataset to its inputs: the study YAML and its hash,
    package versions, the solver-code fingerprint and the solver settings."""
    import platform
    from importlib.metadata import version

    import numpy
    import pydantic

    from .cases import code_fingerprint

    return {
        "Conventions": "CF-1.8",
        "title": str(src.data.get("name", "")),
        "study_name": str(src.data.get("name", "")),
        "study_description": str(src.data.get("description", "")),
        "study_yaml": src.text,
        "study_sha256": src.sha256,
        "cablestudy_version": __version__,
        "numpy_version": numpy.__version__,
        # from the installed metadata: the same strings as scipy.__version__ and
        # xarray.__version__, without importing them (the array path needs neither)
        "scipy_version": version("scipy"),
        "xarray_version": version("xarray"),
        "pydantic_version": pydantic.VERSION,
        "dask_version": version("dask"),
        "python_version": platform.python_version(),
        "cablestudy_code_sha256": code_fingerprint(),
        "solver_settings": json.dumps(solver_settings, sort_keys=True),
        "history": f"{datetime.now(UTC).isoformat(timespec='seconds')}: {command_line()}",
        **line_type_attrs(src),
    }


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _atomically(path: str | Path, write: Any) -> Path:
    """Call ``write(tmp)`` on a temporary file in ``path``'s folder, then fsync it, give it
    the permissions of a new file and rename it to ``path`` (atomic): a crash never
    leaves a half-written or corrupted result. The temporary file's name holds this
    process's id (:func:`cablestudy.outputs.temporary_prefix`): a later run removes it
    if this one is killed while writing. A full disk raises
    :class:`cablestudy.outputs.OutputWriteError`."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(
        prefix=temporary_prefix(f".{path.name}."), suffix=".tmp", dir=path.parent
    )
    os.close(fd)

    def complete() -> None:
        write(tmp)
        with open(tmp, "rb+") as fh:  # on disk before the rename makes it visible
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp makes it private (0600)
        os.replace(tmp, path)

    try:
        written(path, complete)  # a full disk named as such, whoever reports it
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path


#: netCDF compression of a floating-point data variable that is worth it (coordinates
#: are never compressed)
FLOAT_ENCODING: dict[str, Any] = {"zlib": True, "complevel": 1, "shuffle": True}
#: an in-memory variable is compressed when samples of it (SAMPLE_BLOCKS blocks of
#: SAMPLE_BYTES, evenly spaced) shrink to at most COMPRESS_BELOW of their size: a
#: constant or mostly-NaN variable shrinks a hundredfold, while the smooth profiles of a
#: sweep shrink by a third at a cost that exceeds their solve (zlib runs at some 100 MB/s,
#: the batch kernel at about 1 GB of output a second)
COMPRESS_BELOW = 0.5
SAMPLE_BYTES = 1 << 14
SAMPLE_BLOCKS = 4


def worth_compressing(values: Any) -> bool:
    """Whether to store the float variable ``values`` zlib-compressed: always for a
    lazily computed (dask) one, which is streamed in blocks; for a NumPy array, when
    byte-shuffled samples of it compress to at most :data:`COMPRESS_BELOW`."""
    import zlib

    if not isinstance(values, np.ndarray):
        return True
    flat = np.ascontiguousarray(values).reshape(-1)
    if flat.size == 0:
        return False
    block = max(1, SAMPLE_BYTES // flat.itemsize)
    starts = np.unique(np.linspace(0, max(flat.size - block, 0), SAMPLE_BLOCKS).astype(int))
    sample = np.concatenate([flat[i : i + block] for i in starts])
    raw = sample.view(np.uint8).reshape(-1, sample.itemsize).T.tobytes()  # as HDF5 shuffles
    return len(zlib.compress(raw, 1)) <= COMPRESS_BELOW * len(raw)


def write_atomic(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to netCDF at ``path`` through a temporary file in the same folder and
    an atomic rename: a crash never leaves a half-written or corrupted result."""
    ds = ds.copy()
    for name, v in ds.data_vars.items():
        if is_status_variable(str(name)) and v.dtype.kind in "if":
            v.attrs.update(status_flag_attrs(v.dtype))
    encoding: dict[str, dict[str, Any]] = {
        name: dict(FLOAT_ENCODING)
        for name, v in ds.data_vars.items()
        if v.dtype.kind == "f" and worth_compressing(v.values if v.chunks is None else v.data)
    }
    for name, v in ds.data_vars.items():
        if v.chunks is not None and name in encoding:
            # variables streamed from chunk files (dask): netCDF chunks of one block
            # of cases (at most 4 MiB), so that reading one case touches little
            block = [c[0] for c in v.chunks]
            per_case = max(1, int(np.prod(block[1:])) * v.dtype.itemsize)
            block[0] = max(1, min(block[0], (4 << 20) // per_case))
            encoding[name]["chunksizes"] = tuple(block)
    return _atomically(path, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding))


#: a variable as (dims, values, attrs), the tuple form xarray.Dataset takes
VariableSpec = tuple[Any, Any, dict[str, Any]]


def write_variables_atomic(
    data_vars: dict[str, VariableSpec],
    coords: dict[str, VariableSpec],
    attrs: dict[str, Any],
    path: str | Path,
) -> Path:
    """Write the dataset ``xarray.Dataset(data_vars, coords=coords, attrs=attrs)`` of
    in-memory NumPy arrays to netCDF at ``path`` (atomically, as :func:`write_atomic`),
    with the netCDF4 library directly: the file :func:`write_atomic` writes (the same
    dimensions, variables in the same order, dtypes, attributes, ``_FillValue`` and
    compression), without importing xarray (and the dask and distributed modules it
    loads when they are installed), which costs a small study more than its solve. A
    dataset this writer does not cover (a non-dimension coordinate, which xarray links
    through a ``coordinates`` attribute; a dtype other than float, int and text) goes
    through xarray."""
    items = [
        (k, (v[0],) if isinstance(v[0], str) else tuple(v[0]), v[1], v[2])
        for k, v in data_vars.items()
    ]
    items += [
        (k, (v[0],) if isinstance(v[0], str) else tuple(v[0]), v[1], v[2])
        for k, v in coords.items()
    ]
    simple = all(dims == (k,) for k, dims, _, _ in items[len(data_vars) :]) and all(
        isinstance(values, np.ndarray) and values.dtype.kind in "fiuUO" for _, _, values, _ in items
    )
    if not simple:
        import xarray as xr

        return write_atomic(xr.Dataset(data_vars, coords=coords, attrs=attrs), path)

    def write(tmp: str) -> None:
        import netCDF4

        with netCDF4.Dataset(tmp, mode="w", clobber=True, format="NETCDF4") as nc:
            for key, value in attrs.items():
                nc.setncattr(key, value)
            for _name, dims, values, _ in items:  # dimensions in order of first use
                for dim, size in zip(dims, values.shape, strict=True):
                    if dim not in nc.dimensions:
                        nc.createDimension(dim, size)
            for i, (name, dims, values, var_attrs) in enumerate(items):
                kind = values.dtype.kind
                text = kind in "UO"
                compress = kind == "f" and i < len(data_vars) and worth_compressing(values)
                encoding = FLOAT_ENCODING if compress else {}
                var = nc.createVariable(
                    varname=name,
                    datatype=str if text else values.dtype,
                    dimensions=dims,
                    zlib=encoding.get("zlib", False),
                    complevel=encoding.get("complevel", 4),
                    shuffle=encoding.get("shuffle", True),
                    fletcher32=False,
                    contiguous=False,
                    chunksizes=None,
                    endian="native",
                    least_significant_digit=None,
                    fill_value=np.nan if kind == "f" else None,
                )
                if i < len(data_vars) and is_status_variable(name) and kind in "if":
                    var_attrs = {**var_attrs, **status_flag_attrs(values.dtype)}
                var.setncatts(var_attrs)
                var.set_auto_maskandscale(False)
                var.set_auto_chartostring(False)
                if text:
                    values = values.astype(object)
                var[...] = values

    return _atomically(path, write)


def grid_dataset(
    axes: list[SweepAxis],
    chunks: list[tuple[int, int, Path]],
    src: StudySource,
    *,
    names: list[str],
    tails: dict[str, tuple[int, ...]],
    arc: np.ndarray | None,
    solver_settings: dict[str, Any],
    lazy: bool = True,
    fallbacks: dict[str, int] | None = None,
    named: dict[str, list[str]] | None = None,
) -> xr.Dataset:
    """The dataset of a study run as arrays (:mod:`cablestudy.grid`), with the same
    variables, dims, coordinates and attributes as :func:`assemble` would give, its large
    variables backed lazily (dask) by the chunk files ``(lo, hi, path)`` (rows ``lo:hi``
    of the first axis each, written by the runner), so that writing it streams chunk by
    chunk; with ``lazy=False`` they are read into memory instead (small studies).
    ``arc``: the arc lengths every successful case shares (then the ``s`` coordinate, as
    in :func:`assemble`), or None (then ``arc_length`` stays a variable and ``s`` is the
    node index)."""
    import xarray as xr

    shape = tuple(a.size for a in axes)
    rest = shape[1:]

    def load(path: Path, name: str) -> np.ndarray:
        with np.load(path, allow_pickle=False) as z:
            key = f"v_{name}"
            if key in z.files:
                return z[key]
            n = len(z["v_status"])
            if name == "warning":  # a chunk with no warnings may not store the column
                return np.full(n, "")
            # a chunk that failed as a whole holds no data: NaN, as a failed case
            return np.full((n, *tails[name]), np.nan)

    def column(name: str) -> np.ndarray:
        return np.concatenate([load(path, name) for _, _, path in chunks])

    values: dict[str, Any] = {}
    for name in names:
        if name == "arc_length" and arc is not None:
            continue
        tail = tails[name]
        if lazy:
            import dask
            import dask.array as da

            values[name] = da.concatenate(
                [
                    da.from_delayed(
                        dask.delayed(load)(path, name).reshape((hi - lo, *rest, *tail)),
                        shape=(hi - lo, *rest, *tail),
                        dtype=np.float64,
                    )
                    for lo, hi, path in chunks
                ],
                axis=0,
            )
        else:  # small enough to hold: no dask needed
            values[name] = np.concatenate(
                [load(path, name).reshape((hi - lo, *rest, *tail)) for lo, hi, path in chunks]
            )
    data_vars, coords, attrs = grid_variables(
        axes,
        src,
        status=column("status"),
        message=column("message"),
        warning=column("warning"),
        wall_time=column("wall_time"),
        values=values,
        tails=tails,
        arc=arc,
        solver_settings=solver_settings,
        fallbacks=fallbacks,
        named=named,
    )
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def grid_variables(
    axes: list[SweepAxis],
    src: StudySource,
    *,
    status: np.ndarray,
    message: np.ndarray,
    wall_time: np.ndarray,
    values: dict[str, Any],
    warning: np.ndarray | None = None,
    tails: dict[str, tuple[int, ...]],
    arc: np.ndarray | None,
    solver_settings: dict[str, Any],
    fallbacks: dict[str, int] | None = None,
    named: dict[str, list[str]] | None = None,
) -> tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]]:
    """Data variables, coordinates and global attributes of a study run as arrays, in
    the form ``xarray.Dataset(data_vars, coords=coords, attrs=attrs)`` takes (and
    :func:`write_variables_atomic` writes): per case ``status``, ``message``,
    ``wall_time`` (flat, cases in C order) and per output its values (shape
    (*sweep shape, *tail), NumPy or dask) -- the variables, dims, coordinates and
    attributes :func:`assemble` gives. ``arc``: the arc lengths every successful case
    shares (then the ``s`` coordinate, and ``arc_length`` is not among ``values``), or
    None (then ``s`` is the node index). ``fallbacks``: why cases were solved by the
    general solver, counted (the ``cases_fallback`` and ``fallback_reasons``
    attributes). ``named``: a system study's coordinates by dimension (line, point,
    body; cablestudy.system_grid), whose outputs are :data:`SYSTEM_OUTPUTS`."""
    registry = OUTPUTS if named is None else SYSTEM_OUTPUTS
    shape = tuple(a.size for a in axes)
    dims = tuple(a.name for a in axes)
    data_vars: dict[str, VariableSpec] = {}
    status = status.reshape(shape)
    warnings = (
        np.full(shape, "", dtype=object)
        if warning is None
        else warning.astype(object).reshape(shape)
    )
    case = (
        ("status", status),
        ("message", message.astype(object).reshape(shape)),
        ("warning", warnings),
        ("wall_time", wall_time.reshape(shape)),
    )
    for name, arr in case:
        spec = CASE_VARIABLES[name]
        data_vars[name] = (dims, arr, {"units": spec.units, "long_name": spec.long_name})
    # the array path runs the statics only: its status is the case's
    spec = OUTPUTS["static_status"]
    data_vars["static_status"] = (
        dims,
        status.astype(np.int64),
        {"units": spec.units, "long_name": spec.long_name},
    )
    for name in sorted(values):
        spec = registry[name]
        data_vars[name] = (
            dims + spec.dims,
            values[name],
            {"units": spec.units, "long_name": spec.long_name},
        )
    coords = sweep_coordinates(axes)
    if named is not None:  # a system: its named dimensions (as assemble gives them)
        named = {**named, "dof": list(BODY_DOFS), "dof_j": list(BODY_DOFS)}
        for dim, names in named.items():
            if any(dim in registry[k].dims for k in values):
                coords[dim] = (
                    dim,
                    np.array(names),
                    {"units": "1", "long_name": COORDINATES[dim][1]},
                )
    if any("component" in registry[k].dims for k in values):
        coords["component"] = (
            "component",
            np.array(["x", "y", "z"]),
            {"units": COORDINATES["component"][0], "long_name": COORDINATES["component"][1]},
        )
    if arc is not None:
        coords["s"] = ("s", arc, {"units": "m", "long_name": COORDINATES["s"][1]})
    elif "arc_length" in values:
        n_s = tails["arc_length"][-1]  # (s,) per case, or a system's (line, s)
        coords["s"] = ("s", np.arange(n_s), {"units": "1", "long_name": "node index"})
    _flag_statuses(data_vars)
    attrs = provenance(src, solver_settings)
    attrs["cases"] = int(np.prod(shape))
    # as assemble counts them: a broken line is a result, not a failure
    attrs["cases_failed"] = int(np.count_nonzero((status != 0) & (status != STATUS_BROKEN)))
    attrs["cases_warned"] = int(np.count_nonzero(warnings != ""))
    if np.any(status == STATUS_BROKEN):
        attrs["cases_broken"] = int(np.count_nonzero(status == STATUS_BROKEN))
    fallbacks = fallbacks or {}
    attrs["cases_fallback"] = int(sum(fallbacks.values()))
    attrs["fallback_reasons"] = "; ".join(
        f"{n} x {why}" for why, n in sorted(fallbacks.items(), key=lambda kv: -kv[1])
    )
    return data_vars, coords, attrs
