"""A user's glTF character stands on its mesh's soles (issue 46): a Mixamo foot, whose toe joint sits at the
ball 40° below the ankle's forward (the built-in body's: 23°), stood 16-20° heel-down with its heel 2-3 cm in
the floor when the retarget turned its toe bone as the built-in body's.

The rig is made in code (:func:`rig_builders.mixamo_feet_glb`: flat shoes on y = 0 in the rest pose); the
output BVH is read back and the shoes' vertices, read from the GLB and skinned by the output's own foot and
toe rotations, are measured on the frames the contact detector calls planted.
"""
from __future__ import annotations

import numpy as np
import pytest

from cli_run import text2anim
from rig_builders import mixamo_feet_glb, mixamo_glb
from text2anim.core import read_bvh
from text2anim.core.contacts import detect_contacts
from text2anim.core.gltf_mesh import bind_vertices
from text2anim.core.gltf_rig import read_gltf_rig
from text2anim.core.rigs import rig_roles
from text2anim.core.soles import sole_lines


def _shoes(rig, motion, ankle: int) -> tuple[np.ndarray, np.ndarray]:
    """``(T, V)`` heights of a foot's vertices (each carried by the joint it weighs most on) and ``(T,)`` the
    pitch (degrees, + toe up) of its sole line, as ``motion`` moves that foot."""
    below = [int(j) for j in rig.skeleton.subtree(ankle)]
    bound = bind_vertices(rig.gl, rig.bin, rig.node_world, np.array([rig.nodes[j] for j in below]))
    joint_of = {rig.nodes[j]: j for j in below}
    carrier = np.array([joint_of[int(n[np.argmax(w)])] for n, w in zip(bound.nodes, bound.weights)])
    rest = rig.node_world[list(rig.nodes), :3, 3]
    rot, pos = motion.pose.rotations, motion.positions
    y = np.einsum("tvb,vb->tv", rot[:, carrier, 1], bound.positions - rest[carrier]) + pos[:, carrier, 1]
    _, roles = rig_roles(rig.skeleton)
    side = "left" if ankle == roles["leftFoot"] else "right"
    line = sole_lines(rig, {side: (ankle, roles[f"{side}Toes"])})[side].line
    d = np.einsum("tab,b->ta", rot[:, ankle], line)
    return y, np.degrees(np.arctan2(d[:, 1], np.hypot(d[:, 0], d[:, 2])))


@pytest.mark.parametrize("text", ["太郎は歩く。", "太郎は走って、ボールを蹴る。そして喜ぶ。"])
def test_a_mixamo_foot_stands_flat_on_its_soles(tmp_path, text):
    glb = mixamo_feet_glb(tmp_path / "feet.glb")
    out = tmp_path / "out.bvh"
    done = text2anim(text, "--rig", glb, "-o", out)
    assert done.returncode == 0, done.stderr
    rig, motion = read_gltf_rig(glb), read_bvh(out)
    _, roles = rig_roles(rig.skeleton)
    contacts = detect_contacts(motion)
    for side in ("left", "right"):
        y, pitch = _shoes(rig, motion, roles[f"{side}Foot"])
        planted = contacts.of(side)
        assert planted.sum() > 20
        assert y.min() > -0.003, f"{side} shoe {100 * y.min():.1f} cm under the floor"  # 2.9-5.5 cm before
        assert np.median(y[planted].min(axis=1)) < 0.015  # on the floor where planted, not floating over it
        if text == "太郎は歩く。":  # a walk's planted feet lie flat (16-20° heel-down before)
            assert abs(np.median(pitch[planted])) < 5.0, np.median(pitch[planted])


def test_a_mesh_that_shows_no_sole_keeps_the_bone_alignment(tmp_path):
    """Boxes around the joints (the other test rigs' mesh) are no sole: their line follows the bone down."""
    rig = read_gltf_rig(mixamo_glb(tmp_path / "boxes.glb"))
    _, roles = rig_roles(rig.skeleton)
    assert sole_lines(rig, {"left": (roles["leftFoot"], roles["leftToes"])}) == {}
    flat = read_gltf_rig(mixamo_feet_glb(tmp_path / "feet.glb"))
    _, roles = rig_roles(flat.skeleton)
    sole = sole_lines(flat, {"left": (roles["leftFoot"], roles["leftToes"])})["left"]
    assert sole.line[1] == pytest.approx(0.0, abs=1e-6)  # flat shoes: a level line
    assert sole.toe_height == pytest.approx(0.024, abs=1e-4)  # the toe joint 2.4 cm over the sole
