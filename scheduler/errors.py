"""Errors of the scheduling stage."""


class ScheduleError(ValueError):
    """A text whose motions cannot be put on a time table."""

    user_facing = True
