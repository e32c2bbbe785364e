"""The animation on the user's glTF/VRM character (``--rig CHARACTER.glb|.vrm``), and VRM Animation (``--vrma``).

Test rigs are made in code (:mod:`rig_builders`): a Mixamo character as Blender exports it (A-pose rest,
bone axes along the bones, an armature scaled by 0.01, a tiny skinned mesh) and VRM avatars built from the
built-in skeleton (VRM 1.0 and 0.x, VRoid-style joint names that only the humanoid extension explains).
The GLB written is read back here by forward kinematics of its own nodes and animation. When Node.js and
the npm packages of ``tests/browser`` are installed (``npm ci --prefix tests/browser``; ``.ci/run`` does)
the outputs also go through the Khronos validator and the VRMA is played on the avatars by
``@pixiv/three-vrm-animation``; otherwise those tests skip, saying why.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from cli_run import assert_clean_error, text2anim as run_cli
from limb_checks import limb_errors
from rig_builders import _a_pose, _mixamo_rows, _positions, _rest, _vroid, mixamo_glb, skinned_glb, vrm_file
from text2anim.core import read_bvh
from text2anim.core.glb import BufferBuilder, pack_glb
from text2anim.core.gltf_rig import read_glb, read_gltf_rig
from text2anim.core.metrics import skating_ratio
from text2anim.core.retarget import map_skeletons
from text2anim.core.rigs import REQUIRED, RigError
from text2anim.export import ExportError, ExportOptions

BROWSER = Path(__file__).parents[1] / "browser"
NODE_MODULES = Path(os.environ.get("T2A_NODE_MODULES", BROWSER / "node_modules"))
RIGS = {"mixamo_glb": lambda p: mixamo_glb(p / "mixamo.glb"), "vrm1": lambda p: vrm_file(p / "avatar.vrm"),
        "vrm0": lambda p: vrm_file(p / "avatar0.vrm", version="0.x")}
_DT = {5126: "<f4", 5121: "u1", 5123: "<u2", 5125: "<u4"}
_N = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def _node(*packages: str) -> str:
    """The node binary, or skip saying what is missing."""
    node = shutil.which("node")
    if node is None:
        pytest.skip("Node.js is not installed (.ci/run installs it)")
    for p in packages:
        if not (NODE_MODULES / p).is_dir():
            pytest.skip(f"npm package {p} is not in {NODE_MODULES} (npm ci --prefix tests/browser)")
    return node


def _accessor(gl: dict, blob: bytes, i: int) -> np.ndarray:
    acc = gl["accessors"][i]
    view = gl["bufferViews"][acc["bufferView"]]
    n = _N[acc["type"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return np.frombuffer(blob, _DT[acc["componentType"]], acc["count"] * n, start).reshape(acc["count"], n)


def glb_world_positions(path: Path) -> tuple[list[str], np.ndarray]:
    """Names and world positions ``(T, J, 3)`` of a skinned GLB's joints over its first animation's key frames,
    by forward kinematics of the file's own node tree (rest TRS, overridden by the animated channels)."""
    gl, blob = read_glb(path)
    nodes = gl["nodes"]
    anim = gl["animations"][0]
    T = gl["accessors"][anim["samplers"][0]["input"]]["count"]
    parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    trs = {i: {"translation": np.tile(n.get("translation", [0.0, 0, 0]), (T, 1)),
               "rotation": np.tile(n.get("rotation", [0.0, 0, 0, 1]), (T, 1)),
               "scale": np.tile(n.get("scale", [1.0, 1, 1]), (T, 1))} for i, n in enumerate(nodes)}
    for ch in anim["channels"]:
        values = _accessor(gl, blob, anim["samplers"][ch["sampler"]]["output"])
        assert len(values) == T
        trs[ch["target"]["node"]][ch["target"]["path"]] = values.astype(np.float64)
    world: dict[int, np.ndarray] = {}

    def matrix(i: int) -> np.ndarray:
        if i not in world:
            m = np.tile(np.eye(4), (T, 1, 1))
            m[:, :3, :3] = Rotation.from_quat(trs[i]["rotation"]).as_matrix() * trs[i]["scale"][:, None, :]
            m[:, :3, 3] = trs[i]["translation"]
            world[i] = matrix(parent[i]) @ m if i in parent else m
        return world[i]

    joints = sorted({j for s in gl["skins"] for j in s["joints"]})
    return [nodes[j]["name"] for j in joints], np.stack([matrix(j)[:, :3, 3] for j in joints], axis=1)


