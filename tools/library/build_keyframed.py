"""Rebuild ``keyframed.npz`` (the shipped keyframed clips, :mod:`motiondb.library.keyframed`) from ``clips/*.json``.

Run after changing a clip's JSON or the generator (keyframes, planting, reach)::

    python tools/library/build_keyframed.py [--out FILE] [--check]

This is the one place the seeded keyframed frames are generated: every clip of
:func:`motiondb.library.build_all` at :data:`motiondb.library.keyframed.FPS` that no captured clip replaces,
with its metadata and the :func:`motiondb.library.keyframed.sources_hash` of what it was made from, and the
foot contacts and the measured descriptions of every seeded clip (the captured ones from
``capture.npz``: rerun this after rebuilding that). The same sources give the same bytes. ``--check`` builds in memory and exits 1 when the file differs.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from text2anim import reproducible

reproducible.pin()  # before numpy: tests compare the shipped arrays bytewise with a fresh build, pinned alike

import numpy as np

from text2anim.motiondb.library.keyframed import ARRAYS, FPS, meta_array, records_of, sources_hash, to_planes


def contacts(records) -> dict[str, list[list]]:
    """``{name: [[side, start, stop], ...]}``: what storing each record computes (:func:`core.contacts.detect_contacts`)."""
    from text2anim.core.contacts import detect_contacts

    out = {}
    for r in records:
        fc = detect_contacts(r.motion)
        out[r.name] = [[side, a, b] for side in ("left", "right") for a, b in fc.intervals(side)]
    return out


def descriptions(records) -> dict[str, dict]:
    """``{name: description}``: what storing each record measures (:func:`motiondb.description.describe`;
    the actions come from ``actions.json`` when a database is seeded)."""
    from text2anim.motiondb.description import describe

    out = {}
    for r in records:
        d = describe(r.motion, r.core or (0.0, r.motion.duration)).to_dict()
        del d["actions"]
        out[r.name] = d
    return out


def arrays() -> dict[str, np.ndarray]:
    """The file's arrays, in order: ``_meta`` then each clip's frame planes."""
    from text2anim.motiondb.library import build_all, capture

    gone = capture.replaced()
    clips, out = [], {}
    for b in build_all(FPS):
        r = b.record
        if r.name in gone:
            continue
        m = r.motion
        assert m.translations is None and m.fps == FPS, r.name
        assert r.core is not None, r.name
        clips.append({"name": r.name, "verbs": list(r.verbs), "objects": list(r.objects),
                      "core": [float(r.core[0]), float(r.core[1])], "body_part": r.body_part,
                      "cyclic": bool(r.cyclic), "source": r.source, "start_posture": r.start_posture,
                      "end_posture": r.end_posture})
        out[r.name] = to_planes(np.concatenate([m.root_positions, m.rotations.reshape(m.n_frames, -1)], axis=1))
    meta = {"sources": sources_hash(), "fps": FPS, "clips": clips}
    # the contacts of the clips as seeded: the keyframed ones as read back from these arrays, the captured ones
    seeded = records_of(meta, out) + capture.capture_records(FPS)
    meta["contacts"] = contacts(seeded)
    meta["descriptions"] = descriptions(seeded)
    return {"_meta": meta_array(meta), **out}


def build(out: Path = ARRAYS, log=print) -> int:
    """Generate every seeded keyframed clip and write ``out``; returns its size in bytes."""
    from build_capture import write_arrays  # this folder's: run as a script, the folder is on sys.path

    data = arrays()
    size = write_arrays(out, data)
    log(f"wrote {out}: {len(data) - 1} keyframed clips, {size / 1e6:.2f} MB")
    return size


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python tools/library/build_keyframed.py",
                                description=__doc__.split("\n")[0])
    p.add_argument("--out", type=Path, default=ARRAYS, help="where to write (the package's keyframed.npz)")
    p.add_argument("--check", action="store_true", help="exit 1 when the file is not what a build gives")
    args = p.parse_args(argv)
    if not args.check:
        build(args.out)
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        fresh = Path(tmp) / "keyframed.npz"
        build(fresh, log=lambda *_: None)
        same = args.out.is_file() and args.out.read_bytes() == fresh.read_bytes()
    print(f"{args.out}: {'up to date' if same else 'differs from a fresh build: rebuild it'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
