"""Running a study: its cases (or its grid's rows) in chunks on a scheduler, the
per-study cache, progress and the summary, and the dataset written atomically.

:mod:`.runner` runs validated cases (:mod:`.scheduler` places the chunks, :mod:`.cache`
keeps finished ones, :mod:`.progress` reports); :mod:`.grid_runner` runs a grid of
cases as arrays. :mod:`.dataset` assembles the records into one dataset and
:mod:`.writer` writes it; :mod:`.outputs` checks and tidies where a run writes,
:mod:`.remote` reaches a dask scheduler given by address. Nothing here knows physics.
"""
