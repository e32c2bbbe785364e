"""Manner words against the neutral motion (issue 40): does each style move its figure the intended way,
and does every styled output meet the quality limits?

    python benchmarks/bench_manner.py

Animates, on the built-in library in a fresh database, a 4 s walk in each of the 13 styles of
``core/styles.py`` (one manner word each), a wave 大きく / 小さく and a jump 元気よく / しょんぼり, beside the
neutral text, and prints:

1. per style, the figures of ``core/style_figures.py`` over the steady part of the walk (0.5 s from each end):
   the hips' speed (m/s), the cadence (steps/min), the step length (m), the head's height above the hips
   (m), how far the head leans ahead of the hips (m), the right hand's range (m) and the hips' bounce (cm), each with its ratio (or difference) to the
   neutral walk, and the figure the style is expected to move, with whether it moved that way;
2. per styled output, the six quality figures of motion made from the built-in library
   (``core.metrics.against_limits``: skating, root pop, jerk p99, floor penetration, frozen frames,
   floating foot) and whether it meets all of them.
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

WALK = "太郎は{}4秒間歩いた。"
#: style -> (the manner word, the figure it should move, the direction: +1 up, -1 down)
WALKS = {
    "energetic": ("元気よく", "bounce", +1), "tired": ("疲れて", "hips_speed", -1),
    "sad": ("しょんぼり", "head_height", -1), "angry": ("怒って", "hips_speed", +1),
    "proud": ("堂々と", "head_lean", -1), "timid": ("おずおずと", "step_length", -1),
    "sneaky": ("こそこそ", "head_lean", +1), "light": ("軽やかに", "bounce", +1),
    "heavy": ("ドスドス", "bounce", +1), "big": ("大股で", "step_length", +1),
    "small": ("小股で", "step_length", -1), "hurried": ("足早に", "cadence", +1),
    "relaxed": ("のんびり", "hips_speed", -1),
}
#: Other motions: (neutral text, styled text, figure, direction, hand)
OTHERS = [
    ("太郎は右手を振った。", "太郎は大きく右手を振った。", "hand_range", +1),
    ("太郎は右手を振った。", "太郎は小さく右手を振った。", "hand_range", -1),
    ("太郎は跳んだ。", "太郎は元気よく跳んだ。", "bounce", +1),
    ("太郎は座った。", "太郎はしょんぼり座った。", "head_height", -1),
]


def main() -> int:
    import text2anim
    from text2anim.core.metrics import against_limits, quality
    from text2anim.core.style_figures import style_figures
    from text2anim.motiondb import MotionDB

    t0, c0 = time.perf_counter(), time.process_time()
    with tempfile.TemporaryDirectory() as tmp, MotionDB.open(f"sqlite:///{tmp}/motions.sqlite") as db:
        def measure(text: str):
            (motion,) = text2anim.animate(text, db=db).motions.values()
            window = (0.5, motion.duration - 0.5) if motion.duration > 2.5 else None
            return style_figures(motion, window), quality(motion)

        neutral, nq = measure(WALK.format(""))
        print("## 1. A 4 s walk per style against the neutral walk\n")
        print("| style | word | hips m/s | cadence /min | step m | head above hips m | head lean m | hand range m "
              "| bounce cm | expected | moved |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
        print(f"| neutral | - | {neutral.hips_speed:.2f} | {neutral.cadence:.0f} | {neutral.step_length:.3f} "
              f"| {neutral.head_height:.3f} | {neutral.head_lean:.3f} | {neutral.hand_range:.3f} "
              f"| {100 * neutral.bounce:.2f} | | |")
        outputs = [("neutral walk", nq)]
        moved_all = True
        for style, (word, figure, sign) in WALKS.items():
            f, q = measure(WALK.format(word))
            outputs.append((f"{style} walk ({word})", q))
            moved = sign * (getattr(f, figure) - getattr(neutral, figure)) > 0
            moved_all &= moved
            cells = [f"{f.hips_speed:.2f} ({f.hips_speed / neutral.hips_speed:.2f}×)",
                     f"{f.cadence:.0f} ({f.cadence / neutral.cadence:.2f}×)",
                     f"{f.step_length:.3f} ({f.step_length / neutral.step_length:.2f}×)",
                     f"{f.head_height:.3f} ({100 * (f.head_height - neutral.head_height):+.1f} cm)",
                     f"{f.head_lean:.3f} ({100 * (f.head_lean - neutral.head_lean):+.1f} cm)",
                     f"{f.hand_range:.3f} ({f.hand_range / neutral.hand_range:.2f}×)",
                     f"{100 * f.bounce:.2f} ({f.bounce / neutral.bounce:.2f}×)"]
            print(f"| {style} | {word} | " + " | ".join(cells) + f" | {figure} {'up' if sign > 0 else 'down'} "
                  f"| {'yes' if moved else 'NO'} |")
        print("\n## 2. Other motions\n")
        print("| neutral | styled | figure | neutral | styled | moved |")
        print("| --- | --- | --- | --- | --- | --- |")
        for plain, styled, figure, sign in OTHERS:
            (a, qa), (b, qb) = measure(plain), measure(styled)
            outputs += [(plain, qa), (styled, qb)]
            moved = sign * (getattr(b, figure) - getattr(a, figure)) > 0
            moved_all &= moved
            print(f"| {plain} | {styled} | {figure} | {getattr(a, figure):.3f} | {getattr(b, figure):.3f} "
                  f"| {'yes' if moved else 'NO'} |")
        print("\n## 3. Quality of every output (limits of motion made from the built-in library)\n")
        print("| output | skating | root pop m/s² | jerk p99 m/s³ | floor cm | frozen | floating cm | meets all |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- |")
        met_all = True
        for name, q in outputs:
            meets = against_limits(q)
            met_all &= all(meets.values())
            missed = ", ".join(k for k, ok in meets.items() if not ok)
            print(f"| {name} | {q.skating_ratio:.3f} | {q.root_pop:.1f} | {q.jerk_p99:.0f} | "
                  f"{q.floor_penetration_cm:.2f} | {q.frozen_fraction:.2f} | {q.floating_cm:.1f} | "
                  f"{'yes' if not missed else 'NO: ' + missed} |")
    print(f"\nevery figure moved the intended way: {'yes' if moved_all else 'NO'}; "
          f"every output meets the limits: {'yes' if met_all else 'NO'}")
    print(f"wall {time.perf_counter() - t0:.1f} s, CPU {time.process_time() - c0:.1f} s")
    return 0 if moved_all and met_all else 1


if __name__ == "__main__":
    sys.exit(main())
