"""Scheduling stage: the analysis of a text plus the database's clips → the motion time table.

Every rule that writes the table is here (:func:`schedule` runs them in order): the
timing of paper 003 (:mod:`.plan`), the clip of each motion and its variants
(:mod:`.picker`, :mod:`.variants`), posture continuity (:mod:`.postures`,
:mod:`.arrangement`), the stops and idles of the waits (:mod:`.fillers`) and the
repetitions as played (:mod:`.repeats`). What it reads of the database is said by
the protocols of :mod:`.clips`.
"""
from .clips import ClipMeta, ClipSource
from .errors import ScheduleError
from .plan import ClipFinder, plan, without
from .schedule import Schedule, schedule
from .table import format_table
from .types import ClipTiming, Element, TimeTable

__all__ = ["ClipFinder", "ClipMeta", "ClipSource", "ClipTiming", "Element", "Schedule", "ScheduleError", "TimeTable",
           "format_table", "plan", "schedule", "without"]
