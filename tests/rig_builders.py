"""Test rigs made from the built-in skeleton (no downloads): Mixamo names with an A-pose rest, SMPL's 22 joints,
the Unreal mannequin (a root bone above the pelvis), VRM humanoid bone names; each with its own proportions,
as BVH files."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from text2anim.core import Motion, Skeleton
from text2anim.core.floor import FOOT_CLEARANCE
from text2anim.motiondb.library.skeleton import canonical_skeleton
from text2anim.output.bvh_write import write_bvh


def _rest() -> dict[str, np.ndarray]:
    skel = canonical_skeleton()
    return dict(zip(skel.names, skel.rest_positions()))


def _mid(p: dict, a: str, b: str) -> np.ndarray:
    return (p[a] + p[b]) / 2


def _positions(p: dict) -> dict[str, np.ndarray]:
    """Where a humanoid's joints (by VRM role; ``*Index``: a finger) sit on the built-in body, metres."""
    out = {"hips": p["Hips"], "spine": p["Spine"], "chest": _mid(p, "Spine", "Spine1"), "upperChest": p["Spine1"],
           "neck": p["Neck1"], "head": p["Head"]}
    for side, s in (("left", 1.0), ("right", -1.0)):
        L = "Left" if side == "left" else "Right"
        out.update({f"{side}Shoulder": p["Spine1"] + np.array([0.04 * s, 0.09, 0.0]),
                    f"{side}UpperArm": p[f"{L}Arm"], f"{side}LowerArm": p[f"{L}ForeArm"],
                    f"{side}Hand": p[f"{L}Hand"], f"{side}Index": p[f"{L}HandIndex1"],
                    f"{side}UpperLeg": p[f"{L}UpLeg"], f"{side}LowerLeg": p[f"{L}Leg"],
                    f"{side}Foot": p[f"{L}Foot"], f"{side}Toes": p[f"{L}ToeBase"]})
    return out


def _a_pose(pos: dict[str, np.ndarray], degrees: float = 45.0) -> dict[str, np.ndarray]:
    """Arms lowered by ``degrees`` about the body's forward axis at the shoulder joints."""
    out = dict(pos)
    for side, sign in (("left", -1.0), ("right", 1.0)):
        rot = Rotation.from_euler("z", sign * degrees, degrees=True)
        pivot = pos[f"{side}UpperArm"]
        for part in ("LowerArm", "Hand", "Index"):
            out[f"{side}{part}"] = pivot + rot.apply(pos[f"{side}{part}"] - pivot)
    return out


def _skeleton(rows, pos: dict[str, np.ndarray], channels, ends: dict[str, tuple]) -> Skeleton:
    """``rows``: (name, parent name, role); positions by role; offsets from the parent's position."""
    names = [r[0] for r in rows]
    parents = [-1 if r[1] is None else names.index(r[1]) for r in rows]
    world = np.array([pos[r[2]] if r[2] in pos else np.zeros(3) for r in rows])
    offsets = np.array([world[j] - (world[p] if p >= 0 else 0.0) for j, p in enumerate(parents)])
    end_sites = tuple((names.index(n), np.array(o)) for n, o in ends.items())
    return Skeleton(names, parents, offsets, end_sites, tuple(channels(n, j) for j, n in enumerate(names)))


def _write(skel: Skeleton, path: Path, unit: float = 1.0) -> Path:
    """A one-frame BVH of the rest pose in ``unit`` per metre."""
    rest = Motion(skel.scaled(unit), 30.0, skel.scaled(unit).offsets[:1], np.tile([0.0, 0, 0, 1], (1, skel.n_joints, 1)))
    write_bvh(rest, path)
    return path


def mixamo_rig(path: Path, scale: float = 1.08) -> Path:
    """Mixamo joint names (``mixamorig:``), an A-pose rest, ZXY channels, fingers, 8% taller; written in cm."""
    pos = {k: v * scale for k, v in _a_pose(_positions(_rest())).items()}
    rows, m = _mixamo_rows(), "mixamorig:"
    zxy = ("Zrotation", "Xrotation", "Yrotation")
    chans = lambda n, j: (("Xposition", "Yposition", "Zposition") + zxy) if j == 0 else zxy  # noqa: E731
    ends = {m + "Head": (0, 0.17 * scale, 0), m + "LeftToeBase": (0, 0, 0.06), m + "RightToeBase": (0, 0, 0.06)}
    return _write(_skeleton(rows, pos, chans, ends), path, unit=100.0)


