"""The error of a skeleton whose humanoid roles cannot be placed (by name, by a joint map or by its shape)."""
from __future__ import annotations


class RigError(ValueError):
    """A skeleton whose humanoid roles cannot be placed; the message names the missing ones."""

    user_facing = True
