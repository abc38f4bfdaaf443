"""Benchmarks: run time against error (``make bench``).

Each ``benchmarks/wp_*.py`` module in the repository defines ``run(quick) ->
WorkPrecision`` (or a list of them): for every method and setting, a median wall time
over repeats and an error against a reference computed in the same run. This module
writes one netCDF dataset and one log-log work-precision plot per benchmark under the
output folder, and
a summary table (``summary.md``) with median time, error and the ratio to the peer at
equal or better error.
"""

from __future__ import annotations

import importlib.util
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

REPO = Path(__file__).resolve().parents[1]


def median_time(fn: Callable[[], object], *, repeats: int = 7, min_time: float = 0.05) -> float:
    """Median over ``repeats`` of the mean wall time of ``fn`` [s]; each repeat runs
    ``fn`` enough times to last ``min_time`` (calibrated on a second call: the first may
    load compiled kernels, which would leave one call per repeat, timed to the clock's
    grain)."""
    fn()
    t0 = time.perf_counter()
    fn()
    once = max(time.perf_counter() - t0, 1e-7)
    inner = max(1, int(min_time / once))
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        samples.append((time.perf_counter() - t0) / inner)
    return float(np.median(samples))


@dataclass
class Curve:
    """One method's points: setting labels, median wall times [s], errors [-]."""

    method: str
    settings: list[str] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    errors: list[float] = field(default_factory=list)
    peer: bool = False

    def add(self, setting: str, seconds: float, error: float) -> None:
        self.settings.append(setting)
        self.times.append(seconds)
        self.errors.append(error)


@dataclass
class WorkPrecision:
    name: str
    title: str
    error_name: str
    time_name: str = "median wall time per case [s]"
    curves: list[Curve] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def curve(self, method: str, *, peer: bool = False) -> Curve:
        c = Curve(method, peer=peer)
        self.curves.append(c)
        return c

    def dataset(self) -> xr.Dataset:
        n = max((len(c.times) for c in self.curves), default=0)
        shape = (len(self.curves), n)
        t = np.full(shape, np.nan)
        e = np.full(shape, np.nan)
        lab = np.full(shape, "", dtype=object)
        for i, c in enumerate(self.curves):
            t[i, : len(c.times)] = c.times
            e[i, : len(c.errors)] = c.errors
            lab[i, : len(c.settings)] = c.settings
        return xr.Dataset(
            {
                "wall_time": (("method", "point"), t, {"units": "s", "long_name": self.time_name}),
                "error": (("method", "point"), e, {"units": "1", "long_name": self.error_name}),
                "setting": (("method", "point"), lab, {"long_name": "solver setting"}),
            },
            coords={"method": [c.method for c in self.curves], "point": np.arange(n)},
            attrs={"title": self.title, "notes": "\n".join(self.notes)},
        )

    def summary_rows(self) -> list[str]:
        """Per method: its most accurate point, and the time ratio to the peer at equal
        or better error; then, when a peer ran, one row comparing our cheapest point
        over all our methods at the peer's best error with that peer point."""
        rows = []
        ours = [(c, i) for c in self.curves if not c.peer for i in range(len(c.times))]
        theirs = [(c, i) for c in self.curves if c.peer for i in range(len(c.times))]
        peer = min(theirs, key=lambda ci: ci[0].errors[ci[1]]) if theirs else None
        pname = peer[0].method.split(" (")[0] if peer else ""

        def versus(points: list[tuple[Curve, int]]) -> tuple[str, tuple[Curve, int] | None]:
            if peer is None:
                return "", None
            p_err, p_time = peer[0].errors[peer[1]], peer[0].times[peer[1]]
            ok = [ci for ci in points if ci[0].errors[ci[1]] <= max(p_err, 1e-15)]
            if not ok:
                return f"never as accurate as {pname} ({p_err:.1e})", None
            mine = min(ok, key=lambda ci: ci[0].times[ci[1]])
            ratio = p_time / mine[0].times[mine[1]]
            return f"{pname} time / ours = {_fmt_ratio(ratio)} (at error <= {p_err:.1e})", mine

        for c in self.curves:
            if not c.times:
                continue
            best = int(np.nanargmin(c.errors))
            ratio = "" if c.peer else versus([(c, i) for i in range(len(c.times))])[0]
            rows.append(
                f"| {self.name} | {c.method} | {c.settings[best]} | "
                f"{_fmt_time(c.times[best])} | {c.errors[best]:.2e} | {ratio} |"
            )
        if peer is not None and ours:
            text, mine = versus(ours)
            if mine is not None:
                c, i = mine
                rows.append(
                    f"| {self.name} | **cablestudy at equal error** | {c.settings[i]} "
                    f"({c.method}) | {_fmt_time(c.times[i])} | {c.errors[i]:.2e} | "
                    f"**{text}** |"
                )
        return rows


