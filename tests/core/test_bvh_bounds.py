"""Every BVH within the 64 MB a file may have is bounded work (issue 41): an oversized token, line or run
of blank lines is refused in one short line that quotes a few dozen characters, cut before they are
escaped; a long chain's shape is read in one pass. The full-size files (63 MB tokens, 60 MB of newlines,
5,000,000 joint-frames) are in ``benchmarks/fuzz_bvh.py``; these are the same bounds at test size."""
from __future__ import annotations

import numpy as np
import pytest

from cli_run import assert_clean_error, text2anim
from text2anim.cli.terminal import message
from text2anim.core import BVHError, parse_bvh, read_bvh
from text2anim.core.bvh_text import MAX_CHARS_PER_VALUE, MAX_TOKEN
from text2anim.core.inputs import QUOTE_WIDTH
from text2anim.output.bvh_write import CHUNK_FRAMES, format_bvh, write_bvh

HEAD = ("HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n"
        "End Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\n")


def _error_line(proc) -> str:
    assert_clean_error(proc)
    lines = [ln for ln in proc.stderr.splitlines() if "error:" in ln]
    assert len(lines) == 1, proc.stderr
    return lines[0]


@pytest.mark.parametrize("char", ["\x1b", "a"])
def test_an_oversized_token_is_refused_quoting_a_few_dozen_characters(tmp_path, char):
    bvh = tmp_path / "token.bvh"
    bvh.write_bytes(char.encode() * 200_000)
    line = _error_line(text2anim("info", bvh))
    assert "a word of 200,000 characters" in line and f"over {MAX_TOKEN}" in line
    assert "\x1b" not in line
    assert len(line) < len(str(bvh)) + 4 * QUOTE_WIDTH + 120  # 40 characters quoted, each at most \x1b


def test_a_name_longer_than_the_token_bound_is_refused(tmp_path):
    words = " ".join(["ab"] * MAX_TOKEN)
    with pytest.raises(BVHError, match=f"joint name over {MAX_TOKEN}"):
        parse_bvh(HEAD.replace("ROOT Hips", f"ROOT {words}") + "Frames: 0\nFrame Time: 0.1\n")


def test_a_file_of_newlines_names_its_last_line(tmp_path):
    bvh = tmp_path / "newlines.bvh"
    bvh.write_bytes(b"\n" * 300_000)
    assert "newlines.bvh:300001: unexpected end of file, expected HIERARCHY" in _error_line(text2anim("info", bvh))


def test_a_frame_line_longer_than_its_channels_can_be_is_refused_short(tmp_path):
    long = "1 " * (3 * MAX_CHARS_PER_VALUE)
    with pytest.raises(BVHError) as err:
        parse_bvh(HEAD + f"Frames: 2\nFrame Time: 0.1\n0 0 0\n{long}\n")
    assert "a frame line of 384 characters, over 192 for 3 channels" in str(err.value)
    assert len(str(err.value)) < 200


def test_a_header_line_is_quoted_cut(tmp_path):
    with pytest.raises(BVHError) as err:
        parse_bvh(HEAD + "Frames: " + "9" * 10_000 + "\nFrame Time: 0.1\n")
    assert "(10,008 characters)" in str(err.value) and len(str(err.value)) < 150


def test_millions_of_extra_frame_lines_are_not_each_counted():
    with pytest.raises(BVHError, match="declares 1 frames but has more than 10001 frame lines"):
        parse_bvh(HEAD + "Frames: 1\nFrame Time: 0.1\n" + "0 0 0\n" * 50_000)
    with pytest.raises(BVHError, match="declares 1 frames but has 3 frame lines"):
        parse_bvh(HEAD + "Frames: 1\nFrame Time: 0.1\n0 0 0\n\n  \n0 0 0\n0 0 0\n")


def test_a_message_is_cut_before_it_is_escaped():
    text = "x: " + "\x1b" * 5_000_000
    shown = message(text)
    assert len(shown) < 1100 and "\x1b" not in shown and "\\x1b" in shown and "characters left out" in shown


def test_a_long_motion_is_written_in_chunks_as_one_text(tmp_path):
    frames = 2 * CHUNK_FRAMES + 7
    rows = "\n".join(f"{k * 0.001:.3f} {k % 7} 0" for k in range(frames))
    m = parse_bvh(HEAD + f"Frames: {frames}\nFrame Time: 0.01\n{rows}\n", scale=1)
    out = tmp_path / "long.bvh"
    write_bvh(m, out)
    assert out.read_text() == format_bvh(m)
    np.testing.assert_allclose(read_bvh(out, scale=1).root_positions, m.root_positions, atol=1e-6)


def test_a_long_chain_is_read_by_its_shape(tmp_path):
    """A 3,000-joint chain is not a human: the shape reader says so (it walked 3,000 subtrees: quadratic)."""
    n = 3000
    lines = ["HIERARCHY", "ROOT j0", "{", "OFFSET 0 0 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
    for k in range(1, n):
        lines += [f"JOINT j{k}", "{", "OFFSET 0 0.1 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
    lines += ["End Site", "{", "OFFSET 0 0.1 0", "}"] + ["}"] * n + ["MOTION", "Frames: 1", "Frame Time: 0.1",
                                                                    " ".join(["0"] * 3 * n)]
    bvh = tmp_path / "chain.bvh"
    bvh.write_text("\n".join(lines) + "\n")
    proc = text2anim("info", bvh)
    assert proc.returncode == 0, proc.stderr
    assert "no hips with two legs below them" in proc.stdout
