"""Malformed glTF/VRM rigs (issue 28): each is one clear line and exit 2, never a traceback,
and a deep node chain is read in time and memory linear in its size.

Every file is a real rig (the builders of ``rig_builders``) with one field broken the way a
careless exporter or an attacker would break it, run through the real ``text2anim --rig``.
"""
from __future__ import annotations

import json
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from cli_run import assert_clean_error, text2anim
from rig_builders import mixamo_glb, vrm_file


def _split(data: bytes) -> tuple[dict, bytes]:
    n = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + n]), data[20 + n:]


def _glb(gl: dict, rest: bytes = b"") -> bytes:
    j = json.dumps(gl).encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + rest
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def _broken(gl: dict, field: str) -> None:
    nodes = gl["nodes"]
    if field == "children as a dict":
        nodes[0]["children"] = {"a": 1}
    elif field == "child out of range":
        nodes[0]["children"] = [len(nodes) + 5]
    elif field == "short matrix":
        nodes[1].pop("translation", None), nodes[1].pop("rotation", None)
        nodes[1]["matrix"] = [1.0] * 15
    elif field == "rotation as a string":
        nodes[1]["rotation"] = "0 0 0 1"
    elif field == "skin joint out of range":
        gl["skins"][0]["joints"].append(len(nodes) + 100)
    elif field == "node not an object":
        nodes[2] = 7
    elif field == "zero scale":
        nodes[1]["scale"] = [0.0, 0.0, 0.0]
    elif field == "mirrored scale":
        nodes[1]["scale"] = [1.0, -1.0, 1.0]
    elif field == "humanoid as a string":
        gl.setdefault("extensions", {})["VRMC_vrm"] = {"humanoid": "hips"}


FIELDS = ["children as a dict", "child out of range", "short matrix", "rotation as a string", "skin joint out of range",
          "node not an object", "zero scale", "mirrored scale", "humanoid as a string"]


@pytest.mark.parametrize("field", FIELDS)
def test_a_rig_with_one_broken_field_is_one_line(tmp_path, field):
    gl, rest = _split(mixamo_glb(tmp_path / "good.glb").read_bytes())
    _broken(gl, field)
    bad = tmp_path / "bad.glb"
    bad.write_bytes(_glb(gl, rest))
    assert_clean_error(text2anim("太郎は歩く。", "--rig", bad, "-o", tmp_path / "x.bvh"), str(bad))
    assert not (tmp_path / "x.bvh").exists()


def test_a_vrm_whose_humanoid_bones_are_not_objects_is_one_line(tmp_path):
    gl, rest = _split(vrm_file(tmp_path / "good.vrm").read_bytes())
    gl["extensions"]["VRMC_vrm"]["humanoid"]["humanBones"] = {"hips": 3}
    bad = tmp_path / "bad.vrm"
    bad.write_bytes(_glb(gl, rest))
    assert_clean_error(text2anim("太郎は歩く。", "--rig", bad, "-o", tmp_path / "x.bvh"), "humanoid bones")


def test_a_deep_node_chain_is_read_in_linear_time_and_memory(tmp_path):
    """An 8,000-node chain (600 KB) needed over 3 GB and 30 s: ancestors listed per joint."""
    n = 8000
    nodes = [{"name": f"j{i}", "children": [i + 1] if i < n - 1 else [], "translation": [0, 0.01, 0]} for i in range(n)]
    chain = tmp_path / "chain.glb"
    chain.write_bytes(_glb({"asset": {"version": "2.0"}, "nodes": nodes, "skins": [{"joints": list(range(n))}]}))
    # VmHWM, this process's own peak (ru_maxrss would start from the forking pytest process's size)
    code = ("import re; from text2anim.core.gltf_rig import read_gltf_rig; "
            f"rig = read_gltf_rig({str(chain)!r}); "
            "hwm = re.search(r'VmHWM:\\s+(\\d+)', open('/proc/self/status').read()).group(1); "
            "print(len(rig.skeleton.names), hwm)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    joints, max_rss_kib = map(int, out.stdout.split())
    assert joints == n
    assert max_rss_kib < 400 * 1024  # the interpreter and numpy are most of it; the chain itself is small
