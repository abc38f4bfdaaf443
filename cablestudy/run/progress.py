"""What a run tells its user: the progress line, and the summary at the end
(cases done, cached, failed and warned, failures and warnings grouped by their text).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class RunSummary:
    path: Path
    n_cases: int
    n_reused: int
    n_computed: int
    n_failed: int
    wall_time: float
    failures: dict[str, int] = field(default_factory=dict)
    #: the scheduler that ran the cases after the in-process probe ('' if none ran)
    scheduler: str = ""
    #: seconds per phase, where measured (solve, assembly, write)
    timings: dict[str, float] = field(default_factory=dict)
    #: the quasi-static database's own file, where the study has one
    database_path: Path | None = None
    #: cases whose kept results carry a warning, and each warning with its count
    n_warned: int = 0
    warnings: dict[str, int] = field(default_factory=dict)
    #: per warning text, the first case that has it (sweep coordinates), where known
    warned_cases: dict[str, str] = field(default_factory=dict)
    #: cases of a study run as arrays that no batch kernel took (solved by the general
    #: solver), counted by reason
    fallbacks: dict[str, int] = field(default_factory=dict)
    #: cases whose line broke in statics (status 10: results kept, not failed), by message
    broken: dict[str, int] = field(default_factory=dict)

    def report(self) -> str:
        """Text summary; failures grouped by message (numbers in messages masked so that
        e.g. residuals of different size group together), most frequent first."""
        lines = [
            f"wrote {self.path}: {self.n_cases} cases ({self.n_computed} computed, "
            f"{self.n_reused} reused from cache), {self.n_failed} failed, "
            + (f"{sum(self.broken.values())} broken, " if self.broken else "")
            + (f"{self.n_warned} with warnings, " if self.n_warned else "")
            + f"{self.wall_time:.2f} s"
            + (f" ({self.scheduler})" if self.scheduler else "")
        ]
        if self.database_path is not None:
            lines.append(f"wrote {self.database_path}: the quasi-static database")
        if self.fallbacks:
            lines.append(
                f"{sum(self.fallbacks.values())} cases solved by the general solver (no batch "
                "kernel took them): "
                + "; ".join(
                    f"{n} x {why}"
                    for why, n in sorted(self.fallbacks.items(), key=lambda kv: -kv[1])
                )
            )
        for i, (pattern, (count, example)) in enumerate(group_failures(self.failures).items()):
            if i == 0:  # (not after the summary line alone: the lines above may be there)
                lines.append("failures by message:")
            single = count == self.failures.get(example)
            shown = example if single else f"{pattern}  (e.g. {example})"
            lines.append(f"  {count:6d} x {shown}")
        for i, (pattern, (count, example)) in enumerate(group_failures(self.broken).items()):
            if i == 0:
                lines.append("lines broken in statics (status 10, results kept):")
            single = count == self.broken.get(example)
            shown = example if single else f"{pattern}  (e.g. {example})"
            lines.append(f"  {count:6d} x {shown}")
        kinds = group_warnings(self.warnings, self.warned_cases)
        if kinds:
            lines.append("warnings by kind (the cases keep status 0):")
        for kind, (count, examples) in kinds.items():
            lines.append(f"  {count:6d} x {kind}, e.g.:")
            lines.extend(f"           {example}" for example in examples)
        return "\n".join(lines)


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def group_failures(failures: dict[str, int]) -> dict[str, tuple[int, str]]:
    """Failure messages grouped with their numbers masked as '#': pattern -> (count, first
    example), most frequent first."""
    groups: dict[str, tuple[int, str]] = {}
    for msg, count in failures.items():
        pattern = _NUMBER.sub("#", msg)
        n, example = groups.get(pattern, (0, msg))
        groups[pattern] = (n + count, example)
    return dict(sorted(groups.items(), key=lambda kv: -kv[1][0]))


#: example warnings shown per kind at the end of a run
WARNING_EXAMPLES = 3


def group_warnings(
    warnings: dict[str, int], cases: dict[str, str] | None = None
) -> dict[str, tuple[int, list[str]]]:
    """Case warnings (each a case's ``warning`` text with its count) split into single
    warnings and grouped by kind (the text before the first colon): kind -> (count, up to
    :data:`WARNING_EXAMPLES` distinct examples, each after its case's coordinates where
    ``cases`` gives them), most frequent first."""
    from ..analyses.plausibility import SEPARATOR

    cases = cases or {}
    groups: dict[str, tuple[int, list[str]]] = {}
    for text, count in warnings.items():
        for one in text.split(SEPARATOR):
            kind = one.split(":", 1)[0]
            n, examples = groups.get(kind, (0, []))
            shown = f"{cases[text]}: {one}" if cases.get(text) else one
            if len(examples) < WARNING_EXAMPLES and shown not in examples:
                examples = [*examples, shown]
            groups[kind] = (n + count, examples)
    return dict(sorted(groups.items(), key=lambda kv: -kv[1][0]))


class Progress:
    """A tqdm progress bar of finished cases on standard error: only on a terminal (or
    when ``enabled``), and only once the study has run for ``delay`` seconds, so quick
    studies and logs stay clean."""

    def __init__(self, total: int, *, enabled: bool | None = None, delay: float = 2.0) -> None:
        self.total = total
        self.done = 0
        self.enabled = sys.stderr.isatty() if enabled is None else enabled
        self._bar = None
        if self.enabled:
            from tqdm import tqdm

            self._bar = tqdm(
                total=total,
                file=sys.stderr,
                delay=delay,
                ascii=" #",
                unit="case",
                dynamic_ncols=True,
                bar_format="[{bar:30}] {n_fmt}/{total_fmt} cases, {elapsed}, eta {remaining} ",
            )

    def update(self, n: int) -> None:
        self.done += n
        if self._bar is not None:
            self._bar.update(n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