@pytest.mark.parametrize("rig", list(RIGS))
def test_the_users_glb_character_is_animated_like_the_source(walk, tmp_path, rig, walk_motion):
    """World joint positions of the GLB written on the rig, by FK of its own nodes, match the source's up to the
    leg-length scale: hands and feet within 2 cm where the source's feet are planted; no more skating."""
    rig_file = RIGS[rig](tmp_path)
    opts = ExportOptions(rig=rig_file)
    glb_path, = walk.save_glb(tmp_path / "out.glb", opts)
    bvh = read_bvh(walk.save_bvh(tmp_path / "out.bvh", opts)[0], scale=1)
    names, pos = glb_world_positions(glb_path)
    src = walk_motion
    m = map_skeletons(src.skeleton, bvh.skeleton, target_map=opts.target_map)
    assert m.scale != pytest.approx(1.0, abs=0.01)
    # the GLB plays the very motion the BVH on the same skeleton holds
    order = [bvh.skeleton.names.index(n) for n in names]
    assert np.abs(pos - bvh.positions[:, order]).max() < 1e-4
    columns = {j: names.index(n) for j, n in enumerate(bvh.skeleton.names) if n in names}
    for role, err in limb_errors(src, pos, m, columns).items():
        assert err < 0.02, (rig, role, err)
    assert skating_ratio(bvh) <= skating_ratio(src)


@pytest.mark.parametrize("rig", list(RIGS))
def test_the_glb_keeps_the_users_mesh_skin_and_extensions(walk, tmp_path, rig):
    rig_file = RIGS[rig](tmp_path)
    gl_in, bin_in = read_glb(rig_file)
    out, = walk.save_glb(tmp_path / "out.glb", ExportOptions(rig=rig_file))
    gl, blob = read_glb(out)
    for key in ("meshes", "skins", "materials", "scenes", "extensions", "extensionsUsed"):
        assert gl.get(key) == gl_in.get(key), key
    assert blob[:len(bin_in)] == bin_in  # the mesh data untouched, the animation appended
    assert [n.get("name") for n in gl["nodes"]] == [n.get("name") for n in gl_in["nodes"]]
    animated = {c["target"]["node"] for c in gl["animations"][0]["channels"]}
    assert animated == set(read_gltf_rig(rig_file).nodes)
    translated = {c["target"]["node"] for c in gl["animations"][0]["channels"] if c["target"]["path"] == "translation"}
    assert len(translated) == 1  # the hips only (the root joint)


def test_a_vrm_humanoid_names_the_joints(tmp_path):
    """VRoid-style names are no known rig's: the roles come from the VRM extension (1.0 and 0.x)."""
    for version in ("1.0", "0.x"):
        rig = read_gltf_rig(vrm_file(tmp_path / f"a{version}.vrm", version=version))
        assert rig.vrm == version
        assert set(REQUIRED) <= set(rig.humanoid)
        assert all(name == _vroid(role) for role, name in rig.humanoid.items())
        assert ExportOptions(rig=rig.path).check().target_map == rig.humanoid


def test_bad_glb_rigs_are_refused_with_one_clear_message(tmp_path):
    gl, blob = read_glb(mixamo_glb(tmp_path / "m.glb"))
    gl.pop("skins")
    gl["nodes"][-1].pop("skin")
    no_skin = tmp_path / "noskin.glb"
    no_skin.write_bytes(pack_glb(gl, BufferBuilder(blob, gl.pop("bufferViews"), gl.pop("accessors"))))
    proc = run_cli("太郎は歩く。", "--rig", no_skin, "-o", tmp_path / "x.bvh", "--glb", tmp_path / "x.glb")
    assert_clean_error(proc, "no skin")
    assert not (tmp_path / "x.bvh").exists() and not (tmp_path / "x.glb").exists()

    # names no table knows: read by the skeleton's shape (a human), so it animates without a --map file;
    # with the legs cut off it is no human skeleton, and the error says so and how to place the joints
    rows = [(n.replace("mixamorig:", "bone_"), p and p.replace("mixamorig:", "bone_"), r) for n, p, r in _mixamo_rows()]
    unknown = tmp_path / "unknown.glb"
    unknown.write_bytes(skinned_glb(rows, _a_pose(_positions(_rest())), bone_axes=False)[0])
    assert run_cli("太郎は歩く。", "--rig", unknown, "-o", tmp_path / "u.bvh").returncode == 0
    legless = [r for r in rows if "Leg" not in r[0] and "Foot" not in r[0] and "Toe" not in r[0]]
    unknown.write_bytes(skinned_glb(legless, _a_pose(_positions(_rest())), bone_axes=False)[0])
    assert_clean_error(run_cli("太郎は歩く。", "--rig", unknown, "-o", tmp_path / "x.bvh"), "hips", "leftUpperLeg",
                       "read by its shape", "--map")

    junk = tmp_path / "junk.vrm"
    junk.write_bytes(b"not a model")
    with pytest.raises(RigError, match="not a glTF binary"):  # a user-facing error: exit 2 like the others
        ExportOptions(rig=junk).check()


