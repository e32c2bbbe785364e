"""``text2anim db import-pack bandai-namco DIR``: a user's copy of the Bandai Namco Research Motion Dataset
imported with its styles mapped to ours (issue 40).

The dataset is never bundled: the files here are written by the test, in its naming
(``dataset-N_CONTENT_STYLE_NNN.bvh``) and its skeleton's joint names and centimetres (the built-in walk and
wave renamed, :mod:`skeleton_families`).
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

import text2anim
from text2anim.cli.main import main
from text2anim.motiondb import MotionDB
from text2anim.motiondb.errors import ClipValidationError
from text2anim.motiondb.style_pack import plan_pack
from text2anim.output.bvh_write import write_bvh
from shared_data import library_motion
from skeleton_families import FAMILIES, family_names


def _bandai_bvh(clip: str, path: Path) -> Path:
    """The built-in ``clip`` written as the dataset writes its files: its joint names, centimetres."""
    m = library_motion(clip)
    _, unit = FAMILIES["bandai"]
    s = m.skeleton
    skel = replace(s, names=family_names("bandai", s.names), offsets=s.offsets / unit,
                   end_sites=tuple((j, o / unit) for j, o in s.end_sites))
    write_bvh(m.replace(skeleton=skel, root_positions=m.root_positions / unit), path)
    return path


@pytest.fixture(scope="module")
def pack(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("bandai")
    (root / "data").mkdir()
    (root / "data" / "data").mkdir()
    for name, clip in (("dataset-1_walk_sad_001", "walk"), ("dataset-1_walk_normal_001", "walk"),
                       ("dataset-2_wave-right-hand_active_003", "wave_hand"),
                       ("dataset-1_walk_musical_001", "walk"), ("dataset-1_guide_happy_001", "walk")):
        folder = root / "data" / ("data" if name.startswith("dataset-2") else "")
        _bandai_bvh(clip, folder / f"{name}.bvh")
    (root / "data" / "motion.bvh").write_text("not the pack's naming")
    return root


def test_the_files_map_to_verbs_and_styles_and_the_rest_is_left_out_by_reason(pack):
    plan = plan_pack("bandai-namco", pack)
    got = {f.name: (f.verbs[0], f.cyclic, f.style) for f in plan.files}
    assert got == {"bn1_walk_sad_001": ("歩く", True, "sad"), "bn1_walk_normal_001": ("歩く", True, None),
                   "bn2_wave-right-hand_active_003": ("振る", False, "energetic")}
    why = {p.name: reason for p, reason in plan.left_out}
    assert why == {"dataset-1_walk_musical_001.bvh": "style musical is none of ours",
                   "dataset-1_guide_happy_001.bvh": "content guide plays no verb of ours",
                   "motion.bvh": "not named dataset-N_CONTENT_STYLE_NNN.bvh"}


def test_import_pack_stores_the_styles_and_a_styled_text_plays_them(pack, tmp_path, capsys):
    url = f"sqlite:///{tmp_path / 'motions.sqlite'}"
    assert main(["db", "import-pack", "bandai-namco", str(pack), "--db", url]) == 0
    out, err = capsys.readouterr()
    assert "imported 3 clips of bandai-namco" in out and "energetic 1, neutral 1, sad 1" in out
    assert "CC BY-NC-ND 4.0" in err and "left out 1 file: style musical is none of ours" in err
    with MotionDB.open(url) as db:
        assert db.info("bn1_walk_sad_001").style == "sad" and db.info("bn1_walk_sad_001").character == "bandai-namco"
    (row,) = text2anim.plan("太郎はしょんぼり歩いた。", url).table.elements
    assert row.clip == "bn1_walk_sad_001" and row.manner is not None and row.manner.by == "clip"
    (plain,) = text2anim.plan("太郎は歩いた。", url).table.elements
    assert plain.clip != "bn1_walk_sad_001"


def test_a_folder_without_the_pack_is_refused_in_one_line(tmp_path, capsys):
    with pytest.raises(ClipValidationError, match="no file of the bandai-namco pack"):
        plan_pack("bandai-namco", tmp_path)
    assert main(["db", "import-pack", "bandai-namco", str(tmp_path / "nowhere"),
                 "--db", f"sqlite:///{tmp_path / 'm.sqlite'}"]) == 2
    err = capsys.readouterr().err
    assert "no such folder" in err and "Traceback" not in err
