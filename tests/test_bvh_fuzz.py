"""Fuzz-style tests: damaged real files never hang and never raise anything but BVHError."""
from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from shared_data import CMU_DIR, requires_cmu
from text2anim.core import BVHError, parse_bvh

SOURCE = CMU_DIR / "127_07_run.bvh"
TEXT = SOURCE.read_text() if SOURCE.exists() else ""
NASTY = ["", "{", "}", "ROOT", "JOINT", "End", "Site", "MOTION", "Frames:", "CHANNELS", "OFFSET",
         "nan", "inf", "-inf", "1e999", "7", "-1", "0.5.5", "Xrotation", "Qrotation", "\t", "\n", "\x00",
         "ジョイント", "HIERARCHY"]

FUZZ = settings(max_examples=120, deadline=2000, suppress_health_check=[HealthCheck.too_slow])


def _parse_or_bvherror(text: str):
    try:
        m = parse_bvh(text, scale=1)
    except BVHError:
        return None
    assert m.positions.shape[0] == m.n_frames
    return m


@requires_cmu
@FUZZ
@given(cut=st.integers(min_value=0, max_value=max(len(TEXT) - 1, 0)))
def test_truncated_file(cut):
    result = _parse_or_bvherror(TEXT[:cut])
    # A cut can only parse if it fell inside the file's last number or its trailing whitespace
    # (a number cut short is still a number: no reader can tell).
    if result is not None:
        assert TEXT[cut:].strip() == "" or not any(c.isspace() for c in TEXT[cut:].rstrip())


@requires_cmu
@FUZZ
@given(data=st.data())
def test_corrupted_token(data):
    tokens = TEXT.split(" ")
    k = data.draw(st.integers(min_value=0, max_value=len(tokens) - 1))
    tokens[k] = data.draw(st.sampled_from(NASTY) | st.text(max_size=6))
    _parse_or_bvherror(" ".join(tokens))


@requires_cmu
@FUZZ
@given(data=st.data())
def test_deleted_lines(data):
    lines = TEXT.split("\n")
    a = data.draw(st.integers(min_value=0, max_value=len(lines) - 1))
    b = data.draw(st.integers(min_value=a, max_value=min(len(lines), a + 5)))
    result = _parse_or_bvherror("\n".join(lines[:a] + lines[b:]))
    first_frame_line = next(i for i, ln in enumerate(lines) if ln.startswith("Frame Time")) + 1
    if result is not None and b > first_frame_line:  # losing a frame line must be noticed
        assert all(not ln.strip() for ln in lines[max(a, first_frame_line):b])


@pytest.mark.parametrize("text", ["", "   \n\n", "HIERARCHY", "MOTION\nFrames: 1\n", "{" * 10000, "ROOT " + "x" * 100000])
def test_degenerate_inputs(text):
    with pytest.raises(BVHError):
        parse_bvh(text)