def test_root_motion_on_a_glb_rig_without_a_root_bone_is_refused(walk, tmp_path):
    rig = mixamo_glb(tmp_path / "m.glb")
    with pytest.raises(ExportError, match="no root bone"):
        walk.save_glb(tmp_path / "r.glb", ExportOptions(rig=rig, root_motion=True))
    assert not (tmp_path / "r.glb").exists()
    proc = run_cli("太郎は歩く。", "--rig", rig, "--root-motion", "--glb", tmp_path / "r.glb", "-o", tmp_path / "r.bvh")
    assert_clean_error(proc, "no root bone")
    assert "synthesising" not in proc.stderr  # refused before any work


def _vrma(path: Path) -> tuple[dict, dict[str, np.ndarray], dict[str, np.ndarray]]:
    gl, blob = read_glb(path)
    anim = gl["animations"][0]
    out: dict[str, dict[str, np.ndarray]] = {"translation": {}, "rotation": {}}
    for ch in anim["channels"]:
        name = gl["nodes"][ch["target"]["node"]]["name"]
        out[ch["target"]["path"]][name] = _accessor(gl, blob, anim["samplers"][ch["sampler"]]["output"])
    return gl, out["translation"], out["rotation"]


def test_the_vrma_holds_the_humanoid_in_a_vrm_t_pose(walk, tmp_path, walk_motion):
    path, = walk.save_vrma(tmp_path / "walk.vrma")
    gl, trans, rots = _vrma(path)
    ext = gl["extensions"]["VRMC_vrm_animation"]
    assert gl["extensionsUsed"] == ["VRMC_vrm_animation"] and ext["specVersion"] == "1.0"
    bones = ext["humanoid"]["humanBones"]
    assert set(REQUIRED) <= set(bones)
    assert {gl["nodes"][b["node"]]["name"] for b in bones.values()} == set(bones)
    assert "meshes" not in gl and all("rotation" not in n and "scale" not in n for n in gl["nodes"])
    assert list(trans) == ["hips"] and set(rots) == set(bones)  # translation on the hips only (the spec)
    hips = gl["nodes"][bones["hips"]["node"]]
    assert 0.8 < hips["translation"][1] < 1.1  # the rest hips stand above the floor, not at the origin
    t = lambda role: np.array(gl["nodes"][bones[role]["node"]]["translation"])  # noqa: E731
    assert t("leftLowerArm")[0] > 0.2 and abs(t("leftLowerArm")[1]) < 0.01  # T-pose: the left arm along +X
    src = walk_motion
    assert len(trans["hips"]) == src.n_frames
    np.testing.assert_allclose(np.linalg.norm(rots["leftUpperLeg"], axis=-1), 1.0, atol=1e-5)
    assert np.ptp(trans["hips"][:, 2]) > 1.0  # the walk travels


