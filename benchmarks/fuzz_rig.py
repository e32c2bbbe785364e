"""Fuzz the glTF/VRM rig reader: ``python benchmarks/fuzz_rig.py [CASES] [SEED]``.

Real rigs (a Mixamo-style GLB, a VRM 1.0 and a VRM 0.x avatar, and a Mixamo GLB with shoes from
``tests/rig_builders.py``) with one to three JSON fields replaced by junk or removed (and, one case in
five, a damaged byte), read by ``core.gltf_rig.read_gltf_rig``, their joints placed and their feet's
mesh read as ``--rig`` does (``ExportOptions.soles``: ``core.skeleton_shape``, ``core.gltf_mesh``). Prints the outcomes: accepted, refused with the reader's
one-line error, or traceback (any other exception; each printed), with the slowest case in CPU
time and the peak memory traced. Then (issue 41) the rigs at the limits through the real CLI
(``text2anim 走る --rig …`` in a child process, ``bounded_runs.py``: no traceback, 10 s of CPU, 1 GB): an
8,000-node chain (the shape reader walked a subtree per joint: 18.5 s) and a 10,001-node one.
"""
import json
import random
import struct
import resource
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from fuzz_mutations import damaged  # noqa: E402
from rig_builders import mixamo_feet_glb, mixamo_glb, vrm_file  # noqa: E402
from text2anim.core.gltf_rig import read_gltf_rig  # noqa: E402
from text2anim.export import ExportOptions  # noqa: E402
from bounded_runs import table, text2anim  # noqa: E402


def _glb(gl: dict) -> bytes:
    j = json.dumps(gl).encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def chain_runs(tmp: Path) -> list:
    """Node chains at and over the 10,000-node limit through ``--rig``."""
    runs = []
    for n in (8000, 10_001):
        nodes = [{"name": f"j{i}", "children": [i + 1] if i < n - 1 else [], "translation": [0, 0.01, 0]} for i in range(n)]
        path = tmp / f"chain{n}.glb"
        path.write_bytes(_glb({"asset": {"version": "2.0"}, "nodes": nodes, "skins": [{"joints": list(range(n))}]}))
        runs.append(text2anim(f"--rig a {n:,}-node chain GLB", "走る", "--rig", path, "-o", tmp / "a.bvh"))
    return runs

def main(n):
    rng = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 7)
    out = {"accepted": 0, "refused": 0, "traceback": 0}; slow = 0.0; kinds = {}
    with tempfile.TemporaryDirectory() as tmp:
        srcs = [mixamo_glb(Path(tmp) / "m.glb"), vrm_file(Path(tmp) / "a.vrm"), vrm_file(Path(tmp) / "b.vrm", version="0.x"),
                mixamo_feet_glb(Path(tmp) / "feet.glb")]
        bases = [(s.suffix, s.read_bytes()) for s in srcs]
        tracemalloc.start()
        for i in range(n):
            suf, base = rng.choice(bases)
            data = damaged(base, rng)
            p = Path(tmp) / f"f{i}{suf}"; p.write_bytes(data)
            t = time.process_time()
            try:
                read_gltf_rig(p); ExportOptions(rig=p).soles; out["accepted"] += 1  # its joints' roles, its soles
            except Exception as e:
                if getattr(e, "user_facing", False): out["refused"] += 1
                else:
                    out["traceback"] += 1; kinds[type(e).__name__] = kinds.get(type(e).__name__, 0) + 1; print(repr(e)[:200])
            slow = max(slow, time.process_time() - t)
            p.unlink()
        peak = tracemalloc.get_traced_memory()[1]
    print(f"{n} mutated rigs (GLB, VRM 1.0, VRM 0.x, GLB with shoes): {out}; tracebacks by type {kinds}; "
          f"slowest {slow*1000:.0f} ms CPU; peak traced {peak/2**20:.1f} MB; maxrss {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss/1024:.0f} MB")
    with tempfile.TemporaryDirectory() as tmp:
        runs = chain_runs(Path(tmp))
    print(table(runs))
    return 1 if out["traceback"] or any(r.failures for r in runs) else 0

if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1]) if len(sys.argv) > 1 else 300))
