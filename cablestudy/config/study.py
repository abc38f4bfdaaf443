"""The study file: the top-level model and its cross-field checks."""

from __future__ import annotations

import re
from typing import Any

from pydantic import Field, field_validator, model_validator

from .analysis import Analysis
from .base import StrictModel
from .ends import Ends, FixedEnd
from .environment import Environment
from .line import Line

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.\-]*$")


class Study(StrictModel):
    """A whole study file. ``sweep`` is kept raw here and expanded by
    :func:`cablestudy.cases.expand_cases`."""

    name: str = Field(description="study name; results go to <out>/<name>.nc")
    description: str = ""
    environment: Environment = Environment()
    line: Line
    ends: Ends
    analysis: Analysis = Analysis()
    sweep: dict[str, Any] = {}

    @field_validator("name")
    @classmethod
    def _file_name(cls, value: str) -> str:
        if not _NAME.match(value):
            raise ValueError(
                f"name {value!r} must be usable as a file name: letters, digits, '_', '-', '.', "
                "starting with a letter or digit"
            )
        return value

    @model_validator(mode="after")
    def _solvable(self) -> Study:
        a, b = self.ends.a, self.ends.b
        if not isinstance(a, FixedEnd) and not isinstance(b, FixedEnd):
            raise ValueError(
                f"ends: end a is '{a.kind}' and end b is '{b.kind}'; at least one end must be "
                "'fixed' for the static problem to have a unique solution"
            )
        depth = self.environment.depth
        if depth is not None and self.environment.seabed.slope_deg == 0.0:
            for label, end in (("a", a), ("b", b)):
                if isinstance(end, FixedEnd) and end.position[2] < -depth - 1e-9 * depth:
                    raise ValueError(
                        f"ends.{label}.position z = {end.position[2]} lies below the seabed at "
                        f"z = {-depth}; allowed z >= -depth"
                    )
        return self
