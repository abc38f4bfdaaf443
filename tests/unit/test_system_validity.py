"""The checks of ``method: auto`` for a system (:mod:`cablestudy.dynamics.system_validity`)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from cablestudy.dynamics.system_validity import judge_system, line_failures, system_measures
from cablestudy.dynamics.validity import Validity, sag
from cablestudy.study.analysis import AutoSettings

DATA = Path(__file__).parents[1] / "data"


def _case8_model():  # noqa: ANN202
    from cablestudy.analyses.system import system_model
    from cablestudy.dynamics.system_frequency import system_linear
    from cablestudy.interchange import import_model, imported_yaml
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.system import solve_system
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    rel = "moorpy/tests/case8.dat"
    path = DATA / rel
    imported = import_model(path.read_text(), rel, folder=path.parent)
    _, grid = expand_cases(parse_study_text(imported_yaml(imported, rel), "<imported>"))
    system = system_model(grid[0].study)
    system = replace(
        system,
        lines=tuple(replace(sl, problem=replace(sl.problem, n_nodes=11)) for sl in system.lines),
    )
    model, why = system_linear(system, solve_system(system, STATIC_SOLVERS["catenary"]))
    assert model is not None, why
    return model


def test_rigid_translation_and_chord_motion_change_no_shape() -> None:
    """A line translated rigidly, or its nodes moved with the chord (interpolated end
    motion, the axial stretch of a taut line), has no geometric measure; a bulge of
    the same size mid-span has its size over the sag. The single line's measure (total
    displacement) would give the translation over the sag for the first."""
    model = _case8_model()
    L = len(model.lines)
    shift = np.array([0.3 - 0.1j, 0.2j, -0.1])
    n = [r.line.n_nodes for r in model.lines]
    zero_t = SimpleNamespace(
        tension_static=np.ones((L, 2)),
        end_tension=np.zeros((L, 2), dtype=complex),
        element_tension=[np.zeros(k - 1, dtype=complex) for k in n],
    )
    bed = [np.zeros(k, dtype=bool) for k in n]
    weight = [np.ones(k) for k in n]
    rigid = SimpleNamespace(**vars(zero_t), displacement=[np.tile(shift, (k, 1)) for k in n])
    for v in system_measures(model, rigid, bed, weight):
        assert v.amplitude_sag_ratio <= 1e-12  # rounding of (1 - xi) + xi = 1
    chord = []
    for r in model.lines:
        xi = (r.line.s / r.line.s[-1])[:, None]
        chord.append(xi * shift[None])  # one end held, the other moved: chord motion only
    moved = SimpleNamespace(**vars(zero_t), displacement=chord)
    for v in system_measures(model, moved, bed, weight):
        assert v.amplitude_sag_ratio <= 1e-12
    bulge = []
    for r in model.lines:
        b = np.zeros((r.line.n_nodes, 3), dtype=complex)
        b[r.line.n_nodes // 2] = shift
        bulge.append(b)
    bent = SimpleNamespace(**vars(zero_t), displacement=bulge)
    for r, v in zip(model.lines, system_measures(model, bent, bed, weight), strict=True):
        expected = np.linalg.norm(np.abs(shift)) / sag(r.line.position)
        np.testing.assert_allclose(v.amplitude_sag_ratio, expected, rtol=1e-12)


def test_judge_names_the_first_failing_line_or_the_nearest() -> None:
    auto = AutoSettings()
    ok = Validity(min_tension_ratio=0.95, amplitude_sag_ratio=0.01, touchdown_travel=0.0)
    near = Validity(min_tension_ratio=0.8, amplitude_sag_ratio=0.01, touchdown_travel=0.0)
    far = Validity(min_tension_ratio=0.9, amplitude_sag_ratio=0.2, touchdown_travel=0.05)
    trusted, why = judge_system(["a", "b", "c"], [ok, near, ok], auto)
    assert trusted and "nearest, line 'b'" in why, why
    trusted, why = judge_system(["a", "b", "c"], [ok, far, near], auto)
    assert not trusted and why.startswith("line 'b': large motion"), why
    assert "touchdown travel 0.05 L > 0.03 L" in why, why
    assert line_failures(ok, auto) == []
    unbounded = Validity(min_tension_ratio=1.0, amplitude_sag_ratio=0.0, touchdown_travel=np.inf)
    assert "unbounded" in line_failures(unbounded, auto)[0]


def _line_by_line(model, result, on_seabed, weight):  # noqa: ANN001, ANN202
    """The measures line by line (:func:`~cablestudy.dynamics.validity.measures_cases`
    of each line's response, as system_measures computed them before it went over all
    lines at once)."""
    from cablestudy.dynamics.validity import Validity, measures_cases

    out = []
    for i, red in enumerate(model.lines):
        line = red.line
        u = result.displacement[i]
        xi = ((line.s - line.s[0]) / (line.s[-1] - line.s[0]))[:, None]
        bed = np.asarray(on_seabed[i], dtype=bool)
        ratio, amp, travel = measures_cases(
            s=line.s,
            position=line.position,
            displacement=(u - (1.0 - xi) * u[0] - xi * u[-1])[None],
            element_tension_static=line.tension,
            element_tension_amplitude=np.abs(result.element_tension[i])[None],
            end_tension_static=result.tension_static[i],
            end_tension_amplitude=np.abs(result.end_tension[i])[None],
            laid_length=float(np.sum(line.rest_length[bed[:-1] & bed[1:]])),
            on_seabed=bed,
            submerged_weight=np.asarray(weight[i], dtype=float),
            held=np.diff(line.free_basis.tocsr().indptr).reshape(-1, 3).sum(axis=1) == 0,
        )
        out.append(
            Validity(
                min_tension_ratio=float(ratio[0]),
                amplitude_sag_ratio=float(amp[0]),
                touchdown_travel=float(travel[0]),
            )
        )
    return out


def test_measures_over_all_lines_are_the_line_by_line_ones() -> None:
    """system_measures over all lines at once gives each line's measures as
    validity.measures_cases does line by line, exactly (the same operations on the same
    numbers; minima and maxima are exact): on case8 (bridles, legs from anchors on the
    seabed) in surge and heave, and on MoorDyn's lines.txt (chains laid on the seabed,
    a touchdown point each: its travel), where a line's static tension goes to zero on
    the bed (slack check leaves it out)."""
    import math

    from cablestudy.analyses import system_frequency as asf
    from cablestudy.analyses.frequency import drag_settings
    from cablestudy.analyses.system import system_model
    from cablestudy.interchange import import_model, imported_yaml
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.system_methods import solve_system_by
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text
    from tests.system_frequency_reference import solve_system_harmonic

    root = Path(__file__).parents[2]
    case8 = (root / "configs" / "system-case8-surge.yaml").read_text()
    rel = "moordyn/tests/Mooring/lines.txt"
    path = DATA / rel
    chains = imported_yaml(import_model(path.read_text(), rel, folder=path.parent), rel)
    chains += """\
  dynamic:
    excitation: {body: vessel, dof: surge, amplitude: 0.2, frequency: 0.05}
    elements: 10
