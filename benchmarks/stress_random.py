"""Run a batch of random studies (tests/stress_studies.py) through the command line and
count the anomalies by kind.

    PYTHONPATH=$PWD python benchmarks/stress_random.py --start 0 --count 100 --out /tmp/stress

Each anomaly is printed with the study's seed; the study's YAML stays in
OUT/<seed>/stress-<seed>.yaml as its reproducer. Not a test (minutes of run time); the
fixed-seed sample is tests/integration/test_stress_random_studies.py.
"""

from __future__ import annotations

import argparse
import collections
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.stress_checks import check_run, check_swap, run_study, swapped
from tests.stress_studies import generate  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--start", type=int, default=0)
    ap.add_argument("--count", type=int, default=50)
    ap.add_argument("--out", type=Path, default=Path("/tmp/stress"))
    ap.add_argument("--slow", type=float, default=30.0, help="report runs longer than this [s]")
    ap.add_argument("--dynamic", action="store_true", help="one-line dynamic studies only")
    a = ap.parse_args(argv)
    kinds: collections.Counter[str] = collections.Counter()
    log = a.out / "anomalies.jsonl"
    a.out.mkdir(parents=True, exist_ok=True)
    cases = 0
    for seed in range(a.start, a.start + a.count):
        study, meta = generate(seed, dynamic=a.dynamic)
        res = run_study(study, a.out / str(seed))
        found = check_run(study, meta, res)
        twin = swapped(study) if seed % 3 == 0 else None
        if twin is not None:
            res2 = run_study(twin, a.out / str(seed))
            found += check_swap(res, res2, meta)
        if res.seconds > a.slow:
            found.append(("slow", f"{res.seconds:.1f} s"))
        ncase = 0
        if res.nc is not None:
            import xarray as xr

            with xr.open_dataset(res.nc) as ds:
                ncase = int(ds["status"].size)
        cases += ncase
        print(
            f"seed {seed}: {meta.kind} {meta.method} dyn={meta.dynamic} exit {res.code} "
            f"{res.seconds:.1f} s, {ncase} cases, {len(found)} anomalies",
            flush=True,
        )
        with log.open("a") as fh:
            for kind, text in found:
                kinds[kind] += 1
                print(f"   [{kind}] {text[:400]}", flush=True)
                fh.write(json.dumps({"seed": seed, "kind": kind, "text": text}) + "\n")
    print(f"{a.count} studies, {cases} cases; anomalies: {dict(kinds)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
