"""Dynamics about the static shape: modal analysis (:mod:`.modal`), with Irvine's
linear theory of shallow cables as its reference (:mod:`.irvine`)."""