def smpl_rig(path: Path, scale: float = 0.93) -> Path:
    """SMPL's 22 body joints by name, children in SMPL's index order, a T-pose, 7% shorter."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    rows = [("pelvis", None, "hips")]
    for side in ("left", "right"):
        rows += [(f"{side}_hip", "pelvis", f"{side}UpperLeg"), (f"{side}_knee", f"{side}_hip", f"{side}LowerLeg"),
                 (f"{side}_ankle", f"{side}_knee", f"{side}Foot"), (f"{side}_foot", f"{side}_ankle", f"{side}Toes")]
    rows += [("spine1", "pelvis", "spine"), ("spine2", "spine1", "chest"), ("spine3", "spine2", "upperChest"),
             ("neck", "spine3", "neck"), ("head", "neck", "head")]
    for side in ("left", "right"):
        rows += [(f"{side}_collar", "spine3", f"{side}Shoulder"), (f"{side}_shoulder", f"{side}_collar", f"{side}UpperArm"),
                 (f"{side}_elbow", f"{side}_shoulder", f"{side}LowerArm"), (f"{side}_wrist", f"{side}_elbow", f"{side}Hand")]
    chans = lambda n, j: Skeleton.default_channels(2)[0 if j == 0 else 1]  # noqa: E731
    return _write(_skeleton(rows, pos, chans, {"head": (0, 0.15, 0)}), path)


def unreal_rig(path: Path, scale: float = 1.02) -> Path:
    """Unreal mannequin names: a ``root`` bone at the floor above ``pelvis`` (which has position channels)."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    pos["root"] = pos["hips"] - np.array([0.0, pos["hips"][1] - min(pos["leftToes"][1], pos["leftFoot"][1]), 0.0])
    rows = [("root", None, "root"), ("pelvis", "root", "hips"), ("spine_01", "pelvis", "spine"),
            ("spine_02", "spine_01", "chest"), ("spine_03", "spine_02", "upperChest"), ("neck_01", "spine_03", "neck"),
            ("head", "neck_01", "head")]
    for side, s in (("left", "l"), ("right", "r")):
        rows += [(f"clavicle_{s}", "spine_03", f"{side}Shoulder"), (f"upperarm_{s}", f"clavicle_{s}", f"{side}UpperArm"),
                 (f"lowerarm_{s}", f"upperarm_{s}", f"{side}LowerArm"), (f"hand_{s}", f"lowerarm_{s}", f"{side}Hand"),
                 (f"index_01_{s}", f"hand_{s}", f"{side}Index")]
    for side, s in (("left", "l"), ("right", "r")):
        rows += [(f"thigh_{s}", "pelvis", f"{side}UpperLeg"), (f"calf_{s}", f"thigh_{s}", f"{side}LowerLeg"),
                 (f"foot_{s}", f"calf_{s}", f"{side}Foot"), (f"ball_{s}", f"foot_{s}", f"{side}Toes")]
    full = ("Xposition", "Yposition", "Zposition", "Zrotation", "Yrotation", "Xrotation")
    chans = lambda n, j: full if j <= 1 else full[3:]  # noqa: E731
    return _write(_skeleton(rows, pos, chans, {"head": (0, 0.15, 0)}), path)


