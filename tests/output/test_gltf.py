"""The GLB export, parsed back by hand: layout, skin, and forward kinematics of the animation.

The motions are clips of the built-in library (no shared data needed). When Node.js and the
npm packages ``three`` and ``gltf-validator`` are found (in ``tests/browser/node_modules``, pinned by
``tests/browser/package.json`` and its lock file: ``npm ci --prefix tests/browser``, which ``.ci/run``
does; ``$T2A_NODE_MODULES`` names another folder) the file is also loaded by three.js' GLTFLoader
and checked by the Khronos validator; otherwise those tests skip, saying why.
"""
from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from shared_data import library_motion
from text2anim.core import Motion, Skeleton
from text2anim.core.atomic import OutputError
from text2anim.output.gltf import glb_bytes, write_glb
from text2anim.output.viewer import Track

NODE_MODULES = Path(os.environ.get("T2A_NODE_MODULES", Path(__file__).parents[1] / "browser" / "node_modules"))
CHECK_SCRIPT = Path(__file__).parents[1] / "browser" / "gltf_check.mjs"

_DTYPES = {5126: "<f4", 5121: "u1", 5123: "<u2", 5125: "<u4"}
_N = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}


class Glb:
    """A parsed .glb, its layout checked on the way."""

    def __init__(self, data: bytes):
        magic, version, length = struct.unpack_from("<4sII", data, 0)
        assert magic == b"glTF" and version == 2 and length == len(data)
        jlen, jtype = struct.unpack_from("<I4s", data, 12)
        assert jtype == b"JSON" and jlen % 4 == 0
        jbytes = data[20:20 + jlen]
        text = jbytes.decode("utf-8")
        assert text == text.rstrip(" ") + " " * (len(text) - len(text.rstrip(" ")))  # padded with spaces only
        self.json = json.loads(text)
        blen, btype = struct.unpack_from("<I4s", data, 20 + jlen)
        assert btype == b"BIN\0" and blen % 4 == 0
        self.bin = data[28 + jlen:28 + jlen + blen]
        assert 28 + jlen + blen == len(data)
        assert self.json["buffers"] == [{"byteLength": blen}]
        assert self.json["asset"]["version"] == "2.0"

    def read(self, index: int) -> np.ndarray:
        acc = self.json["accessors"][index]
        view = self.json["bufferViews"][acc["bufferView"]]
        dt = np.dtype(_DTYPES[acc["componentType"]])
        start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        assert start % 4 == 0 and view["byteOffset"] % 4 == 0
        n = _N[acc["type"]]
        assert "byteStride" not in view
        assert acc["count"] * n * dt.itemsize <= view["byteLength"]
        assert view["byteOffset"] + view["byteLength"] <= len(self.bin)
        arr = np.frombuffer(self.bin, dt, acc["count"] * n, start).reshape(acc["count"], n)
        if "min" in acc:
            np.testing.assert_array_equal(arr.min(axis=0), np.array(acc["min"], dtype=dt))
            np.testing.assert_array_equal(arr.max(axis=0), np.array(acc["max"], dtype=dt))
        return arr


def _quat_mul(a, b):
    return (Rotation.from_quat(a) * Rotation.from_quat(b)).as_quat()


def _fk(g: Glb, skin: dict, frame: int) -> np.ndarray:
    """World positions of a skin's joints at a key frame, from the node tree and the animation."""
    nodes = g.json["nodes"]
    anim = g.json["animations"][0]
    local = {}
    for ch in anim["channels"]:
        node = ch["target"]["node"]
        if node in skin["joints"]:
            out = g.read(anim["samplers"][ch["sampler"]]["output"])
            local.setdefault(node, {})[ch["target"]["path"]] = out[frame].astype(np.float64)
    parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    world = {}

    def solve(i):
        if i in world:
            return world[i]
        t = local.get(i, {}).get("translation", np.array(nodes[i].get("translation", [0.0, 0.0, 0.0])))
        r = local.get(i, {}).get("rotation", np.array(nodes[i].get("rotation", [0.0, 0.0, 0.0, 1.0])))
        if i in parent:
            pp, pr = solve(parent[i])
            world[i] = (pp + Rotation.from_quat(pr).apply(t), _quat_mul(pr, r))
        else:
            world[i] = (t, r)
        return world[i]

    return np.array([solve(j)[0] for j in skin["joints"]])


@pytest.fixture(scope="module")
def walk():
    return library_motion("walk")


@pytest.fixture(scope="module")
def kick():
    return library_motion("kick")


