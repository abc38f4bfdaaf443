"""Statuses of the seabed-contact batch kernel (:func:`._fast_contact.contact_cases`, and
the same kernel compiled ahead of time, :mod:`.aot`): 0 converged and checked, else why
the case is left to the general solver. Kept apart from the kernel so that reading them
does not import numba."""

from __future__ import annotations

#: the Newton iteration did not converge
NOT_CONVERGED = 1
#: the touchdown point reaches the anchor: the line hangs free (the suspended solver's case)
LIFT_OFF = 2
#: the line is longer than the path along the seabed and up to B: slack on the seabed,
#: the laid shape is not determined
SLACK = 3
#: a singular Jacobian or non-finite values
NUMERICAL = 4
#: the solved line passes below the seabed (a contact this model does not describe)
BELOW_SEABED = 5
#: the touchdown point lies past a point load lifting the line (a buoy): the laid part
#: would hold it down, which the seabed cannot (set after the kernel, by its caller)
LIFTING_LOAD_LAID = 6