"""
    studies = [
        case8.replace("elements: 20", "elements: 6"),
        case8.replace("dof: surge, amplitude: 2.0", "dof: heave, amplitude: 0.05").replace(
            "elements: 20", "elements: 5"
        ),
        chains,
    ]
    # element counts no other test uses: the models are cached per process, and the
    # integration tests count the assemblies of theirs (20 and 16 elements a line)
    seen_travel = False
    for text in studies:
        _, cases = expand_cases(parse_study_text(text, "s.yaml"))
        case = cases[0]
        system = system_model(case.study)
        static = solve_system_by(system, "catenary", STATIC_SOLVERS)
        model = asf.system_frequency_model(case, system, static)
        assert not isinstance(model, str), model
        X, U, f = asf.harmonic_motion(case.study)
        res = solve_system_harmonic(
            model,
            2 * math.pi * f,
            X,
            drag_settings(case.study.analysis.dynamic),
            point_excitation=U,
        )
        assert res.status == 0, res.message
        bed, weight = asf._judged_nodes(model, system)
        got = system_measures(model, res, bed, weight)
        ref = _line_by_line(model, res, bed, weight)
        assert got == ref  # every float equal
        seen_travel |= any(v.touchdown_travel > 0.0 for v in got)
    assert seen_travel  # the touchdown branch was taken
