"""The batch's own error: settings it cannot run with."""


class BatchError(ValueError):
    """Bad batch settings (jobs, chunk size, a scheduler that cannot be reached, no Dask)."""

    user_facing = True