def _fmt_ratio(r: float) -> str:
    return f"{r:.2g}" if r < 10 else f"{r:.0f}"


def _fmt_time(t: float) -> str:
    if not math.isfinite(t):
        return "n/a"
    if t < 1e-3:
        return f"{t * 1e6:.1f} us"
    if t < 1.0:
        return f"{t * 1e3:.2f} ms"
    return f"{t:.2f} s"


def _tick_time(t: float) -> str:
    """Short axis label of a time [s]: 20 us, 5 ms, 2 s."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6)):
        if t >= scale * 0.999:
            return f"{t / scale:.3g} {unit}"
    return f"{t / 1e-9:.3g} ns"


def plot(wp: WorkPrecision, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    fig, ax = plt.subplots(figsize=(8.2, 4.4))
    for c in wp.curves:
        t, e = np.asarray(c.times), np.maximum(np.asarray(c.errors), 1e-17)
        ax.loglog(t, e, "s--" if c.peer else "o-", label=c.method)
    # decades only when the times span more than two of them (labels would collide)
    times = [t for c in wp.curves for t in c.times if t > 0]
    span = max(times) / min(times) if times else 1.0
    subs = (1.0,) if span > 100.0 else (1.0, 2.0, 5.0)
    ax.xaxis.set_major_locator(LogLocator(base=10.0, subs=subs))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: _tick_time(v)))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel(wp.time_name)
    ax.set_ylabel(wp.error_name)
    ax.set_title(wp.title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _modules(directory: Path) -> list[Path]:
    return sorted(directory.glob("wp_*.py"))


README_START = "<!-- bench:start (written by make bench) -->"
README_END = "<!-- bench:end -->"


def update_readme(readme: Path, summary: str, plots: list[Path]) -> None:
    """Replace the text between the bench markers of ``readme`` with the summary table
    and links to the plots (paths relative to the README)."""
    text = readme.read_text()
    if README_START not in text or README_END not in text:
        return
    links = "\n".join(f"![{p.stem}]({p.relative_to(readme.parent).as_posix()})" for p in plots)
    block = f"{README_START}\n{summary}\n{links}\n{README_END}"
    head, rest = text.split(README_START, 1)
    tail = rest.split(README_END, 1)[1]
    readme.write_text(head + block + tail)


def run_benchmarks(
    out: Path,
    *,
    quick: bool = False,
    only: list[str] | None = None,
    readme: Path | None = None,
    docs: Path | None = None,
) -> str:
    """Run every work-precision benchmark; write datasets, plots and summary.md (and, if
    asked, copy the plots to ``docs`` and put the table into ``readme``)."""
    out.mkdir(parents=True, exist_ok=True)
    rows = [
        "| benchmark | method | setting | median time | error | ratio to peer |",
        "|---|---|---|---|---|---|",
    ]
    notes = []
    plots: list[Path] = []
    for path in _modules(REPO / "benchmarks"):
        if only and path.stem not in only:
            continue
        spec = importlib.util.spec_from_file_location(path.stem, path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        t0 = time.perf_counter()
        got = module.run(quick=quick)
        print(f"{path.stem}: {time.perf_counter() - t0:.0f} s", flush=True)
        for wp in got if isinstance(got, list) else [got]:
            wp.dataset().to_netcdf(out / f"{wp.name}.nc")
            plot(wp, out / f"{wp.name}.png")
            plots.append(out / f"{wp.name}.png")
            rows.extend(wp.summary_rows())
            notes.extend(f"- {wp.name}: {n}" for n in wp.notes)
    text = "\n".join(rows) + "\n"
    if notes:
        text += "\n" + "\n".join(notes) + "\n"
    (out / "summary.md").write_text(text)
    if readme is not None and docs is not None:
        import shutil

        docs.mkdir(parents=True, exist_ok=True)
        copied = []
        for p in plots:
            shutil.copy(p, docs / p.name)
            copied.append((docs / p.name).resolve())
        update_readme(readme.resolve(), text, copied)
    return text
