"""A character written out again drops the animations it replaces, with the accessors, buffer views and
bytes only they used: a file animated by text2anim and animated again is the same size, not bigger by
the first animation (a Mixamo X Bot with its own animation: 752 unused objects, 2.25 -> 2.47 MB)."""
from __future__ import annotations

import json
import struct

import numpy as np

from rig_builders import mixamo_glb, vrm_file
from text2anim.core.gltf_rig import read_glb
from text2anim.export import ExportOptions


def _counts(gl: dict) -> dict[str, int]:
    return {k: len(gl.get(k, [])) for k in ("accessors", "bufferViews", "animations", "meshes", "skins", "nodes")}


def test_animating_an_animated_character_again_keeps_its_size(walk, tmp_path):
    rig = mixamo_glb(tmp_path / "xbot.glb")
    gl_rig, bin_rig = read_glb(rig)
    first, = walk.save_glb(tmp_path / "first.glb", ExportOptions(rig=rig))  # a character with an animation
    again, = walk.save_glb(tmp_path / "again.glb", ExportOptions(rig=first))
    thrice, = walk.save_glb(tmp_path / "thrice.glb", ExportOptions(rig=again))
    gl1, bin1 = read_glb(first)
    gl2, bin2 = read_glb(again)
    assert _counts(gl2) == _counts(gl1) and _counts(gl1)["animations"] == 1
    assert len(bin2) == len(bin1) and again.stat().st_size == first.stat().st_size
    assert thrice.read_bytes() == again.read_bytes() == first.read_bytes()
    # what the character is made of is untouched: the same mesh and skin data as the original rig's
    for key in ("meshes", "skins", "materials", "scenes"):
        assert gl2.get(key) == gl_rig.get(key), key
    assert bin2[:len(bin_rig)] == bin_rig


def test_the_old_animations_data_goes_wherever_it_lies(walk, tmp_path):
    """An animation whose data lies before the mesh's in the file (exporters interleave them): dropped, and the
    mesh's and skin's accessors renumbered to the same data."""
    rig = vrm_file(tmp_path / "avatar.vrm")
    first, = walk.save_glb(tmp_path / "first.vrm", ExportOptions(rig=rig))
    gl, blob = read_glb(first)
    n_rig = len(read_glb(rig)[0]["accessors"])
    # move the animation's accessors (appended last) to the front, as another exporter might have written them
    order = list(range(n_rig, len(gl["accessors"]))) + list(range(n_rig))
    new = {old: i for i, old in enumerate(order)}
    gl["accessors"] = [gl["accessors"][i] for i in order]
    for a in gl["animations"]:
        for s in a["samplers"]:
            s["input"], s["output"] = new[s["input"]], new[s["output"]]
    for m in gl["meshes"]:
        for p in m["primitives"]:
            p["attributes"] = {k: new[v] for k, v in p["attributes"].items()}
            p["indices"] = new[p["indices"]]
            for t in p.get("targets", []):
                t.update({k: new[v] for k, v in t.items()})
    for s in gl["skins"]:
        s["inverseBindMatrices"] = new[s["inverseBindMatrices"]]
    shuffled = tmp_path / "shuffled.vrm"
    js = json.dumps(gl).encode()
    js += b" " * (-len(js) % 4)
    shuffled.write_bytes(struct.pack("<4sII", b"glTF", 2, 28 + len(js) + len(blob)) + struct.pack("<I4s", len(js), b"JSON")
                         + js + struct.pack("<I4s", len(blob), b"BIN\0") + blob)
    again, = walk.save_glb(tmp_path / "again.vrm", ExportOptions(rig=shuffled))
    gl2, bin2 = read_glb(again)
    assert _counts(gl2) == _counts(read_glb(first)[0])
    assert len(bin2) == len(blob)

    def data(g, b, i):
        v = g["bufferViews"][g["accessors"][i]["bufferView"]]
        return b[v.get("byteOffset", 0):v.get("byteOffset", 0) + v["byteLength"]]

    for m, m2 in zip(gl["meshes"], gl2["meshes"]):
        for p, p2 in zip(m["primitives"], m2["primitives"]):
            for k in p["attributes"]:
                assert data(gl, blob, p["attributes"][k]) == data(gl2, bin2, p2["attributes"][k]), k
    ibm = [np.frombuffer(data(g, b, s["inverseBindMatrices"]), "<f4") for g, b in ((gl, blob), (gl2, bin2))
           for s in g["skins"][:1]]
    assert np.array_equal(*ibm)