@pytest.mark.parametrize("version,bone_axes", [("1.0", False), ("1.0", True), ("0.x", False)])
def test_the_vrma_plays_on_a_vrm_avatar_in_three_vrm(walk, tmp_path, version, bone_axes):
    """@pixiv/three-vrm-animation plays the file on the avatar: frames advance, the bones move, and the avatar's
    joints go where our retargeting onto it puts them (within 1 cm; a 0.x avatar faces -Z and plays turned;
    an avatar whose bones have rest rotations plays the same)."""
    node = _node("three", "@pixiv/three-vrm", "@pixiv/three-vrm-animation")
    avatar = vrm_file(tmp_path / "avatar.vrm", version=version, bone_axes=bone_axes)
    opts = ExportOptions(rig=avatar)
    vrma, = walk.save_vrma(tmp_path / "walk.vrma", opts)
    bvh = read_bvh(walk.save_bvh(tmp_path / "walk.bvh", opts)[0], scale=1)
    frames = [0, 15, 30, 45, bvh.n_frames - 1]
    proc = subprocess.run([node, str(BROWSER / "vrma_check.mjs"), str(NODE_MODULES), str(avatar), str(vrma),
                           json.dumps([f / bvh.fps for f in frames])], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["metaVersion"] == version[0] and out["warnings"] == []
    assert out["duration"] == pytest.approx((bvh.n_frames - 1) / bvh.fps, abs=1e-4)
    turn = np.array([-1.0, 1.0, -1.0]) if version == "0.x" else np.ones(3)
    moved = {b: np.ptp(np.array(p), axis=0).max() for b, p in out["bones"].items()}
    assert moved["hips"] > 1.0 and moved["leftHand"] > 0.2 and moved["rightFoot"] > 0.5
    for bone, positions in out["bones"].items():
        j = bvh.skeleton.names.index(_vroid(bone))
        err = np.linalg.norm(np.array(positions) - bvh.positions[frames, j] * turn, axis=-1)
        assert err.max() < 0.01, (bone, err.max())


def test_glb_and_vrma_outputs_pass_the_khronos_validator_and_load_in_three(walk, tmp_path):
    """No validator errors; three.js' GLTFLoader plays the GLB with the user's bones where its own nodes put them."""
    node = _node("gltf-validator", "three")
    files = [walk.save_vrma(tmp_path / "walk.vrma")[0]]
    for rig in RIGS:
        files += walk.save_glb(tmp_path / f"{rig}.glb", ExportOptions(rig=RIGS[rig](tmp_path)))
    files += walk.save_vrma(tmp_path / "on_avatar.vrma", ExportOptions(rig=RIGS["vrm1"](tmp_path), loop=True))
    times = [0.0, 1.0]
    for f in files:
        proc = subprocess.run([node, str(BROWSER / "gltf_check.mjs"), str(NODE_MODULES), str(f), json.dumps(times)],
                              capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        if f.suffix == ".glb":
            (actor,) = json.loads(proc.stdout)["three"]["actors"]
            names, pos = glb_world_positions(f)
            order = [names.index(b) for b in (n.replace("mixamorig", "mixamorig:") if ":" in names[0] else n
                                              for n in actor["bones"])]  # three.js drops ':' from node names
            for k, t in enumerate(times):
                np.testing.assert_allclose(actor["frames"][k], pos[round(t * walk.fps), order], atol=1e-4)
        report = json.loads(proc.stdout)["validator"]
        assert report["numErrors"] == 0, (f.name, report["messages"])
        # only notes that the validator does not know the VRM extensions, and VRMA's mesh-less leaf bones
        assert all(m.split(":")[0] in ("UNSUPPORTED_EXTENSION", "NODE_EMPTY", "INVALID_EXTENSION_NAME_FORMAT")
                   for m in report["messages"]), (f.name, report["messages"])


@pytest.mark.parametrize("rig", list(RIGS))
def test_blender_imports_the_animated_character(walk, tmp_path, rig):
    """Needs a Python with Blender's ``bpy`` (``pip install bpy`` in a Python 3.11 venv) named by $T2A_BLENDER_PYTHON:
    Blender's glTF importer finds the user's mesh and armature, and its bones go where the BVH on the rig puts them."""
    py = os.environ.get("T2A_BLENDER_PYTHON")
    if not py:
        pytest.skip("set T2A_BLENDER_PYTHON to a Python that has bpy to import the GLB into Blender")
    opts = ExportOptions(rig=RIGS[rig](tmp_path))
    path, = walk.save_glb(tmp_path / "out.glb", opts)
    bvh = read_bvh(walk.save_bvh(tmp_path / "out.bvh", opts)[0], scale=1)
    frames = [0, bvh.n_frames // 2, bvh.n_frames - 1]
    proc = subprocess.run([py, str(BROWSER / "blender_check.py"), str(path), str(round(bvh.fps)), json.dumps(frames)],
                          capture_output=True, text=True, timeout=300)
    line = next((ln for ln in proc.stdout.splitlines() if ln.startswith("JSON")), None)
    assert proc.returncode == 0 and line, proc.stderr[-3000:]
    out = json.loads(line[4:])
    assert out["result"] == ["FINISHED"] and ["Body", "MESH"] in out["objects"]
    idx = [bvh.skeleton.names.index(b) for b in out["bones"]]
    for f in frames:
        v = np.array(out["frames"][str(f)])
        np.testing.assert_allclose(np.c_[v[:, 0], v[:, 2], -v[:, 1]], bvh.positions[f][idx], atol=1e-3)


def test_the_glb_of_a_bvh_rig_carries_the_exported_motion(walk, tmp_path):
    """With a BVH rig (and the engine options) the GLB shows the same motion the BVH holds, in metres."""
    from rig_builders import mixamo_rig

    opts = ExportOptions(rig=mixamo_rig(tmp_path / "m.bvh"), in_place=True, units="cm")
    glb, = walk.save_glb(tmp_path / "out.glb", opts)
    bvh = read_bvh(walk.save_bvh(tmp_path / "out.bvh", opts)[0], scale=0.01)
    names, pos = glb_world_positions(glb)
    assert names == list(bvh.skeleton.names)
    assert np.abs(pos - bvh.positions).max() < 1e-4
    assert np.abs(pos[:, 0, [0, 2]]).max() < 0.1  # in place
