"""Scheduling stage: the analysis of a text plus clip timing → the motion time table."""
from .errors import ScheduleError
from .plan import ClipFinder, plan, without
from .table import format_table
from .types import ClipTiming, Element, TimeTable

__all__ = ["ClipFinder", "ClipTiming", "Element", "ScheduleError", "TimeTable", "format_table", "plan", "without"]
