"""Fixtures the API's export tests share."""
from __future__ import annotations

import pytest

import text2anim
from text2anim.core.motion import Motion


@pytest.fixture(scope="session")
def walk(library_db):
    """太郎は歩く。 animated with the built-in library (the animation the rig and glTF exports are checked on)."""
    return text2anim.animate("太郎は歩く。", db=library_db)


@pytest.fixture(scope="session")
def walk_motion(walk) -> Motion:
    """The one actor's motion of :func:`walk`, as the engines made it."""
    (motion,) = walk.motions.values()
    return motion