def vrm_rig(path: Path, scale: float = 0.85) -> Path:
    """VRM humanoid bone names (a T-pose avatar 15% shorter), with an index finger left at rest."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    rows = [(name + "Proximal" if name.endswith("Index") else name, parent, role) for name, parent, role in _vrm_rows()]
    chans = lambda n, j: Skeleton.default_channels(2)[0 if j == 0 else 1]  # noqa: E731
    return _write(_skeleton(rows, pos, chans, {"head": (0, 0.15, 0)}), path)


# ----------------------------------------------------------------------------- glTF rigs (.glb, .vrm)
def _mixamo_rows() -> list[tuple[str, str | None, str]]:
    m = "mixamorig:"
    rows = [(m + "Hips", None, "hips"), (m + "Spine", m + "Hips", "spine"), (m + "Spine1", m + "Spine", "chest"),
            (m + "Spine2", m + "Spine1", "upperChest"), (m + "Neck", m + "Spine2", "neck"),
            (m + "Head", m + "Neck", "head")]
    for side, L in (("left", "Left"), ("right", "Right")):
        rows += [(f"{m}{L}Shoulder", m + "Spine2", f"{side}Shoulder"),
                 (f"{m}{L}Arm", f"{m}{L}Shoulder", f"{side}UpperArm"),
                 (f"{m}{L}ForeArm", f"{m}{L}Arm", f"{side}LowerArm"), (f"{m}{L}Hand", f"{m}{L}ForeArm", f"{side}Hand"),
                 (f"{m}{L}HandIndex1", f"{m}{L}Hand", f"{side}Index")]
    for side, L in (("left", "Left"), ("right", "Right")):
        rows += [(f"{m}{L}UpLeg", m + "Hips", f"{side}UpperLeg"), (f"{m}{L}Leg", f"{m}{L}UpLeg", f"{side}LowerLeg"),
                 (f"{m}{L}Foot", f"{m}{L}Leg", f"{side}Foot"), (f"{m}{L}ToeBase", f"{m}{L}Foot", f"{side}Toes")]
    return rows


def _bone_frame(d: np.ndarray) -> np.ndarray:
    """A rotation whose +Y axis points along ``d`` (a Blender bone's axes), its roll fixed by world +Z/+X."""
    y = d / np.linalg.norm(d)
    helper = np.array([0.0, 0.0, 1.0]) if abs(y[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    x = np.cross(y, helper)
    x /= np.linalg.norm(x)
    return np.stack([x, y, np.cross(x, y)], axis=1)


def _box(center: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray]:
    """A cube's 8 corners and its 12 triangles (outward, counter-clockwise)."""
    corners = center + r * np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    tris = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                     [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return corners, tris


def skinned_glb(rows, world: dict[str, np.ndarray], *, bone_axes: bool, armature_scale: float = 1.0,
                extensions: dict | None = None, names: dict[str, str] | None = None,
                parts: tuple[tuple[np.ndarray, str], ...] = ()) -> tuple[bytes, dict[str, int]]:
    """A glTF binary of a skinned character: joints ``rows`` ``(name, parent name, role)`` at world positions by
    role (metres, Y up), under an ``Armature`` node scaled by ``armature_scale`` (joint translations in its units);
    ``bone_axes``: each joint's rest rotation turns its +Y along its bone (as Blender exports), else identity.
    The mesh is a small cube per joint, bound to it, and ``parts``: boxes ``(corners (8, 3), role)`` bound to
    that role's joint. ``extensions(node of role)`` may add root extensions.
    Returns the bytes and ``{role: node}``."""
    from text2anim.core.glb import BufferBuilder, pack_glb

    names = names or {}
    joint_names = [names.get(r[0], r[0]) for r in rows]
    index = {r[0]: i for i, r in enumerate(rows)}
    parents = [-1 if r[1] is None else index[r[1]] for r in rows]
    pos = np.array([world[r[2]] for r in rows])
    children = {i: [j for j, p in enumerate(parents) if p == i] for i in range(len(rows))}
    rot = np.tile(np.eye(3), (len(rows), 1, 1))
    if bone_axes:
        for i in range(len(rows)):
            d = pos[children[i][0]] - pos[i] if children[i] else pos[i] - pos[parents[i]]
            rot[i] = _bone_frame(d)
    arm = np.eye(4)
    arm[:3, :3] *= armature_scale
    nodes: list[dict] = []
    for i, (p, name) in enumerate(zip(parents, joint_names)):
        Wp = rot[p] if p >= 0 else np.eye(3)
        base = pos[p] if p >= 0 else np.zeros(3)
        t = Wp.T @ (pos[i] - base) / armature_scale
        node: dict = {"name": name, "translation": [float(v) for v in t]}
        q = Rotation.from_matrix(Wp.T @ rot[i]).as_quat()
        if not np.allclose(q, [0, 0, 0, 1]):
            node["rotation"] = [float(v) for v in q]
        if children[i]:
            node["children"] = [c + 1 for c in children[i]]  # node 0 is the armature
        nodes.append(node)
    b = BufferBuilder()
    verts, tris, joints = [], [], []
    for i in range(len(rows)):
        c, t = _box(pos[i], 0.02)
        tris.append(t + 8 * i)
        verts.append(c)
        joints += [i] * 8
    roles = [r[2] for r in rows]
    for corners, role in parts:
        tris.append(_box(np.zeros(3), 1.0)[1] + 8 * len(verts))
        verts.append(corners)
        joints += [roles.index(role)] * 8
    v = np.vstack(verts)
    j4 = np.zeros((len(v), 4), dtype=np.uint8)
    j4[:, 0] = joints
    w4 = np.zeros((len(v), 4))
    w4[:, 0] = 1.0
    ibm = np.zeros((len(rows), 4, 4))
    for i in range(len(rows)):
        m = np.eye(4)
        m[:3, :3] = rot[i] * armature_scale
        m[:3, 3] = pos[i]
        ibm[i] = np.linalg.inv(m)
    prim = {"attributes": {"POSITION": b.accessor(v, 5126, "VEC3", target=34962, minmax=True),
                           "JOINTS_0": b.accessor(j4, 5121, "VEC4", target=34962),
                           "WEIGHTS_0": b.accessor(w4, 5126, "VEC4", target=34962)},
            "indices": b.accessor(np.vstack(tris).reshape(-1), 5123, "SCALAR", target=34963), "mode": 4,
            "material": 0}
    gl: dict = {
        "asset": {"version": "2.0", "generator": "text2anim tests"},
        "scene": 0, "scenes": [{"nodes": [0, len(rows) + 1]}],
        "nodes": [{"name": "Armature", "children": [1], **({"scale": [armature_scale] * 3}
                                                             if armature_scale != 1.0 else {})}]
        + nodes + [{"name": "Body", "mesh": 0, "skin": 0}],
        "materials": [{"name": "skin", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.5, 1.0],
                                                                "metallicFactor": 0.0}}],
        "meshes": [{"name": "Body", "primitives": [prim]}],
        "skins": [{"joints": [i + 1 for i in range(len(rows))], "skeleton": 1,
                   "inverseBindMatrices": b.accessor(ibm.transpose(0, 2, 1).reshape(-1, 16), 5126, "MAT4")}],
        "buffers": [{}],
    }
    role_node = {r[2]: i + 1 for i, r in enumerate(rows)}
    if extensions:
        gl["extensions"] = extensions(role_node)
        gl["extensionsUsed"] = sorted(gl["extensions"])
    return pack_glb(gl, b), role_node


def mixamo_glb(path: Path, scale: float = 1.08) -> Path:
    """A Mixamo character as Blender exports it: ``mixamorig:`` names, an A-pose rest, bone axes along the
    bones, an armature scaled by 0.01 (joint translations in cm), a tiny skinned mesh; 8% taller; standing as our
    motions do (the lowest joint FOOT_CLEARANCE above y = 0)."""
    pos = {k: v * scale for k, v in _a_pose(_positions(_rest())).items()}
    lift = -min(p[1] for p in pos.values()) + FOOT_CLEARANCE
    pos = {k: v + [0.0, lift, 0.0] for k, v in pos.items()}
    data, _ = skinned_glb(_mixamo_rows(), pos, bone_axes=True, armature_scale=0.01)
    path.write_bytes(data)
    return path


def mixamo_feet_glb(path: Path, scale: float = 1.0) -> Path:
    """A Mixamo character with a Mixamo foot (as three.js's Michelle has it): the toe joint at the ball of the
    foot, 40° below the ankle's forward (the built-in body's: 23°), and a mesh of shoes whose flat soles stand
    on y = 0 in the rest pose, heel 5 cm behind the ankle, toe tip 6 cm ahead of the ball; otherwise as
    :func:`mixamo_glb`. A retarget that turns its toe bone as the built-in body's leaves it heel-down."""
    pos = {k: v * scale for k, v in _a_pose(_positions(_rest())).items()}
    lift = -min(p[1] for p in pos.values())
    pos = {k: v + [0.0, lift, 0.0] for k, v in pos.items()}
    parts = []
    for side in ("left", "right"):
        ankle = pos[f"{side}Foot"].copy()
        ankle[1] = 0.095 * scale
        pos[f"{side}Foot"] = ankle
        pos[f"{side}Toes"] = np.array([ankle[0], 0.024 * scale, ankle[2] + 0.085 * scale])
        x0, x1 = ankle[0] - 0.045 * scale, ankle[0] + 0.045 * scale
        for z0, z1, role in ((-0.05, 0.085, f"{side}Foot"), (0.085, 0.145, f"{side}Toes")):
            top = (0.075 if role.endswith("Foot") else 0.035) * scale
            corners = np.array([[x, y, ankle[2] + z * scale] for x in (x0, x1) for y in (0.0, top) for z in (z0, z1)])
            parts.append((corners, role))
    data, _ = skinned_glb(_mixamo_rows(), pos, bone_axes=True, armature_scale=0.01, parts=tuple(parts))
    path.write_bytes(data)
    return path


#: VRoid-style node names: no known rig's, so the roles come from the VRM humanoid extension alone.
def _vroid(role: str) -> str:
    side = "L" if role.startswith("left") else "R" if role.startswith("right") else "C"
    part = role[4:] if side == "L" else role[5:] if side == "R" else role
    return f"J_Bip_{side}_{part[0].upper()}{part[1:]}"


def vrm_file(path: Path, scale: float = 0.85, version: str = "1.0", bone_axes: bool = False) -> Path:
    """A VRM avatar from the built-in skeleton: VRM T-pose, 15% shorter, VRoid-style joint names, the humanoid
    bones in the ``VRMC_vrm`` 1.0 extension (facing +Z) or the ``VRM`` 0.x one (facing -Z, as 0.x models do);
    ``bone_axes``: rest rotations along the bones (VRM 1.0 allows any)."""
    pos = {k: v * scale for k, v in _positions(_rest()).items()}
    lift = -min(p[1] for p in pos.values()) + FOOT_CLEARANCE
    flip = np.array([-1.0, 1.0, -1.0]) if version == "0.x" else np.ones(3)
    pos = {k: (v + [0.0, lift, 0.0]) * flip for k, v in pos.items()}
    rows = _vrm_rows()
    names = {r[0]: _vroid(r[0]) for r in rows}
    humanoid_roles = [r[0] for r in rows if not r[0].endswith("Index")]

    def ext(role_node: dict[str, int]) -> dict:
        if version == "0.x":
            return {"VRM": {"exporterVersion": "text2anim tests", "specVersion": "0.0",
                            "meta": {"title": "test avatar", "author": "text2anim", "licenseName": "CC0"},
                            "humanoid": {"humanBones": [{"bone": r, "node": role_node[r], "useDefaultValues": True}
                                                        for r in humanoid_roles]}}}
        return {"VRMC_vrm": {"specVersion": "1.0",
                             "meta": {"name": "test avatar", "authors": ["text2anim"],
                                      "licenseUrl": "https://vrm.dev/licenses/1.0/"},
                             "humanoid": {"humanBones": {r: {"node": role_node[r]} for r in humanoid_roles}}}}

    data, _ = skinned_glb(rows, pos, bone_axes=bone_axes, extensions=ext, names=names)
    path.write_bytes(data)
    return path


def _vrm_rows() -> list[tuple[str, str | None, str]]:
    """The VRM humanoid's bones as rows (name, parent name, role): each named after its role."""
    pairs: list[tuple[str, str | None]] = [("hips", None), ("spine", "hips"), ("chest", "spine"),
                                           ("upperChest", "chest"), ("neck", "upperChest"), ("head", "neck")]
    for side in ("left", "right"):
        pairs += [(f"{side}Shoulder", "upperChest"), (f"{side}UpperArm", f"{side}Shoulder"),
                  (f"{side}LowerArm", f"{side}UpperArm"), (f"{side}Hand", f"{side}LowerArm"),
                  (f"{side}Index", f"{side}Hand")]
    for side in ("left", "right"):
        pairs += [(f"{side}UpperLeg", "hips"), (f"{side}LowerLeg", f"{side}UpperLeg"),
                  (f"{side}Foot", f"{side}LowerLeg"), (f"{side}Toes", f"{side}Foot")]
    return [(name, parent, name) for name, parent in pairs]
