"""The analyses: a chunk of cases in, one record per case out.

:mod:`cablestudy.analyses.evaluate` is the one entry: it picks the analysis kinds a
case asks for from a small registry (static, modal, dynamic; a system of lines; the
quasi-static database) and runs them in order. One module per kind: :mod:`.static`
(with :mod:`.spring` and :mod:`.pulley` for those lines), :mod:`.modal`,
:mod:`.dynamic` (by method: :mod:`.time`, :mod:`.frequency`), :mod:`.system`,
:mod:`.database`. A static grid's chunk runs as arrays (:mod:`.static_grid`) or as
validated cases (:mod:`.static_grid_cases`). The variables they write are declared in
:mod:`.variables`. Nothing is imported here: a run loads only the kinds it needs.
"""