def _random_chain(T=12, translations=False):
    skel = Skeleton(["root", "a", "b", "c"], [-1, 0, 1, 1], [[0, 0, 0], [0, 0.4, 0], [0.1, 0.3, 0], [-0.1, 0.3, 0.05]],
                    end_sites=[(2, [0, 0.1, 0])])
    rng = np.random.default_rng(3)
    rot = Rotation.random(T * 4, random_state=4).as_quat().reshape(T, 4, 4)
    tr = rng.normal(scale=0.2, size=(T, 4, 3)) if translations else None
    return Motion(skel, 24, rng.normal(size=(T, 3)), rot, tr)


def test_layout_nodes_skin_and_channels(walk):
    g = Glb(glb_bytes([Track("太郎", walk)]))
    J = walk.skeleton.n_joints
    gl = g.json
    (skin,) = gl["skins"]
    assert len(skin["joints"]) == J
    assert [gl["nodes"][j]["name"] for j in skin["joints"]] == list(walk.skeleton.names)
    assert len(gl["nodes"]) == J + 2  # joints, the actor's group node, the mesh node
    assert g.read(skin["inverseBindMatrices"]).shape == (J, 16)
    (anim,) = gl["animations"]
    assert len(anim["channels"]) == J + 1  # every joint's rotation, the root's translation
    paths = sorted((c["target"]["node"], c["target"]["path"]) for c in anim["channels"])
    assert paths.count((skin["joints"][0], "translation")) == 1
    assert all(s["interpolation"] == "LINEAR" for s in anim["samplers"])
    times = g.read(anim["samplers"][0]["input"])[:, 0]
    np.testing.assert_allclose(times, walk.times, atol=1e-6)
    # mesh: skinned to the joints, weights one, normals unit
    (mesh,) = gl["meshes"]
    prim = mesh["primitives"][0]
    pos = g.read(prim["attributes"]["POSITION"])
    assert g.read(prim["attributes"]["JOINTS_0"]).max() < J
    np.testing.assert_allclose(g.read(prim["attributes"]["WEIGHTS_0"]).sum(axis=1), 1)
    np.testing.assert_allclose(np.linalg.norm(g.read(prim["attributes"]["NORMAL"]), axis=1), 1, atol=1e-6)
    idx = g.read(prim["indices"])
    assert idx.max() < len(pos) and len(idx) % 3 == 0
    names = [n["name"] for n in gl["nodes"]]
    assert "太郎" in names
    for view in gl["bufferViews"]:
        assert view["byteOffset"] % 4 == 0


def test_bind_pose_and_inverse_bind_matrices_agree(walk):
    g = Glb(glb_bytes(walk))
    skin = g.json["skins"][0]
    ibm = g.read(skin["inverseBindMatrices"]).reshape(-1, 4, 4).transpose(0, 2, 1)  # column-major
    nodes = g.json["nodes"]
    # bind pose from the nodes' own translations (no rotations in the bind pose)
    bind = np.zeros((len(skin["joints"]), 3))
    for k, j in enumerate(skin["joints"]):
        assert "rotation" not in nodes[j] and "scale" not in nodes[j]
        t = np.array(nodes[j].get("translation", [0.0, 0.0, 0.0]))
        p = walk.skeleton.parents[k]
        bind[k] = t if p < 0 else bind[p] + t
    for k in range(len(bind)):
        world = np.eye(4)
        world[:3, 3] = bind[k]
        np.testing.assert_allclose(world @ ibm[k], np.eye(4), atol=1e-5)


@pytest.mark.parametrize("frames", [(0, 100, -1)])
def test_animation_reproduces_the_motion(walk, frames):
    g = Glb(glb_bytes([Track("a", walk)]))
    skin = g.json["skins"][0]
    for f in frames:
        f = f % walk.n_frames
        np.testing.assert_allclose(_fk(g, skin, f), walk.positions[f], atol=1e-3)
    # rotations are unit quaternions with continuous signs
    anim = g.json["animations"][0]
    for ch in anim["channels"]:
        if ch["target"]["path"] == "rotation":
            q = g.read(anim["samplers"][ch["sampler"]]["output"]).astype(np.float64)
            np.testing.assert_allclose(np.linalg.norm(q, axis=1), 1, atol=1e-6)
            assert np.all(np.sum(q[1:] * q[:-1], axis=1) >= 0)


