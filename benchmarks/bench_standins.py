"""Stand-ins for verbs the library lacks: right, wrong or refused, now and with the vectors alone.

``python benchmarks/bench_standins.py [--list]``

The set is ``tests/corpus/standin_set.json``: verbs with no clip, each with the built-in clips a
person accepts in their place (judged on the clips' contact sheets), and verbs nothing may stand
in for. Each verb is planned as a user would run it (``text2anim.plan(VERB + "。",
fallback="nearest")`` on a fresh built-in database) and the clip the time table plays is judged:

- **right**: an accepted clip (or a captured variant of one) plays;
- **wrong**: another clip plays; for a verb of the ``refuse`` list, any clip;
- **refused**: the clear "no clip ... no stand-in" error.

The second column replays the previous rule (the database verb nearest by chiVe vectors, cosine
>= ``meaning.MIN_SIMILARITY`` and among the verb's ``meaning.MAX_RANK`` nearest words) on the same
verbs, planned the same way. Timing: wall and CPU seconds of the whole run.
"""
from __future__ import annotations

import json
import re
import sys
import tempfile
import time
from pathlib import Path

CORPUS = Path(__file__).resolve().parent.parent / "tests" / "corpus"
SETS = (CORPUS / "standin_set.json", CORPUS / "standin_unseen.json")


def judged_set(path: Path = SETS[0]) -> tuple[dict[str, list[str]], dict[str, str]]:
    """``(acceptable clips by verb, why by verb to refuse)`` of the stand-in set at ``path``."""
    data = json.loads(path.read_text(encoding="utf-8"))
    return data["acceptable"], data["refuse"]


def base(clip: str) -> str:
    """A captured variant's base clip (``walk_02_01`` -> ``walk``)."""
    return re.sub(r"(_\d+)+$", "", clip)


def played_now(verb: str, db) -> str | None:
    """The clip ``--fallback nearest`` plays for ``verb`` today, or None when it refuses."""
    import text2anim
    from text2anim.motiondb import UnknownVerbError

    try:
        return text2anim.plan(verb + "。", db, fallback="nearest").table.elements[0].clip
    except UnknownVerbError:
        return None


def played_before(verb: str, db) -> str | None:
    """The clip the vectors-only rule (before issue 27's stand-ins) played for ``verb``."""
    from dataclasses import replace

    from text2anim.clip_search import DatabaseClips
    from text2anim.motiondb import UnknownVerbError
    from text2anim.nlp import analyze, meaning

    spec = analyze(verb + "。").motions[0]
    near = meaning.nearest(spec.verb, [v.lemma for v in db.verbs()], n=1, floor=meaning.MIN_SIMILARITY,
                           within=meaning.MAX_RANK)
    if not near:
        return None
    try:
        hits = DatabaseClips(db).search(replace(spec, verb=near[0][0], reading="", written=""), None)
    except UnknownVerbError:
        return None
    return hits[0].name if hits else None


def judge(clip: str | None, accepted: list[str] | None) -> str:
    """``right``, ``wrong`` or ``refused``; ``accepted`` None: a verb nothing may stand in for."""
    if clip is None:
        return "refused"
    return "right" if accepted is not None and base(clip) in accepted else "wrong"


def score(db, play, path: Path = SETS[0]) -> tuple[dict, dict, list]:
    """Counts over the acceptable verbs and over the refuse verbs of the set at ``path``, and the rows
    (verb, clip, verdict)."""
    acceptable, refuse = judged_set(path)
    rows = []
    for verb, accepted in acceptable.items():
        clip = play(verb, db)
        rows.append((verb, clip, judge(clip, accepted), True))
    for verb in refuse:
        clip = play(verb, db)
        rows.append((verb, clip, judge(clip, None), False))
    counts = {True: {"right": 0, "wrong": 0, "refused": 0}, False: {"right": 0, "wrong": 0, "refused": 0}}
    for _, _, verdict, has in rows:
        counts[has][verdict] += 1
    return counts[True], counts[False], rows


def main(argv: list[str]) -> int:
    paths = [Path(a) for a in argv if not a.startswith("--")] or list(SETS)
    for path in paths:
        table(path, "--list" in argv)
    return 0


def table(path: Path, listing: bool) -> None:
    """Print the scores of the set at ``path`` (and each verb's verdict with ``listing``)."""
    from text2anim.motiondb import MotionDB

    t0, c0 = time.perf_counter(), time.process_time()
    with tempfile.TemporaryDirectory() as tmp, MotionDB.open(f"{tmp}/lib.sqlite") as db:
        now = score(db, played_now, path)
        before = score(db, played_before, path)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    acceptable, refuse = judged_set(path)
    n, m = len(acceptable), len(refuse)
    print(f"{path.name}: {n} verbs with an acceptable clip, {m} verbs nothing may stand in for")
    print("| verbs | verdict | vectors only (before) | lexicon + vectors (now) |")
    print("| --- | --- | ---: | ---: |")
    for has, total, label in ((True, n, "with a stand-in"), (False, m, "to refuse")):
        for verdict in ("right", "wrong", "refused"):
            if not has and verdict == "right":
                continue
            b, a = before[0 if has else 1][verdict], now[0 if has else 1][verdict]
            print(f"| {label} | {verdict} | {b} ({100 * b / total:.0f} %) | {a} ({100 * a / total:.0f} %) |")
    print(f"wall {wall:.1f} s, CPU {cpu:.1f} s (both rules, {n + m} verbs each)")
    if listing:
        for (verb, clip, verdict, _), (_, old, old_verdict, _) in zip(now[2], before[2]):
            print(f"{verb}\t{clip or '-'}\t{verdict}\t(before: {old or '-'} {old_verdict})")
    print()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
