"""Fuzz the glTF/VRM rig reader: ``python benchmarks/fuzz_rig.py [CASES] [SEED]``.

Real rigs (a Mixamo-style GLB, a VRM 1.0 and a VRM 0.x avatar from ``tests/rig_builders.py``)
with one to three JSON fields replaced by junk or removed (and, one case in five, a damaged byte),
read by ``core.gltf_rig.read_gltf_rig``. Prints the outcomes: accepted, refused with the reader's
one-line error, or traceback (any other exception; each printed), with the slowest case in CPU
time and the peak memory traced.
"""
import random
import resource
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from fuzz_mutations import damaged  # noqa: E402
from rig_builders import mixamo_glb, vrm_file  # noqa: E402
from text2anim.core.gltf_rig import read_gltf_rig  # noqa: E402

def main(n):
    rng = random.Random(int(sys.argv[2]) if len(sys.argv) > 2 else 7)
    out = {"accepted": 0, "refused": 0, "traceback": 0}; slow = 0.0; kinds = {}
    with tempfile.TemporaryDirectory() as tmp:
        srcs = [mixamo_glb(Path(tmp) / "m.glb"), vrm_file(Path(tmp) / "a.vrm"), vrm_file(Path(tmp) / "b.vrm", version="0.x")]
        bases = [(s.suffix, s.read_bytes()) for s in srcs]
        tracemalloc.start()
        for i in range(n):
            suf, base = rng.choice(bases)
            data = damaged(base, rng)
            p = Path(tmp) / f"f{i}{suf}"; p.write_bytes(data)
            t = time.process_time()
            try:
                read_gltf_rig(p); out["accepted"] += 1
            except Exception as e:
                if getattr(e, "user_facing", False): out["refused"] += 1
                else:
                    out["traceback"] += 1; kinds[type(e).__name__] = kinds.get(type(e).__name__, 0) + 1; print(repr(e)[:200])
            slow = max(slow, time.process_time() - t)
            p.unlink()
        peak = tracemalloc.get_traced_memory()[1]
    print(f"{n} mutated rigs (GLB, VRM 1.0, VRM 0.x): {out}; tracebacks by type {kinds}; "
          f"slowest {slow*1000:.0f} ms CPU; peak traced {peak/2**20:.1f} MB; maxrss {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss/1024:.0f} MB")

if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 300)
