"""Texts a hostile or unlucky user types, through the real CLI: ``python benchmarks/fuzz_text.py [--quick]``.

Each case is one ``text2anim TEXT -o …`` (or ``plan``, ``batch``) in a child process, held to the bounds of
``bounded_runs.py``: no traceback, at most 10 s of CPU and 1 GB peak resident, no raw control character
printed. The cases are the issue 41 ones (a 309-digit kanji numeral as a duration and as a delay, a
32-motion text of 223 characters, escape codes in a corpus line) and the limits of README's *Limits*
(the longest text, too many motions, a huge repeat count, control and text-direction characters).
``--quick`` leaves out the 32-motion animation (the slowest case). Exits 1 if any case fails.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from bounded_runs import table, text2anim

KU = "九" * 309
LONG = "走る。" + "3秒後に歩く。" * 31  # 220 characters, 32 motions


def cases(tmp: Path, quick: bool) -> list[tuple[str, list[str]]]:
    out = str(tmp / "a.bvh")
    corpus = tmp / "corpus.txt"
    corpus.write_text("走る。\n\x1b]0;pwned\x07歩く。\x1b[2J\n\u202e歩く。\n" + f"{KU}秒走る。\n")
    runs = [
        ("309 digits of 九 as a duration", [f"太郎は{KU}秒走る。", "-o", out]),
        ("309 digits of 九 as a delay", [f"{KU}秒後に走る。", "-o", out]),
        ("a delay of 1,000,000 s", ["走ってから一〇〇〇〇〇〇秒後に歩く。", "-o", out]),
        ("100000秒 with --max-seconds 86400", ["100000秒走る。", "--max-seconds", "86400", "-o", out]),
        ("400 digits of 9 as a repeat", ["9" * 400 + "回跳ぶ。", "-o", out]),
        ("33 motions", ["歩く。" * 33, "-o", out]),
        ("2,001 characters", ["歩" * 2001, "-o", out]),
        ("ESC in the text", ["\x1b]0;pwned\x07走る。", "-o", out]),
        ("a text-direction override", ["\u202e走る。", "-o", out]),
        ("batch: escape codes in corpus lines", ["batch", str(corpus)]),
        ("plan of 32 motions", ["plan", LONG]),
    ]
    if not quick:
        runs.append(("32 motions (a run, then 31 times 3秒後に歩く。)", [LONG, "-o", out]))
    return runs


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="leave out the 32-motion animation")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        runs = [text2anim(name, *argv_, cwd=Path(tmp), timeout=120) for name, argv_ in cases(Path(tmp), args.quick)]
    print(table(runs))
    return 1 if any(r.failures for r in runs) else 0


if __name__ == "__main__":
    sys.exit(main())
