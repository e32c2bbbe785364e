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


# ----------------------------------------------------------- edge cases of issue 9 (no CMU needed)
def _chain_file(n: int, *, nested: bool = True, frame_time: str = "0.0333333", row: str | None = None) -> str:
    """A BVH file with ``n`` joints, each the child of the last (``nested``) or all children of the root."""
    lines = ["HIERARCHY", "ROOT j0", "{", "OFFSET 0 0 0", "CHANNELS 6 Xposition Yposition Zposition "
             "Zrotation Xrotation Yrotation"]
    for k in range(1, n):
        lines += [f"JOINT j{k}", "{", "OFFSET 0 0.01 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
        if not nested:
            lines.append("}")
    lines += ["End Site", "{", "OFFSET 0 0.01 0", "}"]
    lines += ["}"] * (n if nested else 1)
    values = row if row is not None else " ".join(["0"] * (6 + 3 * (n - 1)))
    lines += ["MOTION", "Frames: 2", f"Frame Time: {frame_time}", values, values]
    return "\n".join(lines) + "\n"


def test_a_thousand_deep_hierarchy_reads_and_writes_back():
    from text2anim.output.bvh_write import format_bvh

    m = parse_bvh(_chain_file(1000), scale=1)
    assert m.skeleton.n_joints == 1000 and m.skeleton.parents[-1] == 998
    again = parse_bvh(format_bvh(m), scale=1)  # the writer needs no recursion
    assert again.skeleton.names == m.skeleton.names
    assert abs(again.positions[-1, -1, 1] - 9.99) < 1e-6


def test_huge_joint_counts_are_refused():
    from text2anim.core.bvh import MAX_JOINTS

    with pytest.raises(BVHError, match=f"more than {MAX_JOINTS} joints"):
        parse_bvh(_chain_file(MAX_JOINTS + 10_000, nested=False), scale=1)


@pytest.mark.parametrize("frame_time", ["1e-320", "4.9e-324", "1e-9", "1e300"])
def test_denormal_or_absurd_frame_time_is_refused(frame_time):
    with pytest.raises(BVHError, match="frame time .* is outside"):
        parse_bvh(_chain_file(3, frame_time=frame_time), scale=1)


@pytest.mark.parametrize("values, channel", [("0 0 0 1e308 0 0", "Zrotation value 1e\\+308"),
                                             ("0 1e300 0 0 0 0", "Yposition value 1e\\+300"),
                                             ("0 0 0 0 0 -5e6", "Yrotation value -5e\\+06")])
def test_absurd_channel_values_are_refused(values, channel):
    with pytest.raises(BVHError, match=f":14: {channel} is beyond"):
        parse_bvh(_chain_file(1, row=values), scale=1)


@pytest.mark.parametrize("offset", ["1e308", "-2e7"])
def test_absurd_offsets_are_refused(offset):
    text = _chain_file(2).replace("OFFSET 0 0.01 0", f"OFFSET 0 {offset} 0", 1)
    with pytest.raises(BVHError, match="OFFSET y is .* beyond"):
        parse_bvh(text, scale=1)


def test_channel_less_joints_cannot_ask_for_gigabytes():
    """2,000 joints without channels cost a few bytes of text each, but 32 bytes per frame in memory."""
    from text2anim.core.bvh import MAX_JOINT_FRAMES

    n = 2000
    frames = MAX_JOINT_FRAMES // n + 1
    text = ("HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xposition\n"
            + "".join(f"JOINT j{k}\n{{\nOFFSET 0 0.001 0\nCHANNELS 0\n" for k in range(n)) + "}\n" * (n + 1)
            + f"MOTION\nFrames: {frames}\nFrame Time: 0.01\n" + "0\n" * frames)
    with pytest.raises(BVHError, match="joint-frames; split the file"):
        parse_bvh(text, scale=1)