def test_motion_with_local_translations():
    m = _random_chain(translations=True)
    g = Glb(glb_bytes(m))
    anim = g.json["animations"][0]
    assert len(anim["channels"]) == 2 * m.skeleton.n_joints
    for f in range(m.n_frames):
        np.testing.assert_allclose(_fk(g, g.json["skins"][0], f), m.positions[f], atol=1e-5)


def test_several_actors(walk, kick):
    k = kick.replace(root_positions=kick.root_positions + [2, 0, 0])
    g = Glb(glb_bytes([Track("太郎", walk), Track("花子", k)]))
    gl = g.json
    assert len(gl["skins"]) == 2 and len(gl["meshes"]) == 2 and len(gl["materials"]) == 2
    assert len(gl["animations"]) == 1
    J1, J2 = walk.skeleton.n_joints, kick.skeleton.n_joints
    assert len(gl["animations"][0]["channels"]) == J1 + 1 + J2 + 1
    for skin, m in zip(gl["skins"], (walk, k)):
        for f in (0, m.n_frames // 2, m.n_frames - 1):
            np.testing.assert_allclose(_fk(g, skin, f), m.positions[f], atol=1e-3)
    assert len(gl["scenes"][0]["nodes"]) == 4


def test_written_atomically(tmp_path, walk):
    out = tmp_path / "a.glb"
    write_glb([Track("a", walk)], out)
    assert out.read_bytes() == glb_bytes([Track("a", walk)])
    with pytest.raises(OutputError) as e:
        write_glb([Track("a", walk)], tmp_path / "nope" / "a.glb")
    assert e.value.user_facing
    assert [p.name for p in tmp_path.iterdir()] == ["a.glb"]


def test_non_finite_motion_is_refused():
    m = _random_chain()
    bad = m.replace(root_positions=np.where(np.arange(m.n_frames)[:, None] == 3, np.nan, m.root_positions))
    with pytest.raises(ValueError, match="non-finite"):
        glb_bytes(bad)


# ------------------------------------------------------------------- three.js, validator
def _node_check(path: Path, times: list[float], package: str) -> dict:
    if shutil.which("node") is None:
        pytest.skip("node not installed")
    if not (NODE_MODULES / package).is_dir():
        pytest.skip(f"npm package {package} not found in {NODE_MODULES} "
                    "(npm ci --prefix tests/browser, or set T2A_NODE_MODULES)")
    proc = subprocess.run(["node", str(CHECK_SCRIPT), str(NODE_MODULES), str(path), json.dumps(times)],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return json.loads(proc.stdout)


def test_khronos_validator_is_clean(tmp_path, walk, kick):
    path = tmp_path / "a.glb"
    write_glb([Track("太郎", walk), Track("花子", kick), Track("chain", _random_chain(translations=True))], path)
    report = _node_check(path, [0], "gltf-validator")["validator"]
    assert report["numErrors"] == 0 and report["numWarnings"] == 0, report["messages"]


def test_threejs_loads_and_plays_it(tmp_path, walk):
    path = tmp_path / "a.glb"
    write_glb([Track("太郎", walk)], path)
    frames = [0, walk.n_frames // 2, walk.n_frames - 1]
    times = [f / walk.fps for f in frames]
    three = _node_check(path, times, "three")["three"]
    assert three["animations"] == 1
    assert three["duration"] == pytest.approx(walk.times[-1], abs=1e-4)
    (actor,) = three["actors"]
    assert actor["bones"] == list(walk.skeleton.names)
    g = Glb(path.read_bytes())
    prim = g.json["meshes"][0]["primitives"][0]
    v0 = g.read(prim["attributes"]["POSITION"])[0].astype(np.float64)
    j0 = int(g.read(prim["attributes"]["JOINTS_0"])[0, 0])
    bind = walk.skeleton.rest_positions() + walk.root_positions[0]
    for k, f in enumerate(frames):
        got = np.array(actor["frames"][k])
        np.testing.assert_allclose(got, walk.positions[f], atol=1e-3)
        # the skinned vertex follows its joint rigidly
        want = walk.positions[f, j0] + walk.pose.rotations[f, j0] @ (v0 - bind[j0])
        np.testing.assert_allclose(actor["vertex"][k], want, atol=1e-3)


def test_blender_imports_it(tmp_path, walk):
    """Needs a Python with Blender's ``bpy`` (``pip install bpy`` in a Python 3.11 venv) named by $T2A_BLENDER_PYTHON."""
    py = os.environ.get("T2A_BLENDER_PYTHON")
    if not py:
        pytest.skip("set T2A_BLENDER_PYTHON to a Python that has bpy to import the GLB into Blender")
    path = tmp_path / "a.glb"
    write_glb([Track("太郎", walk)], path)
    frames = [0, walk.n_frames // 2, walk.n_frames - 1]
    proc = subprocess.run([py, str(Path(__file__).parents[1] / "browser" / "blender_check.py"), str(path),
                           str(round(walk.fps)), json.dumps(frames)], capture_output=True, text=True, timeout=300)
    line = next((ln for ln in proc.stdout.splitlines() if ln.startswith("JSON")), None)
    assert proc.returncode == 0 and line, proc.stderr[-3000:]
    out = json.loads(line[4:])
    assert out["result"] == ["FINISHED"] and ["太郎", "ARMATURE"] in out["objects"]
    idx = [walk.skeleton.names.index(b) for b in out["bones"]]
    assert len(idx) == walk.skeleton.n_joints
    for f in frames:
        v = np.array(out["frames"][str(f)])
        y_up = np.c_[v[:, 0], v[:, 2], -v[:, 1]]  # Blender's importer turns glTF's +Y up into +Z up
        np.testing.assert_allclose(y_up, walk.positions[f][idx], atol=1e-3)


# ------------------------------------------------------------------------- props
def _prop_nodes(g: Glb) -> dict[str, int]:
    return {n["name"]: i for i, n in enumerate(g.json["nodes"]) if "prop" in n.get("extras", {})}


def _channels(g: Glb, node: int) -> dict[str, np.ndarray]:
    anim = g.json["animations"][0]
    return {c["target"]["path"]: g.read(anim["samplers"][c["sampler"]]["output"]).astype(np.float64)
            for c in anim["channels"] if c["target"]["node"] == node}


def test_props_are_nodes_named_as_written_moved_by_the_actors_animation(library_db):
    from scene_props import scene

    anim, (ball, chair) = scene(library_db)
    g = Glb(glb_bytes(anim.tracks(), props=[ball, chair]))
    gl = g.json
    nodes = _prop_nodes(g)
    assert list(nodes) == ["ボール", "椅子"]
    assert all(n in gl["scenes"][0]["nodes"] for n in nodes.values())  # at the top of the scene
    (anim_gl,) = gl["animations"]
    # the ball follows the hand: one key per frame, on the actors' clock
    ch = _channels(g, nodes["ボール"])
    np.testing.assert_allclose(ch["translation"], ball.positions, atol=1e-5)
    np.testing.assert_allclose(np.abs(np.sum(ch["rotation"] * ball.unit_rotations, axis=1)), 1, atol=1e-5)
    ball_sampler = next(c["sampler"] for c in anim_gl["channels"] if c["target"]["node"] == nodes["ボール"])
    np.testing.assert_allclose(g.read(anim_gl["samplers"][ball_sampler]["input"])[:, 0],
                               next(iter(anim.motions.values())).times, atol=1e-6)
    # the chair stands still: no channel, its node where it stands
    assert _channels(g, nodes["椅子"]) == {}
    node = gl["nodes"][nodes["椅子"]]
    np.testing.assert_allclose(node["translation"], chair.positions[0])
    assert node["extras"] == {"prop": "chair"}
    # each mesh is its shape at its size, in a material of its colour
    for prop in (ball, chair):
        n = gl["nodes"][nodes[prop.name]]
        prim = gl["meshes"][n["mesh"]]["primitives"][0]
        pos = g.read(prim["attributes"]["POSITION"])
        np.testing.assert_allclose(pos.max(axis=0) - pos.min(axis=0), prop.size, rtol=0.02)
        rgb = np.array([int(prop.color[i:i + 2], 16) for i in (1, 3, 5)]) / 255
        linear = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
        colour = gl["materials"][prim["material"]]["pbrMetallicRoughness"]["baseColorFactor"]
        np.testing.assert_allclose(colour[:3], linear, atol=1e-6)
    # the actors are as they were without props
    plain = Glb(glb_bytes(anim.tracks()))
    assert gl["nodes"][:len(plain.json["nodes"])] == plain.json["nodes"]
    assert gl["skins"] == plain.json["skins"]


def test_no_props_no_change(walk):
    assert glb_bytes([Track("a", walk)], props=[]) == glb_bytes([Track("a", walk)])


def test_props_pass_the_validator_and_threejs_moves_them(tmp_path, library_db):
    from scene_props import scene

    anim, (ball, chair) = scene(library_db)
    path = tmp_path / "scene.glb"
    write_glb(anim.tracks(), path, props=[ball, chair])
    frames = [0, ball.n_frames // 2, ball.n_frames - 1]
    out = _node_check(path, [f / ball.fps for f in frames], "gltf-validator")
    report = out["validator"]
    assert report["numErrors"] == 0 and report["numWarnings"] == 0, report["messages"]
    if out["three"] is None:
        pytest.skip(f"npm package three not found in {NODE_MODULES}")
    props = {p["name"]: p for p in out["three"]["props"]}
    assert sorted(props) == ["ボール", "椅子"] and props["椅子"]["shape"] == "chair" and props["ボール"]["mesh"]
    for k, f in enumerate(frames):
        np.testing.assert_allclose(props["ボール"]["frames"][k], ball.positions[f], atol=1e-4)
        np.testing.assert_allclose(props["椅子"]["frames"][k], chair.positions[0], atol=1e-6)
    # a loader sees the ball in the hand it follows
    from text2anim.core.bodyparts import body_map

    name, motion = list(anim.motions.items())[-1]
    actor = next(a for a in out["three"]["actors"] if a["name"].startswith(name))  # "花子_mesh"
    hand = body_map(motion.skeleton).hands["right"]  # the skin's joints are the skeleton's, in its order
    for k in range(len(frames)):
        np.testing.assert_allclose(props["ボール"]["frames"][k], actor["frames"][k][hand], atol=1e-3)


def test_a_users_rig_file_gets_the_props_scaled_with_the_character(tmp_path, library_db):
    """With --rig CHARACTER.glb the props go into each actor's file, where the retargeted hand is: the retarget
    scales the travel by the legs' ratio about the origin, so the props are scaled by it too."""
    from rig_builders import mixamo_glb
    from scene_props import in_hand

    import text2anim
    from text2anim.core.bodyparts import body_map
    from text2anim.export import ExportOptions, export_props, glb_files

    anim = text2anim.animate("太郎は歩いて、手を振る。", db=library_db)
    (motion,) = anim.motions.values()
    ball = in_hand(motion)
    rig = mixamo_glb(tmp_path / "hero.glb", scale=1.3)
    opts = ExportOptions(rig=rig)
    (moved,) = anim.exported_motions(opts, units=False).values()
    (placed,) = export_props([ball], anim.motions, opts)
    hand = moved.positions[:, body_map(moved.skeleton).hands["right"]]
    assert placed.size[0] == pytest.approx(ball.size[0] * 1.3, rel=0.05)
    gap = np.linalg.norm(placed.positions - hand, axis=1)
    assert np.median(gap) < 0.05 and gap.max() < 0.15, (np.median(gap), gap.max())  # scaled, it stays in the hand
    data = glb_files({"太郎": moved}, opts, [placed])["太郎"]
    g = Glb(data)
    nodes = _prop_nodes(g)
    assert list(nodes) == ["ボール"]
    np.testing.assert_allclose(_channels(g, nodes["ボール"])["translation"], placed.positions, atol=1e-5)
    assert any(n.get("skin") is not None for n in g.json["nodes"])  # the user's character is still there
    path = tmp_path / "hero_anim.glb"
    path.write_bytes(data)
    report = _node_check(path, [0], "gltf-validator")["validator"]
    assert report["numErrors"] == 0 and report["numWarnings"] == 0, report["messages"]
    # in place or looped, the body leaves the frames the things move in: the GLB has the body alone
    assert export_props([ball], anim.motions, ExportOptions(in_place=True)) == []
    assert export_props([ball], anim.motions, ExportOptions(root_motion=True)) == [ball]


def test_a_text_that_names_things_writes_them_into_its_glb(tmp_path, library_db):
    """Through the API: the scene stage's things (a chair under the sitter, a book in the hand) in the GLB."""
    import text2anim

    anim = text2anim.animate("太郎は椅子に座って本を読む。", db=library_db)
    anim.save(glb=tmp_path / "a.glb")
    g = Glb((tmp_path / "a.glb").read_bytes())
    nodes = _prop_nodes(g)
    assert list(nodes) == [p.name for p in anim.props()] == ["椅子", "本"]
    assert _channels(g, nodes["椅子"]) == {}  # a chair stays put
    book = next(p for p in anim.props() if p.name == "本")
    np.testing.assert_allclose(_channels(g, nodes["本"])["translation"], book.positions, atol=1e-5)
    report = _node_check(tmp_path / "a.glb", [0], "gltf-validator")["validator"]
    assert report["numErrors"] == 0 and report["numWarnings"] == 0, report["messages"]
