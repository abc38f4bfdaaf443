"""Line and end builders shared by the statics tests (plain physics inputs, SI units)."""

from __future__ import annotations

import numpy as np

from cablestudy.statics import EndCondition, LineModel


def make_line(
    lengths,
    weights,
    stiffness,
    *,
    diameter=0.02,
    cn=1.2,
    ct=0.01,  # noqa: ANN001
    attachments=(),
) -> LineModel:  # noqa: ANN001
    n = len(lengths)

    def arr(v):  # noqa: ANN001, ANN202
        return np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy()

    return LineModel(
        length=arr(lengths),
        weight=arr(weights),
        mass=arr(weights) / 9.80665,
        axial_stiffness=arr(stiffness),
        diameter=arr(diameter),
        drag_normal=arr(cn),
        drag_tangential=arr(ct),
        added_mass_normal=arr(1.0),
        added_mass_tangential=arr(0.0),
        bending_stiffness=arr(0.0),
        damping_ratio=arr(0.0),
        attachment_s=np.array([a[0] for a in attachments], dtype=float),
        attachment_force=np.array([a[1] for a in attachments], dtype=float).reshape(-1, 3),
        attachment_mass=np.zeros(len(attachments)),
        attachment_volume=np.zeros(len(attachments)),
    )


def fixed(*p: float) -> EndCondition:
    return EndCondition(kind="fixed", position=np.array(p, dtype=float))
