"""The study: the study file's models (pydantic v2: strict, frozen, SI units) and its
hardened YAML loader, then its cases: the sweep expansion and case hashes
(:mod:`.cases`), the case grid validated once per swept value (:mod:`.grid`,
:mod:`.grid_studies`), and a validated study as the solvers' plain inputs
(:mod:`.problem`). The models are importable from here."""

from .analysis import Analysis, ModalSettings, StaticSettings
from .ends import End, Ends, FixedEnd, ForceEnd, MooringEnd
from .environment import CurrentPoint, CustomFluid, Environment, Seabed
from .line import Attachment, Line, Segment
from .loader import StudyError, StudySource, load_study, parse_study_text, read_study_source
from .study import Study

__all__ = [
    "Analysis",
    "Attachment",
    "CurrentPoint",
    "CustomFluid",
    "End",
    "Ends",
    "Environment",
    "FixedEnd",
    "ForceEnd",
    "Line",
    "ModalSettings",
    "MooringEnd",
    "Seabed",
    "Segment",
    "StaticSettings",
    "Study",
    "StudyError",
    "StudySource",
    "load_study",
    "parse_study_text",
    "read_study_source",
]
