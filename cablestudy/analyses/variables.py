"""The output variables every analysis may write, declared once: dimensions, units,
long name and the analysis they belong to (:data:`OUTPUTS`; a system's
:data:`SYSTEM_OUTPUTS`), the per-case variables and coordinates, the statuses whose
results are kept, and :class:`CaseRecord`, what one case produced.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np


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
    #: the value of a case whose analysis failed, or beyond a shorter case's extent,
    #: where not the dtype's own (NaN, -1 or ''; cablestudy.analyses.grid_chunk)
    fill: int | None = None


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
        "mode shape: node displacement scaled to a largest displacement of 1 m, signed so "
        "that its largest component is positive (on the modal model's nodes; of tied nodes "
        "the first from end A, of tied components the first of x, y, z)",
    ),
    "modal_dof": OutputVariable((), "1", "degrees of freedom of the modal model"),
    "drag_iterations": OutputVariable((), "1", "outer drag iterations of the static solver"),
    # dynamics (cablestudy.dynamics.timedomain): tensions at the excited end over the
    # steady-state window (the envelope of the last periods when steady_converged is 0)
    # one variable for both methods (dynamic_method says which ran): each writes the
    # static state its motion is about
    "tension_static": OutputVariable(
        (),
        "N",
        "static tension at the excited end, in the equilibrium the dynamic method's motion "
        "is about: the time domain's own discretised model at rest (it differs from the "
        "static solver's by that model's discretisation), the frequency domain's static "
        "solution, which it linearises about (the static solver's); dynamic_method says "
        "which ran",
    ),
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
    # (cablestudy.analyses.along_line.tension_along)
    "tension_envelope_max": OutputVariable(
        ("s",), "N", "largest effective tension along the line over the steady motion"
    ),
    "tension_envelope_min": OutputVariable(
        ("s",), "N", "smallest effective tension along the line over the steady motion"
    ),
    # the elevation envelope (range graph of z): the time domain's per-step highest z of
    # each node over the steady window, the frequency domain's static z + |z amplitude|
    # (a spectrum: most probable maximum); the surface warning judges it
    "z_envelope_max": OutputVariable(
        ("s",), "m", "highest elevation (z, up; the surface at 0) along the line over the motion"
    ),
    "touchdown_min": OutputVariable(
        (),
        "m",
        "smallest arc length from end A of the touchdown point over the steady window "
        "(frequency domain: the static point minus the "
        "catenary estimate of its travel; for a spectrum, the most probable maximum "
        "travel over storm_duration)",
        nan_means="the line does not touch the seabed over the steady window",
    ),
    "touchdown_max": OutputVariable(
        (),
        "m",
        "largest arc length from end A of the touchdown point over the steady window "
        "(frequency domain: the static point plus the "
        "catenary estimate of its travel; for a spectrum, the most probable maximum "
        "travel over storm_duration)",
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
    "status": (
        False,
        "1",
        "static status per grid point (0 ok; 5 not solved: the case's statics failed, or "
        "the point lies beyond this case's grid)",
    ),
}

#: status of a database point not solved (the case's statics failed, or the point lies
#: beyond a smaller grid of the sweep): cablestudy.analyses.evaluate.STATUS_NOT_RUN
_DATABASE_NOT_SOLVED = 5


def _database_outputs() -> dict[str, OutputVariable]:
    """The study-dataset variables of every database layout (``database_*``)."""
    out = {}
    for lay in DATABASE_LAYOUTS.values():
        for q, (vector, units, long_name) in DATABASE_QUANTITIES.items():
            # the per-point status is a code (CF flag_values of the variable's integer
            # type): an integer variable, "not solved" where a case has no value
            status = q == "status"
            out[f"{lay.prefix}{q}"] = OutputVariable(
                lay.dims + (("component",) if vector else ()),
                units,
                f"quasi-static database: {long_name}",
                dtype="int64" if status else "float64",
                fill=_DATABASE_NOT_SOLVED if status else None,
            )
        # the check of each cell at build (cablestudy.analyses.database.check_cells)
        out[f"{lay.prefix}cell_check"] = OutputVariable(
            lay.dims,
            "1",
            "quasi-static database: check of the cell whose lower corner is this grid point "
            "(0 verified; bits: 1 straddles the taut chord, 2 patch off a direct solve at the "
            "cell centre by > 1 %; -1 no cell: last row or column, or not checked)",
            dtype="int64",
            fill=-1,
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
# cases of one study may run different dynamic methods (method: auto, or a sweep over
# analysis.dynamic.method): each writes only its own method's counters and results, and
# the other method's are NaN in it, said so (not a bare NaN, which means a failure)
for _k in (
    "tension_max_spread",
    "tension_min_spread",
    "periods",
    "dynamic_steps",
    "newton_iterations",
    "rejected_steps",
):
    OUTPUTS[_k] = replace(
        OUTPUTS[_k],
        nan_means="the case ran the frequency domain (dynamic_method 'frequency'), which "
        "has no time steps",
    )
for _k in (
    "tension_amplitude_a",
    "tension_amplitude_b",
    "tension_phase_a",
    "tension_phase_b",
    "linearisation_iterations",
    "linearisation_converged",
):
    OUTPUTS[_k] = replace(
        OUTPUTS[_k],
        nan_means="the case ran the time domain (dynamic_method 'time'), which has no "
        "harmonic amplitude, phase or drag linearisation",
    )
# a sweep may switch the mode shapes off in some cases (analysis.modal.mode_shapes), or
# ask some cases for fewer modes than others (analysis.modal.modes: the mode dimension
# is the largest count)
#: (natural_frequency has no nan_means in the registry, so that a NaN frequency of a
#: solved case is caught: the dataset adds this one where the padding shows,
#: cablestudy/run/dataset.py)
FEWER_MODES = "the mode number is beyond the case's analysis.modal.modes (a sweep over it)"
OUTPUTS["mode_shape"] = replace(
    OUTPUTS["mode_shape"],
    nan_means="the case's analysis.modal.mode_shapes is false: its mode shapes were not "
    f"written; or {FEWER_MODES}",
)
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
#: cablestudy.analyses.system): the one-line names gain a ``line`` dimension, and points and
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
    "point_seabed_force": OutputVariable(
        ("point", "component"),
        "N",
        "force of the seabed on each free point resting on it (zero off the seabed)",
        analysis="static",
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
# the system time domain (cablestudy.analyses.system_dynamic): per line over the steady
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
            for k in ("tension_envelope_max", "tension_envelope_min", "z_envelope_max")
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
                # a case of method auto may run the time domain: said, not a bare NaN
                nan_means="the case ran the time domain (dynamic_method 'time'): no "
                "harmonic amplitude",
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
# the system frequency domain writes no steady_converged (the one-line one writes 1)
SYSTEM_OUTPUTS["steady_converged"] = replace(
    SYSTEM_OUTPUTS["steady_converged"],
    nan_means="the case ran the frequency domain (dynamic_method 'frequency'), which has "
    "no steady window to settle",
)
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
    #: why the kept results are implausible or risky (cablestudy.analyses.plausibility; '' if not)
    warning: str = ""
    #: why the general solver, not a batch kernel, solved its statics
    #: (cablestudy.analyses.fallback; '' if a batch kernel did)
    fallback: str = ""


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
