"""Line-type library: segment properties of common mooring materials from their nominal
diameter, by published rules of thumb (pure: numbers in, numbers out, SI units).

Each material is one :class:`Material` in :data:`MATERIALS`; each of its coefficients
names its source (:attr:`Material.sources`). The nominal diameter ``d`` [m] is the bar
diameter of a chain link or the nominal diameter of a rope.

How the published coefficients become the segment's keys (``diameter``,
``drag_normal``, ``drag_tangential``, ``added_mass_*``):

- ``diameter`` is the volume-equivalent diameter ``D = r d`` (the solid cylinder with
  the displaced volume per length of the line): it sets buoyancy and added mass, and it
  is the diameter our drag coefficients refer to.
- The sources give the normal drag coefficient ``C_n`` on the nominal diameter ``d``
  (force per length 1/2 rho C_n d |u_n| u_n). Ours acts on ``D``
  (:mod:`cablestudy.physics.hydro`), so the same force needs ``drag_normal = C_n / r``.
- The chains' axial drag (OrcaFlex) acts on the area per length ``pi d_a`` with the
  axial drag diameter ``d_a = d / pi``: force 1/2 rho C_a d |u_t| u_t. Ours acts on
  ``pi D``, so ``drag_tangential = C_a / (pi r)``.
- The added-mass coefficients refer to the displaced volume in every source, as ours.

Sources (cited by key in :attr:`Material.sources`):

``orcaflex-chain``
    Orcina, OrcaFlex help, "Chain" (line type wizard), orcina.com/webhelp/OrcaFlex/
    Content/html/Chain.htm: studless / studlink OD 1.80 d / 1.89 d, mass 19.9 d^2 /
    21.9 d^2 te/m, EA 0.854e8 d^2 / 1.01e8 d^2 kN (d in m), normal drag 2.4 / 2.6 on d,
    axial drag 1.15 / 1.4 on d / pi, added mass 1.0 normal and 0.5 axial.
``dnv-os-e302``
    DNV-OS-E302 "Offshore mooring chain" (IACS W22) minimum breaking load of grades R3,
    R3S and R4: MBL = c d^2 (44 - 0.08 d) kN with d in mm and c = 0.0223, 0.0249,
    0.0274 (the same for studless and studlink chain).
``orcaflex-wire``
    OrcaFlex line type wizard, six-strand wire rope with an independent wire-rope core,
    as tabulated in NREL's getLineProps 'Orcaflex-original' (WISDEM MoorProps): OD 0.80
    d, mass 3.9897 d^2 te/m, EA 4.04e7 d^2 kN, MBL 633358 d^2 kN (d in m).
``moorpy-library``
    NREL MoorPy, moorpy/library/MoorProps_default.yaml: the 'wire' entry (mass 5293 d^2
    kg/m, D 1.18 d, EA 97.1e9 d^2 N, MBL 1022e6 d^2 N; sheathed: its steel modulus on
    the steel area, 97.1e9 / (5293 / 7850) = 144 GPa, is that of a spiral strand, where
    a six-strand rope has about 80 GPa) and added mass from Bureau Veritas NR 493 (fibre
    ropes 1.1 normal, 0.15 axial).
``moorpy-default``
    NREL MoorPy, moorpy/MoorProps_default.yaml: fibre ropes' mass, MBL and quasi-static
    EA / MBL (polyester 678.75 d^2 kg/m, 308.2e6 d^2 N, 14; nylon 585.15 d^2,
    207.0e6 d^2 + 230.29e6 d^3 N, 5; HMPE 495.72 d^2, 579.5e6 d^2 + 650.65e6 d^3 N,
    56.54) and material densities (1380, 1140, 975 kg/m^3) giving D.
``dnv-os-e301``
    DNV-OS-E301 "Position mooring", drag coefficients on the nominal diameter: wire
    rope 1.2, fibre rope 1.6 (MoorPy's library lists them divided by its D / d: 1.021
    for its wire, 2.021 / 1.979 / 1.988 for polyester / nylon / HMPE).
``dnv-rp-c205``
    DNV-RP-C205 "Environmental conditions and environmental loads", added mass of a
    circular cylinder in cross flow: 1.0 (wire ropes).

Where no source gives a coefficient (the tangential drag of wire and fibre ropes, the
tangential added mass of wire ropes) the library fills nothing: the segment's own value
or its default applies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

#: chain grades and their MBL factor c [kN/mm^2] of MBL = c d^2 (44 - 0.08 d) (dnv-os-e302)
CHAIN_GRADES: dict[str, float] = {"R3": 0.0223, "R3S": 0.0249, "R4": 0.0274}
#: the grade used when a chain's line_type names none
DEFAULT_CHAIN_GRADE = "R3"
#: the chain MBL formula peaks at d = 2 * 44 / (3 * 0.08) mm and falls beyond it
CHAIN_MAX_DIAMETER = 2.0 * 44.0 / (3.0 * 0.08) / 1000.0


@dataclass(frozen=True)
class Material:
    """One material of the library (SI units; ``d`` the nominal diameter [m]).

    Attributes
    ----------
    description : str
    diameter_ratio : float  [-]
        Volume-equivalent diameter over nominal diameter ``r``.
    mass_d2 : float  [kg/m^3]
        Mass per length over d^2.
    stiffness_d2 : float  [N/m^2]
        EA over d^2 (0: EA from ``stiffness_per_mbl``).
    stiffness_per_mbl : float  [-]
        EA over MBL (fibre ropes; 0: EA from ``stiffness_d2``).
    mbl_d2, mbl_d3 : float  [N/m^2], [N/m^3]
        MBL = mbl_d2 d^2 + mbl_d3 d^3 (chains: from the grade instead).
    drag_normal_nominal : float  [-]
        Normal drag coefficient on the nominal diameter.
    drag_axial_nominal : float | None  [-]
        Axial drag coefficient on the area per length d (None: not published).
    added_mass_normal, added_mass_tangential : float | None  [-]
    chain : bool
        MBL by chain grade (``dnv-os-e302``).
    sources : dict
        Property -> source key (module docstring).
    """

    description: str
    diameter_ratio: float
    mass_d2: float
    stiffness_d2: float = 0.0
    stiffness_per_mbl: float = 0.0
    mbl_d2: float = 0.0
    mbl_d3: float = 0.0
    drag_normal_nominal: float = 0.0
    drag_axial_nominal: float | None = None
    added_mass_normal: float | None = None
    added_mass_tangential: float | None = None
    chain: bool = False
    sources: dict[str, str] = field(default_factory=dict)


def _fibre_ratio(mass_d2: float, density: float) -> float:
    """D / d of a rope of mass ``mass_d2`` d^2 [kg/m] and material density [kg/m^3]."""
    return math.sqrt(4.0 * mass_d2 / (math.pi * density))


_CHAIN_SOURCES = {
    "diameter": "orcaflex-chain",
    "mass_per_length": "orcaflex-chain",
    "axial_stiffness": "orcaflex-chain",
    "minimum_breaking_load": "dnv-os-e302",
    "drag_normal": "orcaflex-chain",
    "drag_tangential": "orcaflex-chain",
    "added_mass_normal": "orcaflex-chain",
    "added_mass_tangential": "orcaflex-chain",
}
_FIBRE_SOURCES = {
    "diameter": "moorpy-default",
    "mass_per_length": "moorpy-default",
    "axial_stiffness": "moorpy-default",
    "minimum_breaking_load": "moorpy-default",
    "drag_normal": "dnv-os-e301",
    "added_mass_normal": "moorpy-library",
    "added_mass_tangential": "moorpy-library",
}

#: the library: material name -> :class:`Material`
MATERIALS: dict[str, Material] = {
    "chain_studless": Material(
        "studless chain (grade R3, R3S or R4)",
        diameter_ratio=1.80,
        mass_d2=19.9e3,
        stiffness_d2=0.854e11,
        drag_normal_nominal=2.4,
        drag_axial_nominal=1.15,
        added_mass_normal=1.0,
        added_mass_tangential=0.5,
        chain=True,
        sources=_CHAIN_SOURCES,
    ),
    "chain_studlink": Material(
        "studlink chain (grade R3, R3S or R4)",
        diameter_ratio=1.89,
        mass_d2=21.9e3,
        stiffness_d2=1.01e11,
        drag_normal_nominal=2.6,
        drag_axial_nominal=1.4,
        added_mass_normal=1.0,
        added_mass_tangential=0.5,
        chain=True,
        sources=_CHAIN_SOURCES,
    ),
    "wire_six_strand": Material(
        "six-strand wire rope, independent wire-rope core",
        diameter_ratio=0.80,
        mass_d2=3.9897e3,
        stiffness_d2=4.04e10,
        mbl_d2=633358e3,
        drag_normal_nominal=1.2,
        added_mass_normal=1.0,
        sources={
            "diameter": "orcaflex-wire",
            "mass_per_length": "orcaflex-wire",
            "axial_stiffness": "orcaflex-wire",
            "minimum_breaking_load": "orcaflex-wire",
            "drag_normal": "dnv-os-e301",
            "added_mass_normal": "dnv-rp-c205",
        },
    ),
    "wire_spiral_strand": Material(
        "sheathed spiral-strand wire rope",
        diameter_ratio=1.18,
        mass_d2=5293.0,
        stiffness_d2=97.1e9,
        mbl_d2=1022e6,
        drag_normal_nominal=1.2,
        added_mass_normal=1.0,
        sources={
            "diameter": "moorpy-library",
            "mass_per_length": "moorpy-library",
            "axial_stiffness": "moorpy-library",
            "minimum_breaking_load": "moorpy-library",
            "drag_normal": "dnv-os-e301",
            "added_mass_normal": "dnv-rp-c205",
        },
    ),
    "polyester": Material(
        "polyester fibre rope (quasi-static stiffness)",
        diameter_ratio=_fibre_ratio(678.75, 1380.0),
        mass_d2=678.75,
        stiffness_per_mbl=14.0,
        mbl_d2=308.2e6,
        drag_normal_nominal=1.6,
        added_mass_normal=1.1,
        added_mass_tangential=0.15,
        sources=_FIBRE_SOURCES,
    ),
    "nylon": Material(
        "nylon fibre rope (quasi-static stiffness)",
        diameter_ratio=_fibre_ratio(585.15, 1140.0),
        mass_d2=585.15,
        stiffness_per_mbl=5.0,
        mbl_d2=207.0e6,
        mbl_d3=230.29e6,
        drag_normal_nominal=1.6,
        added_mass_normal=1.1,
        added_mass_tangential=0.15,
        sources=_FIBRE_SOURCES,
    ),
    "hmpe": Material(
        "high-modulus polyethylene fibre rope (quasi-static stiffness)",
        diameter_ratio=_fibre_ratio(495.72, 975.0),
        mass_d2=495.72,
        stiffness_per_mbl=56.54,
        mbl_d2=579.5e6,
        mbl_d3=650.65e6,
        drag_normal_nominal=1.6,
        added_mass_normal=1.1,
        added_mass_tangential=0.15,
        sources=_FIBRE_SOURCES,
    ),
}


def chain_mbl(nominal_diameter: float, grade: str) -> float:
    """Minimum breaking load [N] of a chain of bar diameter ``nominal_diameter`` [m] and
    ``grade`` (``dnv-os-e302``: c d^2 (44 - 0.08 d) kN with d in mm)."""
    d_mm = 1000.0 * nominal_diameter
    return CHAIN_GRADES[grade] * d_mm * d_mm * (44.0 - 0.08 * d_mm) * 1000.0


def line_type_properties(
    material: str, nominal_diameter: float, grade: str | None = None
) -> dict[str, float]:
    """The segment keys a line type fills, in SI units.

    Parameters
    ----------
    material : str
        A key of :data:`MATERIALS`.
    nominal_diameter : float  [m]
    grade : str, optional
        Chain grade (a key of :data:`CHAIN_GRADES`; default :data:`DEFAULT_CHAIN_GRADE`).

    Returns
    -------
    dict
        ``diameter`` [m], ``mass_per_length`` [kg/m], ``axial_stiffness`` [N],
        ``minimum_breaking_load`` [N], ``drag_normal`` [-] and, where published,
        ``drag_tangential``, ``added_mass_normal``, ``added_mass_tangential`` [-].
    """
    m = MATERIALS[material]
    d = float(nominal_diameter)
    if m.chain:
        mbl = chain_mbl(d, grade or DEFAULT_CHAIN_GRADE)
    else:
        mbl = m.mbl_d2 * d * d + m.mbl_d3 * d**3
    stiffness = m.stiffness_d2 * d * d if m.stiffness_d2 else m.stiffness_per_mbl * mbl
    out = {
        "diameter": m.diameter_ratio * d,
        "mass_per_length": m.mass_d2 * d * d,
        "axial_stiffness": stiffness,
        "minimum_breaking_load": mbl,
        "drag_normal": m.drag_normal_nominal / m.diameter_ratio,
    }
    if m.drag_axial_nominal is not None:
        out["drag_tangential"] = m.drag_axial_nominal / (math.pi * m.diameter_ratio)
    if m.added_mass_normal is not None:
        out["added_mass_normal"] = m.added_mass_normal
    if m.added_mass_tangential is not None:
        out["added_mass_tangential"] = m.added_mass_tangential
    return out


#: how each filled key is computed, for ``cablestudy line-types`` and the docs
FORMULAS: dict[str, str] = {
    "diameter": "r d (volume-equivalent)",
    "mass_per_length": "m2 d^2",
    "axial_stiffness": "k2 d^2, or (EA/MBL) MBL for fibre ropes",
    "minimum_breaking_load": "chains: c d^2 (44 - 0.08 d) kN, d in mm; others: b2 d^2 + b3 d^3",
    "drag_normal": "C_n / r (C_n on the nominal diameter)",
    "drag_tangential": "C_a / (pi r) (C_a on the area per length d)",
}
