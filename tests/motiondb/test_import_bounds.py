"""An import is bounded by the clip's size: a take too long for one clip is refused before any work on it."""
from __future__ import annotations

from cli_run import assert_clean_error, text2anim
from text2anim.motiondb.bvh_import import MAX_CLIP_SAMPLES


def _long_take(path, joints: int, frames: int):
    lines = ["HIERARCHY", "ROOT Hips", "{", "OFFSET 0 0 0",
             "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation"]
    for i in range(1, joints):
        lines += [f"JOINT J{i}", "{", "OFFSET 0 1 0", "CHANNELS 3 Zrotation Xrotation Yrotation"]
    lines += ["End Site", "{", "OFFSET 0 1 0", "}"] + ["}"] * joints
    row = " ".join(["0"] * (6 + 3 * (joints - 1)))
    path.write_text("\n".join(lines + ["MOTION", f"Frames: {frames}", "Frame Time: 0.0083333"] + [row] * frames) + "\n")
    return path


def test_a_take_over_the_clip_limit_is_refused_and_nothing_is_imported(tmp_path):
    joints = 100
    take = _long_take(tmp_path / "long.bvh", joints, MAX_CLIP_SAMPLES // joints + 1)
    db = f"sqlite:///{tmp_path / 'm.sqlite'}"
    proc = text2anim("db", "import", take, "--verb", "歩く", "--db", db)
    assert_clean_error(proc, "too long for one clip", "nothing was imported")
    listed = text2anim("db", "list", "--db", db)
    assert "long" not in listed.stdout
