"""Study-file models (pydantic v2): strict, frozen, SI units."""

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
