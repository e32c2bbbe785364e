"""A human skeleton no name table knows is read by its shape (core.skeleton_shape): the limbs from the rest
pose, the same joints the names would give; what is not a human skeleton is refused, saying what is missing."""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cli_run import text2anim as run
from shared_data import CMU_FILES, EVERYDAY_DIR, cmu, requires_cmu, requires_everyday
from skeleton_families import FAMILIES, family_bvh
from text2anim.core import read_bvh
from text2anim.core.rigs import REQUIRED, RigError, rig_roles
from text2anim.core.skeleton import Skeleton
from text2anim.core.skeleton_shape import infer_roles
from text2anim.motiondb import ImportOptions, MotionDB
from text2anim.output.bvh_write import format_bvh


def _anonymous(skel: Skeleton) -> Skeleton:
    return replace(skel, names=tuple(f"bone_{j:02d}" for j in range(skel.n_joints)))


def _agrees_with_the_names(skel: Skeleton) -> None:
    _, by_name = rig_roles(skel)
    by_shape = infer_roles(skel)
    assert {r: by_shape.get(r) for r in REQUIRED} == {r: by_name[r] for r in REQUIRED}


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_the_shape_places_every_family_as_its_names_do(family, tmp_path):
    _agrees_with_the_names(read_bvh(family_bvh(family, tmp_path / f"{family}.bvh")).skeleton)


@requires_cmu
def test_the_shape_places_real_capture_as_its_names_do():
    _agrees_with_the_names(read_bvh(cmu("02_01_walk")).skeleton)


@requires_everyday
def test_the_shape_places_the_daz_friendly_take_as_its_names_do():
    """cgspeed's Daz-friendly skeleton: a buttock joint before each thigh, twist-free arms."""
    _agrees_with_the_names(read_bvh(EVERYDAY_DIR / "13_30.bvh").skeleton)


@requires_cmu
def test_a_take_with_names_no_table_knows_imports_like_the_named_one(tmp_path, library_db):
    """The CMU walk with every joint renamed bone_00.. imports without a --map file and plays as the named
    take does on the built-in character (retargeted by the roles its shape gives)."""
    named = read_bvh(cmu("02_01_walk"))  # all frames, as the named import below reads them
    anon = tmp_path / "anon_walk.bvh"
    anon.write_text(format_bvh(named.replace(skeleton=_anonymous(named.skeleton))))
    with MotionDB.open(library_db) as lib:
        walk = lib.load("walk")
    db_url = f"sqlite:///{tmp_path / 'mine.sqlite'}"
    with MotionDB.open(db_url, seed=lambda: []) as db:
        from text2anim.motiondb import ClipRecord

        db.add([ClipRecord("built_in_walk", walk, ("歩く",), cyclic=True)])  # the character to retarget onto
        opts = ImportOptions(("散歩する",), cyclic=True)
        (a,) = db.import_bvh([anon], opts)
        (b,) = db.import_bvh([cmu("02_01_walk")], opts)
        pa, pb = db.load(a.name).positions, db.load(b.name).positions
        assert (a.left_contacts, a.right_contacts) == (b.left_contacts, b.right_contacts)
    assert np.abs(pa - pb).max() < 0.005  # the same motion, within half a centimetre


def _bvh(tmp_path: Path, joints: list[tuple[str, int, tuple]]) -> Path:
    """A one-frame BVH of ``(name, parent, offset)`` joints (metres), the rest pose."""
    names, parents, offsets = zip(*joints)
    skel = Skeleton(list(names), list(parents), np.array(offsets, dtype=float),
                    end_sites=[(len(joints) - 1, [0.0, 0.1, 0.0])])
    from text2anim.core import Motion

    rot = np.zeros((2, len(joints), 4))
    rot[..., 3] = 1
    path = tmp_path / "thing.bvh"
    path.write_text(format_bvh(Motion(skel, 30.0, np.array([[0, 1.0, 0]] * 2, dtype=float), rot)))
    return path


def test_what_is_not_a_human_skeleton_is_refused_saying_what_is_missing(tmp_path):
    snake = _bvh(tmp_path, [(f"s{j}", j - 1, (0.0, 0.0, 0.2) if j else (0.0, 0.0, 0.0)) for j in range(8)])
    with pytest.raises(RigError, match="two legs"):
        infer_roles(read_bvh(snake, scale=1.0).skeleton)
    done = run("db", "import", snake, "--verb", "這う", "--db", tmp_path / "x.sqlite")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert "read by its shape" in done.stderr and "legs" in done.stderr
