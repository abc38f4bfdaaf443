"""Shared set-up of the frequency-domain validation tests: a study text for the
moustafa cable (d = 0.01 m, L = 10.9774 m, span 10.792 m, m = 0.61 kg/m,
EA = 7.854e6 N) with the fluid, excitation and method given, evaluated in process."""

from __future__ import annotations

from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.analyses.variables import CaseRecord
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

LENGTH = 10.9774
SPAN = 10.792


def study_text(
    *,
    fluid: str = "vacuum",
    method: str = "frequency",
    amplitude: float = 0.001,
    frequency: float = 0.5,
    elements: int = 80,
    span: float = SPAN,
    extra: str = "",
    line_extra: str = "",
    dynamic: bool = True,
) -> str:
    text = f"""
name: fd-check
environment: {{fluid: {fluid}, gravity: 9.80665}}
line:
  segments:
    - {{length: {LENGTH}, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e+6,
       drag_normal: 1.2, drag_tangential: 0.01, added_mass_normal: 1.0{line_extra}}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [{span}, 0.0, 0.0]}}
analysis:
  static: {{method: analytic, nodes: 101, tolerance: 1.0e-12}}
  dynamic:
    excitation: {{end: b, direction: [1.0, 0.0, 0.0], amplitude: {amplitude},
                  frequency: {frequency}}}
    method: {method}
    elements: {elements}
{extra}"""
    return text if dynamic else text.split("  dynamic:")[0]


def evaluate(text: str) -> list[CaseRecord]:
    _, cases = expand_cases(parse_study_text(text))
    return [evaluate_case(c) for c in cases]
