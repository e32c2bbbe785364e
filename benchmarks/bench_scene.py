"""Benchmark of the scene: ``python benchmarks/bench_scene.py [--list] [--corpus FILE]``.

Animates every text of the scene corpus (tests/corpus/scene_corpus.jsonl, issue 45: targets, partners,
objects, interactions) with the built-in library (``--fallback nearest``: a verb the library lacks plays
its stand-in or is refused) and measures each of the line's checks on the output
(:mod:`text2anim.scene_figures`: distance to the target at the end of an approach, heading error towards
an addressee, contact-instant alignment of synchronized pairs, a held thing's distance to its hand, a
kicked or thrown thing's launch against the foot's or hand's contact, a thing put down resting on the floor
or the table, a thing looked at not held, ...). Prints one row per check:
how many pass, the median and worst figure, the limit; then the lines animated or refused, and the CPU and
wall time per line (median). ``--list`` prints every check of every line.
"""
from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT / "tests" / "corpus" / "scene_corpus.jsonl"


def load(path: Path) -> list[dict]:
    return [json.loads(x) for x in path.read_text(encoding="utf-8").splitlines() if x.startswith("{")]


def run(items: list[dict]) -> tuple[list[tuple[dict, list, str | None]], list[float], list[float]]:
    import text2anim
    from text2anim.motiondb import MotionDB
    from text2anim.scene_figures import figures

    out, cpu, wall = [], [], []
    with MotionDB.open(None) as db:
        text2anim.animate("太郎は歩く。", db=db)  # warm: the tagger, the library's clips
        for item in items:
            c0, w0 = time.process_time(), time.perf_counter()
            try:
                anim = text2anim.animate(item["text"], db=db, fallback="nearest")
            except ValueError as exc:
                out.append((item, [], f"{type(exc).__name__}: {str(exc)[:90]}"))
                continue
            figs = figures(anim, item.get("scene", []))
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
            out.append((item, figs, None))
    return out, cpu, wall


def table(results) -> list[str]:
    from text2anim.scene_figures import (AT_M, CATCH_M, CLEAR_M, FACING_DEG, FREE_M, HANDS_M, HOLD_M, LAUNCH_S,
                                         REST_M, RETURN_FRACTION, SYNC_S)

    limits = {"approach": "0.3-1.6 m", "faces": f"< {FACING_DEG:g} deg", "sync": f"< {SYNC_S:g} s",
              "holds": f"< {HOLD_M:g} m", "launch": f"<= {LAUNCH_S:g} s", "catch": f"< {CATCH_M:g} m",
              "seat": "< 0.2 m", "present": "yes", "together": f"< {SYNC_S:g} s", "leaves": "> 0.5 m",
              "behind": "> 120 deg", "reaches": "< 0.15 m", "apart": "> 0.5 m",
              "at": f"< {AT_M:g} m, facing it", "hand_in_hand": f"< {HANDS_M:g} m", "rests": f"< {REST_M:g} m",
              "free": f"> {FREE_M:g} m", "round": ">= 0.9 laps", "returns": f"< {RETURN_FRACTION:g} of the way",
              "clear": f"> {CLEAR_M:g} m"}
    by: dict[str, list] = {}
    for item, figs, err in results:
        for c in item.get("scene", []):
            by.setdefault(c["check"], [])
        for f in figs:
            by[f.check].append(f)
        if err:
            for c in item.get("scene", []):
                by[c["check"]].append(None)
    lines = [f"{'check':12} {'passed':>9} {'median':>8} {'worst':>8}  limit"]
    for check, figs in by.items():
        vals = [f.value for f in figs if f is not None and not math.isnan(f.value)]
        ok = sum(1 for f in figs if f is not None and f.passed)
        unit = next((f.unit for f in figs if f is not None), "")
        med = f"{statistics.median(vals):.3g}" if vals else "-"
        worst = f"{(min(vals) if check in ('leaves', 'behind') else max(vals)):.3g}" if vals else "-"
        lines.append(f"{check:12} {ok:>4}/{len(figs):<4} {med:>8} {worst:>8}  {limits.get(check, unit)}")
    total = sum(len(item.get("scene", [])) for item, _, _ in results)
    passed = sum(1 for _, figs, _ in results for f in figs if f.passed)
    texts_ok = sum(1 for item, figs, err in results if not err and all(f.passed for f in figs))
    lines.append(f"{'all':12} {passed:>4}/{total:<4}   texts with every check met: {texts_ok}/{len(results)}")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--corpus", type=Path, default=CORPUS)
    ap.add_argument("--list", action="store_true", help="print every check of every line")
    args = ap.parse_args(argv)
    items = load(args.corpus)
    results, cpu, wall = run(items)
    print(f"scene corpus: {len(items)} texts, {sum(len(i.get('scene', [])) for i in items)} checks "
          f"({args.corpus.relative_to(ROOT) if args.corpus.is_relative_to(ROOT) else args.corpus})")
    print("\n".join(table(results)))
    refused = [(item["text"], err) for item, _, err in results if err]
    print(f"animated {len(results) - len(refused)}/{len(results)}; per text: CPU {statistics.median(cpu):.2f} s, "
          f"wall {statistics.median(wall):.2f} s (median)")
    for text, err in refused:
        print(f"  refused: {text}  {err}")
    if args.list:
        for item, figs, err in results:
            print(item["text"])
            for f in figs:
                mark = "ok " if f.passed else "MISS"
                print(f"  {mark} {f.check:12} {f.value:8.3f} {f.unit:4} {f.note}")
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    sys.exit(main())
