"""What reaches the terminal from a hostile file stays short and escaped: one bounded error line, a bounded tree."""
from __future__ import annotations

from cli_run import assert_clean_error, text2anim
from text2anim.cli.terminal import MESSAGE_WIDTH


def _chain_bvh(path, joints: int):
    """A valid BVH of one long chain whose joint names hold ESC (a non-human skeleton, 1 cm bones)."""
    lines = ["HIERARCHY", "ROOT Hips", "{", "OFFSET 0 0 0",
             "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"]
    for i in range(1, joints):
        lines += [f"JOINT J\x1b]0;x\x07{i}", "{", "OFFSET 0 0.01 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
    lines += ["End Site", "{", "OFFSET 0 0.01 0", "}"] + ["}"] * joints
    lines += ["MOTION", "Frames: 2", "Frame Time: 0.0333333"] + [" ".join(["0"] * (6 + 3 * (joints - 1)))] * 2
    path.write_text("\n".join(lines) + "\n")
    return path


def test_an_error_naming_thousands_of_joints_is_one_short_escaped_line(tmp_path):
    bvh = _chain_bvh(tmp_path / "chain.bvh", 3000)
    proc = text2anim("db", "import", bvh, "--verb", "歩く", "--db", f"sqlite:///{tmp_path / 'm.sqlite'}")
    assert_clean_error(proc, "cannot place these joints", "characters left out")
    error = [line for line in proc.stderr.splitlines() if "error:" in line]
    assert len(error) == 1 and len(error[0]) < MESSAGE_WIDTH + 100  # it named all 3,000 joints: 60 KB
    assert "\x1b" not in proc.stderr and "\x07" not in proc.stderr and "\\x1b" in proc.stderr


def test_info_draws_a_deep_chain_with_bounded_indentation(tmp_path):
    bvh = _chain_bvh(tmp_path / "chain.bvh", 3000)
    proc = text2anim("info", bvh)
    assert proc.returncode == 0, proc.stderr
    tree = [line for line in proc.stdout.splitlines() if "ch, ZXY" in line]
    assert len(tree) == 3000  # every joint listed
    assert max(len(line) for line in tree) < 120  # a 3,000-deep indentation was 6,000 spaces a line
    assert "(depth 2999)" in proc.stdout and "\x1b" not in proc.stdout
