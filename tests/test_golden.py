"""Byte identity: the golden sentences animate to the same BVH bytes and report as recorded.

Guards refactors (moving modules must not change a single output byte). A change that is
meant to alter the animation regenerates ``tests/golden/outputs.json`` with
``python tests/golden/regen.py`` and says so in its commit message.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from golden.regen import ENGINES, SENTENCES, digests
from text2anim.motiondb import MotionDB

RECORDED = json.loads((Path(__file__).parent / "golden" / "outputs.json").read_text())


@pytest.fixture(scope="module")
def current(tmp_path_factory):
    url = f"sqlite:///{tmp_path_factory.mktemp('golden') / 'motions.sqlite'}"
    with MotionDB.open(url) as db:
        return digests(db)


@pytest.mark.parametrize("engine", ENGINES)
@pytest.mark.parametrize("text", SENTENCES)
def test_output_bytes_are_unchanged(current, engine, text):
    key = f"{engine}|{text}"
    assert current[key] == RECORDED[key], f"{key}: output changed (regenerate only if intended)"
