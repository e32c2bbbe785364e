"""Where the shared test data lives (``../shared`` beside the repo), and a skip marker for it."""
from __future__ import annotations

from pathlib import Path

import pytest

SHARED = Path(__file__).resolve().parents[1].parent / "shared"
CMU_DIR = SHARED / "mocap" / "cmu"
CMU_FILES = sorted(CMU_DIR.glob("*.bvh")) if CMU_DIR.is_dir() else []

requires_cmu = pytest.mark.skipif(not CMU_FILES, reason=f"shared CMU mocap not found at {CMU_DIR}")


def cmu(name: str) -> Path:
    """Path of one CMU file by its stem (``02_01_walk``); skips the test when the data is absent."""
    path = CMU_DIR / f"{name}.bvh"
    if not path.exists():
        pytest.skip(f"shared CMU file {path} not found")
    return path
