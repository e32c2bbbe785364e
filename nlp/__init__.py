"""nlp stage: Japanese text -> motions and temporal constraints.

``analyze(text) -> Analysis`` is the entry point; see ``nlp.types`` for the
values it returns and ``docs/language.md`` for what they mean.
"""
from .analyze import MAX_CHARS, analyze
from .errors import NLPError
from .types import Analysis, Bunsetsu, Constraint, MotionSpec

__all__ = ["analyze", "Analysis", "Bunsetsu", "Constraint", "MotionSpec", "NLPError", "MAX_CHARS"]
