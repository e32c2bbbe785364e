"""Damaged glTF/VRM rigs (seeded, in CI): the rig reader accepts them or refuses them with its one-line error,
never another exception. The larger run with timings is benchmarks/fuzz_rig.py."""
from __future__ import annotations

import random

import pytest

from fuzz_mutations import damaged
from rig_builders import mixamo_feet_glb, mixamo_glb, vrm_file
from text2anim.core.gltf_rig import read_gltf_rig
from text2anim.export import ExportOptions

CASES = 150  # per base rig; 450 in all, about 2 s


@pytest.mark.parametrize("kind", ["glb", "vrm1", "vrm0", "feet"])
def test_damaged_rigs_are_read_or_refused_in_one_line(kind, tmp_path):
    """The skeleton and, where it is read, the mesh under the feet (``core.gltf_mesh``: accessors, views and
    skins damaged as well, on the rig with shoes, ``mixamo_feet_glb``)."""
    base = {"glb": lambda: mixamo_glb(tmp_path / "base.glb"), "vrm1": lambda: vrm_file(tmp_path / "base.vrm"),
            "vrm0": lambda: vrm_file(tmp_path / "base.vrm", version="0.x"),
            "feet": lambda: mixamo_feet_glb(tmp_path / "base.glb")}[kind]()
    rng = random.Random(f"fuzz-{kind}")
    data = base.read_bytes()
    outcomes = {"accepted": 0, "refused": 0}
    for i in range(CASES):
        path = tmp_path / f"case{i}{base.suffix}"
        path.write_bytes(damaged(data, rng))
        try:
            read_gltf_rig(path)
            ExportOptions(rig=path).soles  # the feet's mesh, as --rig reads it
            outcomes["accepted"] += 1
        except Exception as exc:  # noqa: BLE001 - what is asserted is the kind of error
            assert getattr(exc, "user_facing", False), f"case {i}: {type(exc).__name__}: {exc}"
            assert "\n" not in str(exc) and len(str(exc)) < 1000
            outcomes["refused"] += 1
    assert outcomes["refused"] > CASES // 4  # the damage is real: most cases are refused
