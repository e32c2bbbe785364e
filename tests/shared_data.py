"""Where the shared test data lives (``../shared`` beside the repo), and a skip marker for it."""
from __future__ import annotations

from pathlib import Path

import pytest

SHARED = Path(__file__).resolve().parents[1].parent / "shared"
CMU_DIR = SHARED / "mocap" / "cmu"
CMU_FILES = sorted(CMU_DIR.glob("*.bvh")) if CMU_DIR.is_dir() else []

#: Where a skip sends a reader who wants these tests to run.
HOW_TO_GET = "README.md: Real capture for the tests"
requires_cmu = pytest.mark.skipif(not CMU_FILES, reason=f"shared CMU mocap not found at {CMU_DIR} ({HOW_TO_GET})")
#: CMU everyday actions in cgspeed's Daz-friendly BVH (drinking, climbing, sitting, ...).
EVERYDAY_DIR = SHARED / "mocap" / "cmu_everyday"
requires_everyday = pytest.mark.skipif(not (EVERYDAY_DIR / "13_09.bvh").exists(),
                                       reason=f"shared everyday capture not found at {EVERYDAY_DIR} ({HOW_TO_GET})")


def cmu(name: str) -> Path:
    """Path of one CMU file by its stem (``02_01_walk``); skips the test when the data is absent."""
    path = CMU_DIR / f"{name}.bvh"
    if not path.exists():
        pytest.skip(f"shared CMU file {path} not found ({HOW_TO_GET})")
    return path


def library_motion(name: str, fps: float = 30.0):
    """A clip of the built-in motion library by name (``walk``, ``kick``): real motion that needs no shared data.

    Building the library takes a few seconds once per process (it is cached, and the
    ``library_db`` fixture builds it too).
    """
    from text2anim.motiondb.library import builtin_clips

    for record in builtin_clips(fps):
        if record.name == name:
            return record.motion
    raise KeyError(f"no built-in clip named {name!r}")
