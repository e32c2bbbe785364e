"""Rewrite ``tests/golden/outputs.json``: sha256 of the BVH bytes and the report of each golden sentence.

Run it only when a change is *meant* to alter the animation (and say so in the commit):
``python tests/golden/regen.py``. A refactor must leave the file as it is; the test
``tests/test_golden.py`` checks that.
"""
from __future__ import annotations

import hashlib
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: The golden sentences, one a line (benchmarks/bench_library.py animates them too).
SENTENCES = (HERE / "sentences.txt").read_text(encoding="utf-8").splitlines()
ENGINES = ("optimal", "constraint")


def digests(db) -> dict[str, str]:
    """``"engine|sentence" → sha256`` of every actor's BVH text and of the JSON report."""
    import text2anim
    from text2anim.output.bvh_write import format_bvh

    out = {}
    for engine in ENGINES:
        for text in SENTENCES:
            anim = text2anim.animate(text, db=db, blend=engine)
            h = hashlib.sha256()
            for name, motion in sorted(anim.motions.items()):
                h.update(name.encode() + b"\0" + format_bvh(motion).encode())
            h.update(json.dumps(anim.report, ensure_ascii=False, sort_keys=True).encode())
            out[f"{engine}|{text}"] = h.hexdigest()
    return out


if __name__ == "__main__":
    import tempfile

    from text2anim import reproducible

    reproducible.pin()  # as the test pins it (tests/conftest.py)

    from text2anim.motiondb import MotionDB

    with tempfile.TemporaryDirectory() as tmp, MotionDB.open(f"sqlite:///{tmp}/golden.sqlite") as db:
        data = digests(db)
    (HERE / "outputs.json").write_text(json.dumps(data, ensure_ascii=False, indent=1, sort_keys=True) + "\n")
    print(f"wrote {len(data)} digests", file=sys.stderr)
