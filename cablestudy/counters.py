"""Work counters of this process (static solves, linear-model assemblies), so tests and
benchmarks can check that a sweep reuses what it may. Light: imports nothing heavy."""

from __future__ import annotations

from collections import Counter

#: counts by kind of work: ``static_solves``, ``linear_assemblies``
COUNTERS: Counter[str] = Counter()
