"""Joins measured the way the literature does (issue 11): CMU pairs and built-in sentences, every method.

1. **CMU pairs.** The clips of :data:`CLIPS` are cut from ``../shared/mocap/cmu/``
   (walk and run: one gait cycle each, found by ``gait_cycle``, and looped;
   the other actions: a window around the action, as ``bench_blend.py`` cuts
   them, with the core interval given; the long multi-action takes are used
   only through such a window), each cut written as a BVH file and imported
   into a temporary SQLite motion database by ``MotionDB.import_bvh`` (what
   ``text2anim db import --core ... [--cyclic]`` runs) with the verb of
   ``index.tsv``: the floor found from the foot contacts and moved to y = 0,
   clips of other subjects retargeted onto the first clip's skeleton. They are
   read back and resampled to 30 fps as the pipeline does; the sources a join is
   compared with are these imported clips. Every
   ordered pair of clips of different actions in :data:`ACTION_PAIRS` (each
   action pair once, its clips taken in turn) is joined by each method
   (optimal, constraint, pose, crossfade) through ``synthesize_with``; the time
   table follows the scheduler: after a looping motion a *transition* (the
   next clip starts at the last step of the first, ``transition_window``),
   otherwise a *connection* (it starts when the first ends).
   Each output is compared with its two source clips at 30 fps
   (:func:`core.metrics.against_sources`): skating ratio ≤ the sources' larger
   + 0.01; root pop ≤ 1.2 × the sources' larger; joint jerk p99 ≤ 1.2 × the
   sources' larger; floor penetration ≤ 1 cm; frozen frames ≤ 5 %; a foot standing on air
   (:mod:`core.floating`) ≤ the sources' larger + 2 cm. Read twice: against the clips as cut, and
   against the two sources *as the pair plays them* (:func:`played_quality`: each alone on a track,
   as long as in the pair, a looping clip looped), the reading that separates what the join adds from
   what playing a one-cycle cut as a loop shows (GMD's figure of a cycle alone is read with its 5-frame
   average zero-padded at both ends: walk07 0.091 alone, 0.202 looped for 3 s). Printed per
   method: the share of pairs meeting each criterion and all six, and how
   often optimal beats crossfade and pose on root pop, skating and jerk p99,
   read two ways side by side: on the whole output (the criteria's reading;
   its largest hips acceleration often lies in a source clip's core, which
   every method plays unchanged) and on the join's window, the figure
   ``--report`` gives per join (:func:`text2anim.quality.join_quality`: each
   method's own blend intervals ± 0.5 s, 30 fps, the same 3-frame average); and, for root pop, the
   figure each method *introduced* (:func:`text2anim.quality.introduced_root_pop`): the largest hips
   acceleration over the frames where its output is not one of its source clips as that method placed
   it (turned and moved, played verbatim; a frame counts as played when the hips are within 1 mm of
   one placed element's on it and the two frames either side, the reach of the 3-frame average and the
   second difference). It judges a method on the frames it changed — its blends, adaptation, post-pass,
   holds — and not on a kick's or a landing's own accelerations that every method plays unchanged.
2. **Built-in sentences.** The sentences of ``tests/corpus/nlp_corpus.jsonl``
   animated with the built-in library by each method, against the fixed
   thresholds of :data:`core.metrics.BUILTIN_LIMITS` (root pop ≤ 15 m/s²,
   jerk p99 ≤ 2,300 m/s³, skating ≤ 0.02, penetration ≤ 1 cm; frozen ≤ 5 %).
3. **Characters.** The corpus sentences and the scene set animated by the default engine, each output
   retargeted (as ``--rig`` does) onto a Mixamo-named A-pose glTF character the tests make
   (``tests/rig_builders.mixamo_glb``: an armature scaled by 0.01, centimetre joints) 0.2 m, 1.7 m and
   20 m tall, and measured at a person's size (:func:`core.size.at_human_size`): the same six limits,
   and the transition figures over each join's window on the frames the engine made (``--no-rigs``
   skips it).
4. **Fig. 5 speed curves** (PNG) of three pairs for each method in ``--out``.

Run: ``python benchmarks/bench_quality.py [--pairs N] [--sentences N] [--methods ...] [--out DIR]
[--json FILE] [--list]``. CPU and wall time are printed per part.
"""
from __future__ import annotations

import argparse
import csv
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))  # cmu_pairs: the CMU pairs the join tests use too
CMU = REPO.parent / "shared" / "mocap" / "cmu"
CORPUS = REPO / "tests" / "corpus" / "nlp_corpus.jsonl"
SCENES = REPO / "tests" / "corpus" / "scenes.txt"  # issue 29's own 40 scene sentences
FPS = 30.0
METHODS = ("optimal", "constraint", "pose", "crossfade")
CRITERIA = ("skating", "root_pop", "jerk", "penetration", "frozen", "floating")  # core.metrics.CRITERIA

#: name: (file stem, cut (s) or "cycle", core (s, relative to the cut)); the action is the file's label
CLIPS = {
    "walk16": ("16_15_walk", "cycle", None),
    "walk02": ("02_01_walk", "cycle", None),
    "walk07": ("07_02_walk", "cycle", None),
    "run16": ("16_35_run", "cycle", None),
    "run02": ("02_03_run", "cycle", None),
    "run127": ("127_07_run", "cycle", None),
    "kick10_03": ("10_03_kick", (0.0, 2.8), (0.7, 1.5)),
    "kick10_01": ("10_01_kick", (3.6, 6.6), (0.6, 1.8)),
    "frontkick": ("135_04_kick", (1.7, 4.0), (0.8, 1.9)),
    "jump_inplace": ("16_01_jump", (0.0, 2.6), (0.8, 1.8)),
    "jump_forward": ("16_05_jump", (0.0, 2.4), (0.8, 1.8)),
    "jump118": ("118_10_jump", (0.4, 3.0), (0.6, 1.8)),
    "punch": ("02_05_punch", (0.6, 2.4), (0.3, 1.2)),
    "lunge": ("135_09_punch", (1.4, 3.6), (0.5, 1.2)),
    "pitch": ("124_01_throw", (1.8, 5.3), (0.6, 2.2)),
    "shot": ("06_14_throw", (1.8, 4.0), (0.4, 1.5)),
    "pickup": ("02_06_pickup", (0.2, 2.6), (0.5, 1.8)),
    "dance": ("05_03_dance", (0.0, 3.6), (0.5, 3.0)),
    "dance02": ("05_02_dance", (0.5, 4.0), (0.5, 3.0)),
}
#: ordered action pairs a sentence could ask for (歩いて走る, 走ってボールを蹴る, 踊ってから歩く, ...)
ACTIONS = ("walk", "run", "jump", "kick", "throw", "punch", "pickup", "dance")
ACTION_PAIRS = [(a, b) for a in ACTIONS for b in ACTIONS if a != b]
CYCLIC_LENGTH = {"walk": 3.0, "run": 2.4}
FIG5 = (("walk", "run"), ("run", "kick"), ("dance", "walk"))  # action pairs whose speed curves are drawn


def action_of(stem: str, index: dict) -> str:
    label = index[stem]["action"]
    for a in ACTIONS:
        if a in label or (a == "throw" and "pitch" in label) or (a == "pickup" and "pick up" in label):
            return a
    raise ValueError(f"{stem}: no action for {label!r}")


def build_database(url: str, workdir: Path) -> dict:
    """Cut the clips, import them into the database at ``url`` as ``text2anim db import`` does, read them back.

    Each cut is written as a BVH file in ``workdir`` and imported by :meth:`MotionDB.import_bvh` (the
    function ``text2anim db import`` calls) with its verb, core interval and looping flag, under one
    character: every clip's floor is found from its foot contacts and moved to y = 0, and clips of other
    capture subjects are retargeted onto the first clip's skeleton. Read back at 30 fps.
    Returns ``{name: (action, ClipInfo, Clip)}``.
    """
    from text2anim.motiondb import MotionDB

    from cmu_pairs import cut_take, import_cut, read_back

    with open(CMU / "index.tsv", encoding="utf-8") as fh:
        index = {r["file"][:-4]: r for r in csv.DictReader(fh, delimiter="\t")}
    actions = {}
    with MotionDB.open(url, seed=False) as db:
        for name, (stem, cut, core) in CLIPS.items():
            m, core = cut_take(CMU / f"{stem}.bvh", cut, core)
            actions[name] = action_of(stem, index)
            import_cut(db, workdir, name, m, core, cut == "cycle", index[stem]["verb_ja"])
        return {name: (actions[name], info, clip) for name, (info, clip) in read_back(db, FPS).items()}


def pairs_of(clips: dict) -> list[tuple[str, str]]:
    """One clip pair per action pair, the clips of each action taken in turn."""
    by_action: dict[str, list[str]] = {}
    for name, (action, _, _) in clips.items():
        by_action.setdefault(action, []).append(name)
    used = {a: 0 for a in by_action}
    out = []
    for a, b in ACTION_PAIRS:
        if a in by_action and b in by_action:
            x = by_action[a][used[a] % len(by_action[a])]
            y = by_action[b][used[b] % len(by_action[b])]
            used[a] += 1
            used[b] += 1
            out.append((x, y))
    return out


def track_of(clips: dict, first: str, second: str):
    """The time table of a pair: a transition after a looping clip (the scheduler's window), else a connection."""
    from cmu_pairs import pair_track

    (act_a, ia, ca), (act_b, ib, cb) = clips[first], clips[second]
    la = CYCLIC_LENGTH.get(act_a, ca.motion.duration) if ca.cyclic else ca.motion.duration
    lb = CYCLIC_LENGTH.get(act_b, cb.motion.duration) if cb.cyclic else cb.motion.duration
    return pair_track((ia, ca), (ib, cb), (la, lb), ca.cyclic)


class Clock:
    """CPU and wall seconds of a part."""

    def __enter__(self):
        self.cpu, self.wall = time.process_time(), time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.cpu, self.wall = time.process_time() - self.cpu, time.perf_counter() - self.wall


def run_pairs(clips: dict, pairs: list, methods, smoothness: float) -> list[dict]:
    from text2anim.core.metrics import against_sources, quality
    from text2anim.quality import introduced_root_pop, join_quality
    from text2anim.synthesis.registry import synthesize_with

    rows, src_q, played_q = [], {}, {}
    for first, second in pairs:
        track = track_of(clips, first, second)
        for name in (first, second):
            if name not in src_q:
                src_q[name] = quality(clips[name][2].motion)
        sources = [src_q[first], src_q[second]]
        for method in methods:
            res = synthesize_with(method, [track], FPS, smoothness=smoothness)
            motion = res.motions[None]
            q = quality(motion)
            played = [played_quality(el, method, smoothness, played_q) for el in track.elements]
            join = join_quality(res, [track])[0]  # the figures `--report` gives for the join: its window
            rows.append({"pair": f"{first}→{second}", "actions": [clips[first][0], clips[second][0]],
                         "how": track.elements[1].method, "method": method,
                         "quality": q.to_dict(), "meets": against_sources(q, sources),
                         "sources_played": [x.to_dict() for x in played],
                         "meets_played": against_sources(q, played),
                         "join": None if join is None else {"window_s": join["window_s"], **join["join"]},
                         "introduced_root_pop": introduced_root_pop(res)[None],
                         "transitions": [] if join is None else [join["transition"]],
                         "sources": [s.to_dict() for s in sources],
                         "blend": ",".join(j.blend for j in res.joins), "_motion": motion, "_result": res})
    return rows


def played_quality(element, method: str, smoothness: float, seen: dict):
    """The quality of one source as the pair plays it, alone: the clip on a track of its own for as long as
    the pair plays it (a looping clip looped that long, by the same engine). GMD's figure of a one-cycle clip
    is read with its 5-frame average zero-padded at both ends, which hides the steps at the cut: a walk cycle
    read 0.091 alone and 0.202 looped for 3 s, the capture it was cut from stepping the same way there."""
    from text2anim.core.metrics import quality
    from text2anim.synthesis.registry import synthesize_with
    from text2anim.synthesis.tracks import Element, Track

    length = round(element.end - element.start, 6)
    key = (element.clip.name, length, method)
    if key not in seen:
        alone = Track(None, (Element(1, element.clip, 0.0, length, "initial"),))
        seen[key] = quality(synthesize_with(method, [alone], FPS, smoothness=smoothness).motions[None])
    return seen[key]


def run_sentences(texts: list[str], methods, db_url: str, rigs: dict | None = None) -> tuple[list[dict], list[dict]]:
    """Rows per sentence, actor and method; and with ``rigs`` (:func:`characters`) the rows of the default
    engine's animation of each sentence on those characters (:func:`rig_rows`), from the same animation."""
    import text2anim
    from text2anim.core.metrics import against_limits, quality
    from text2anim.motiondb import MotionDB
    from text2anim.quality import join_quality

    rows: list[dict] = []
    rigged: list[dict] = []
    with MotionDB.open(db_url) as db:
        for text in texts:
            for method in list(methods) + ([] if rigs is None or DEFAULT in methods else [DEFAULT]):
                try:
                    anim = text2anim.animate(text, db=db, blend=method)
                except Exception as exc:  # an unknown verb, a refused sentence: not animated
                    if getattr(exc, "user_facing", False):
                        break
                    raise
                if rigs is not None and method == DEFAULT:
                    rigged += rig_rows(text, anim, rigs)
                if method not in methods:
                    continue
                joins = join_quality(anim.result)
                for actor, m in anim.motions.items():
                    q = quality(m)
                    mine = [e["transition"] for j, e in zip(anim.result.joins, joins)
                            if e is not None and anim.result.actor_of(j.second) == actor]
                    rows.append({"text": text, "actor": actor, "method": method, "quality": q.to_dict(),
                                 "meets": against_limits(q), "transitions": mine})
    return rows, rigged


#: the engine text2anim uses when none is asked for: the one the characters section exports
DEFAULT = "optimal"
#: heights (m) of the Mixamo-named A-pose characters the sentences are retargeted onto
RIG_HEIGHTS = (0.2, 1.7, 20.0)


def characters(tmp: Path) -> dict:
    """``{height: ExportOptions}``: a Mixamo-named A-pose character of each of :data:`RIG_HEIGHTS` (m), written
    into ``tmp``."""
    from rig_builders import mixamo_glb
    from text2anim.export import ExportOptions

    return {h: ExportOptions(rig=mixamo_glb(tmp / f"mixamo_{h}.glb", scale=h / 1.7)) for h in RIG_HEIGHTS}


def rig_rows(text: str, anim, rigs: dict) -> list[dict]:
    """Rows as :func:`run_sentences` gives, ``method`` naming the character (``rig 0.2 m``): ``anim``
    retargeted onto each character of ``rigs`` (:func:`characters`), measured at a person's size. The
    transition figures are read on the frames the engine made (found on its own skeleton: retargeting keeps
    every frame where it is)."""
    from text2anim.core.metrics import against_limits
    from text2anim.quality import exported_figures

    rows = []
    for h, export in rigs.items():
        figures = exported_figures(anim.result, anim.exported_motions(export, units=False))
        for actor, (q, mine) in figures.items():
            rows.append({"text": text, "actor": actor, "method": f"rig {h:g} m", "quality": q.to_dict(),
                         "meets": against_limits(q), "transitions": mine})
    return rows


def share_table(rows: list[dict], methods, title: str, four: bool = False) -> None:
    """Per method, the share of rows meeting each criterion and all six (and, with ``four``, all but frozen:
    the list issue 11 gives for built-in sentences)."""
    print(f"\n{title}")
    print(f"{'method':11} {'n':>4} " + " ".join(f"{c:>11}" for c in CRITERIA) + f" {'all six':>9}"
          + (f" {'all but frozen':>15}" if four else ""))
    for m in methods:
        mine = [r for r in rows if r["method"] == m]
        n = len(mine)
        if not n:
            continue
        cells = [f"{100 * sum(r['meets'][c] for r in mine) / n:10.0f}%" for c in CRITERIA]
        ok = 100 * sum(all(r["meets"].values()) for r in mine) / n
        ok4 = 100 * sum(all(v for c, v in r["meets"].items() if c != "frozen") for r in mine) / n
        print(f"{m:11} {n:4d} " + " ".join(cells) + f" {ok:8.0f}%" + (f" {ok4:14.0f}%" if four else ""))
    gmd_line(rows, methods)


def gmd_line(rows: list[dict], methods) -> None:
    """Per method, the share of rows whose skating as GMD measures it (above the motion's lowest foot point)
    is within what the shared capture reaches (:data:`core.metrics.CAPTURE_GMD_LIMIT`) and, for a join, within
    its sources' larger + 0.01; a join whose larger source is itself over the capture's limit (a user's
    capture: CMU 02_01's walk cycle looped reads 0.36) is held to that source + 0.01, as a library clip is
    held to its cut (``tests/motiondb/test_clip_quality.py``)."""
    from text2anim.core.metrics import CAPTURE_GMD_LIMIT, SKATING_MARGIN

    cells = []
    for m in methods:
        mine = [r for r in rows if r["method"] == m]
        if mine:
            ok = []
            for r in mine:
                src = max([q["skating_gmd"] for q in r.get("sources", [])], default=None)
                limit = (CAPTURE_GMD_LIMIT if src is None else src + SKATING_MARGIN if src > CAPTURE_GMD_LIMIT
                         else min(CAPTURE_GMD_LIMIT, src + SKATING_MARGIN))
                ok.append(r["quality"]["skating_gmd"] <= limit)
            cells.append(f"{m} {sum(ok)}/{len(ok)}")
    print(f"  GMD's skating (its floor) <= {CAPTURE_GMD_LIMIT} (capture) and, for a join, <= its sources' + "
          f"{SKATING_MARGIN}: " + ", ".join(cells))


def transition_table(rows: list[dict], methods, what: str) -> None:
    """Per method, over every join of ``rows``: the share within capture's balance and glide limits
    (core.balance, core.glide, on the frames the method made) and the worst of each."""
    from text2anim.core.balance import LIMIT_CM
    from text2anim.core.glide import LIMIT_S

    from text2anim.core import hang

    print(f"  transitions of {what} (frames no source plays as recorded): balance <= {LIMIT_CM} cm, glide <= {LIMIT_S} s, "
          f"hang in the air <= {hang.LIMIT_S} s")
    for m in methods:
        ts = [t for r in rows if r["method"] == m for t in r.get("transitions", [])]
        if not ts:
            continue
        n = len(ts)
        print(f"  {m:11} {n:4d} joins  balance {100 * sum(t['meets']['balance'] for t in ts) / n:4.0f}% "
              f"(max {max(t['balance_cm'] for t in ts):5.1f} cm)  glide {100 * sum(t['meets']['glide'] for t in ts) / n:4.0f}% "
              f"(max {max(t['glide_s'] for t in ts):4.2f} s)  hang {100 * sum(t['meets']['hang'] for t in ts) / n:4.0f}% "
              f"(max {max(t['hang_s'] for t in ts):4.2f} s)")


def median_table(rows: list[dict], methods) -> None:
    keys = ("skating_ratio", "skating_gmd", "root_pop", "jerk_p99", "floor_penetration_cm", "frozen_fraction",
            "floating_cm")
    print(f"{'method':11} " + " ".join(f"{k:>21}" for k in ("skating", "GMD's skating", "root pop m/s2", "jerk p99 m/s3",
                                                            "penetration cm", "frozen", "floating cm")) + "   (median / max)")
    for m in methods:
        mine = [r["quality"] for r in rows if r["method"] == m]
        if mine:
            cells = [f"{np.median([q[k] for q in mine]):10.3g} /{max(q[k] for q in mine):9.3g}" for k in keys]
            print(f"{m:11} " + " ".join(cells))


def beats_table(rows: list[dict]) -> None:
    """How often optimal beats, ties and loses to crossfade and pose, per pair, on two readings side by side.

    *whole output*: the figures of the whole joined motion (the criteria's reading). Its largest hips
    acceleration often lies inside a source clip's core, which every method plays unchanged: a tie there
    says nothing about the join. *join window*: the same figures over the join's window only, each
    method's own blend intervals widened by ``JOIN_MARGIN`` (0.5 s) either side, at 30 fps after the
    same 3-frame moving average (:func:`text2anim.quality.join_quality`, what ``--report`` prints per
    join): where the methods differ.
    """
    by = {(r["pair"], r["method"]): r["quality"] for r in rows}
    by_join = {(r["pair"], r["method"]): r["join"] for r in rows if r.get("join") is not None}
    by_own = {(r["pair"], r["method"]): r["introduced_root_pop"] for r in rows
              if r.get("introduced_root_pop") is not None}
    pairs = sorted({r["pair"] for r in rows if (r["pair"], "optimal") in by})
    print("\noptimal against the baselines, per pair (lower is better; 'ties' counts equal figures)")
    print("  whole output: the figure of the whole joined motion; join window: over each method's own join "
          "window (blend intervals ± 0.5 s, as --report gives per join);")
    print("  introduced: root pop over the frames each method changed (not its source clips' own as placed, "
          "the 3-frame average's reach included)")
    print(f"{'against':10} {'figure':14} {'whole output: beats':>20} {'ties':>5} {'worse':>6}   "
          f"{'join window: beats':>19} {'ties':>5} {'worse':>6}   {'introduced: beats':>18} {'ties':>5} "
          f"{'worse':>6} {'n':>4}")

    def counts(both: list[tuple[float, float]]) -> tuple[int, int, int]:
        b = sum(o < x - 1e-9 for o, x in both)
        t = sum(abs(o - x) <= 1e-9 for o, x in both)
        return b, t, len(both) - b - t

    for other in ("crossfade", "pose"):
        for key, label in (("root_pop", "root pop"), ("skating_ratio", "skating"), ("jerk_p99", "jerk p99")):
            both = [(by[p, "optimal"][key], by[p, other][key]) for p in pairs if (p, other) in by]
            if not both:
                continue
            b, t, w = counts(both)
            jb = [(by_join[p, "optimal"][key], by_join[p, other][key]) for p in pairs
                  if (p, "optimal") in by_join and (p, other) in by_join]
            cells = "{:19d} {:5d} {:6d}".format(*counts(jb)) if jb else f"{'-':>19} {'-':>5} {'-':>6}"
            ib = [(by_own[p, "optimal"], by_own[p, other]) for p in pairs
                  if key == "root_pop" and (p, "optimal") in by_own and (p, other) in by_own]
            own = "{:18d} {:5d} {:6d}".format(*counts(ib)) if ib else f"{'-':>18} {'-':>5} {'-':>6}"
            print(f"{other:10} {label:14} {b:20d} {t:5d} {w:6d}   {cells}   {own} {len(both):4d}")
    decided_table(by_own, pairs)


#: m/s²: the introduced root pops of two methods closer than this are a tie (issue 29's decision)
DECIDED = 0.5


def decided_table(by_own: dict, pairs: list[str]) -> None:
    """Issue 29's decided reading: over the pairs where optimal's introduced root pop and a baseline's differ
    by more than :data:`DECIDED` m/s², the share optimal beats (the target: 90 % against each baseline)."""
    for other in ("crossfade", "pose"):
        both = [(by_own[p, "optimal"], by_own[p, other]) for p in pairs
                if (p, "optimal") in by_own and (p, other) in by_own]
        apart = [(o, x) for o, x in both if abs(o - x) > DECIDED]
        if apart:
            won = sum(o < x for o, x in apart)
            print(f"  introduced root pop, decided (pairs differing by more than {DECIDED} m/s2): optimal beats "
                  f"{other} on {won} of {len(apart)} ({100 * won / len(apart):.0f} %; target 90 %)")


def failing(rows: list[dict], method: str) -> None:
    bad = [r for r in rows if r["method"] == method and not all(r["meets"].values())]
    print(f"\n{method}: pairs that miss a criterion ({len(bad)}): figure (sources' larger)")
    for r in bad:
        q, s = r["quality"], r["sources"]
        worst = {k: max(x[k] for x in s) for k in ("skating_ratio", "root_pop", "jerk_p99", "floating_cm")}
        miss = [c for c, ok in r["meets"].items() if not ok]
        print(f"  {r['pair']:26} {r['how']:10} {','.join(miss):32} skate {q['skating_ratio']:.3f} "
              f"({worst['skating_ratio']:.3f}) pop {q['root_pop']:5.1f} ({worst['root_pop']:4.1f}) "
              f"jerk {q['jerk_p99']:5.0f} ({worst['jerk_p99']:4.0f}) floor {q['floor_penetration_cm']:.1f} "
              f"frozen {q['frozen_fraction']:.2f} floating {q['floating_cm']:.1f} ({worst['floating_cm']:.1f})")


def join_losses(rows: list[dict]) -> None:
    """The pairs on which optimal does not beat crossfade or pose on the join window's root pop, with each
    method's window (s): a longer window holds more of the clips' own motion (a kick, a landing); and those
    it does not beat on the root pop it introduced, with each method's figure."""
    by = {(r["pair"], r["method"]): r for r in rows if r.get("join") is not None}
    pairs = sorted({p for p, m in by if m == "optimal"})
    print("\noptimal: pairs not beating a baseline on the join window's root pop (m/s2, window s)")
    for p in pairs:
        o = by[p, "optimal"]
        others = [(m, by[p, m]["join"]) for m in ("crossfade", "pose") if (p, m) in by]
        if not any(o["join"]["root_pop"] >= j["root_pop"] - 1e-9 for _, j in others):
            continue
        cells = " ".join(f"{m} {j['root_pop']:5.1f} {j['window_s']}" for m, j in others)
        print(f"  {p:26} {o['blend']:24} optimal {o['join']['root_pop']:5.1f} {o['join']['window_s']} {cells}")
    print("\noptimal: pairs not beating a baseline on the root pop it introduced (m/s2)")
    for p in pairs:
        o = by[p, "optimal"]["introduced_root_pop"]
        others = [(m, by[p, m]["introduced_root_pop"]) for m in ("crossfade", "pose") if (p, m) in by]
        if o is None or not any(x is not None and o >= x - 1e-9 for _, x in others):
            continue
        cells = " ".join(f"{m} {x:5.1f}" for m, x in others if x is not None)
        print(f"  {p:26} {by[p, 'optimal']['blend']:24} optimal {o:5.1f} {cells}")


def plot_fig5(rows: list[dict], out: Path) -> list[Path]:
    from text2anim.output.plots import plot_speeds
    from text2anim.output.viewer.types import Span

    written = []
    for r in rows:
        if (r["actions"][0], r["actions"][1]) not in FIG5:
            continue
        res = r["_result"]
        spans = [Span("default", f"{j.first}→{j.second} {iv.kind}", iv.begin, iv.end, "blend", iv.part)
                 for j in res.joins for iv in j.intervals if iv.end > iv.begin]
        path = out / f"fig5_{r['pair'].replace('→', '_to_')}_{r['method']}.png"
        plot_speeds({r["method"]: r["_motion"]}, path, spans, title=f"{r['pair']} ({r['method']}, {r['how']})")
        written.append(path)
    return written


def corpus_texts(n: int | None) -> list[str]:
    from text2anim.cli.batch.corpus import load_corpus

    items = [i for i in load_corpus(str(CORPUS)) if "error" not in (i.expect or {})]
    texts = list(dict.fromkeys(i.text for i in items))
    return texts if n is None else texts[:n]


def scene_texts() -> list[str]:
    """The scene set: one sentence a line, ``#`` lines are comments."""
    return [t for t in (line.strip() for line in SCENES.read_text(encoding="utf-8").splitlines())
            if t and not t.startswith("#")]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pairs", type=int, default=None, help="only the first N CMU pairs (default all)")
    ap.add_argument("--sentences", type=int, default=None, help="only the first N corpus sentences (default all)")
    ap.add_argument("--methods", default=",".join(METHODS), help="comma-separated methods (default all four)")
    ap.add_argument("--smoothness", type=float, default=0.5)
    ap.add_argument("--out", default="bench_quality_out", help="folder for the Fig. 5 PNGs (default %(default)s)")
    ap.add_argument("--json", help="write every figure to this file")
    ap.add_argument("--list", action="store_true", help="also list the failing pairs and sentences")
    ap.add_argument("--no-rigs", action="store_true", help="skip the characters of other rigs and sizes")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    methods = [m for m in args.methods.split(",") if m]
    if not CMU.is_dir():
        print(f"no CMU clips at {CMU}", file=sys.stderr)
        return 2
    from text2anim.synthesis.registry import METHODS as KNOWN

    if bad := [m for m in methods if m not in KNOWN]:
        print(f"unknown method(s) {','.join(bad)}; choose from {','.join(KNOWN)}", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        with Clock() as c_db:
            clips = build_database(f"sqlite:///{tmp}/cmu.sqlite", Path(tmp))
        pairs = pairs_of(clips)[:args.pairs]
        with Clock() as c_pairs:
            rows = run_pairs(clips, pairs, methods, args.smoothness)
        texts = corpus_texts(args.sentences)
        rigs = None if args.no_rigs else characters(Path(tmp))
        rigged: dict[str, list[dict]] = {}
        with Clock() as c_sent:
            sent, rigged["corpus"] = run_sentences(texts, methods, f"sqlite:///{tmp}/library.sqlite", rigs)
        with Clock() as c_scene:
            scenes, rigged["scenes"] = run_sentences(scene_texts(), methods, f"sqlite:///{tmp}/library.sqlite", rigs)
        if rigs is None:
            rigged = {}
    print(f"CMU: {len(clips)} clips imported ({c_db.cpu:.1f} s CPU, {c_db.wall:.1f} s wall); {len(pairs)} pairs "
          f"x {len(methods)} methods; all figures at 30 fps")
    share_table(rows, methods, "CMU pairs: share meeting each criterion against their two source clips")
    as_played = [dict(r, meets=r["meets_played"], sources=r["sources_played"]) for r in rows]
    share_table(as_played, methods, "CMU pairs against their two sources as the pair plays them (each alone, as "
                                    "long as in the pair: a looping clip looped)")
    median_table(rows, methods)
    transition_table(rows, methods, "the CMU pairs")
    if "optimal" in methods:
        beats_table(rows)
    print(f"(pairs: {c_pairs.cpu:.1f} s CPU, {c_pairs.wall:.1f} s wall)")
    if sent:
        n_texts = len({r["text"] for r in sent})
        share_table(sent, methods, f"built-in library: {n_texts} corpus sentences, share of animations meeting "
                                   "root pop <= 15 m/s2, jerk p99 <= 2300 m/s3, skating <= 0.02, floor <= 1 cm, "
                                   "frozen <= 5 %", four=True)
        median_table(sent, methods)
        transition_table(sent, methods, "the corpus sentences")
        print(f"(sentences: {c_sent.cpu:.1f} s CPU, {c_sent.wall:.1f} s wall)")
    n_scenes = len({r["text"] for r in scenes})
    share_table(scenes, methods, f"scene set (tests/corpus/scenes.txt): {n_scenes} sentences, the same limits "
                                 "and floating <= 10 cm", four=True)
    median_table(scenes, methods)
    transition_table(scenes, methods, "the scene set")
    print(f"(scenes: {c_scene.cpu:.1f} s CPU, {c_scene.wall:.1f} s wall)")
    labels = [f"rig {h:g} m" for h in RIG_HEIGHTS]
    for name, these in rigged.items():
        what = "the corpus sentences" if name == "corpus" else "the scene set"
        share_table(these, labels, f"{what} on a Mixamo-named A-pose character of {', '.join(f'{h:g}' for h in RIG_HEIGHTS)} m "
                                   "(retargeted as --rig does; measured at a person's size)", four=True)
        median_table(these, labels)
        transition_table(these, labels, what)
    if rigged:
        print("(the characters' figures are timed with the sentences and scenes they export)")
    if args.list:
        for m in methods:
            failing(rows, m)
            print("  ... against their sources as played:")
            failing([dict(r, meets=r["meets_played"], sources=r["sources_played"]) for r in rows], m)
        if "optimal" in methods:
            join_losses(rows)
        every = sent + scenes + [r for these in rigged.values() for r in these]
        for m in methods + (labels if rigged else []):
            bad = [r for r in every if r["method"] == m and not all(r["meets"].values())]
            print(f"\n{m}: built-in sentences that miss a threshold ({len(bad)})")
            for r in bad:
                q = r["quality"]
                miss = [c for c, ok in r["meets"].items() if not ok]
                print(f"  {r['text']} [{r['actor']}] {','.join(miss)}: skate {q['skating_ratio']:.3f} pop "
                      f"{q['root_pop']:.1f} jerk {q['jerk_p99']:.0f} floor {q['floor_penetration_cm']:.1f} "
                      f"frozen {q['frozen_fraction']:.2f} floating {q['floating_cm']:.1f}")
            over = [(r, t) for r in every if r["method"] == m for t in r.get("transitions", [])
                    if not all(t["meets"].values())]
            print(f"{m}: built-in sentences' joins over a transition limit ({len(over)})")
            for r, t in over:
                print(f"  {r['text']} [{r['actor']}] balance {t['balance_cm']:.1f} cm, glide {t['glide_s']:.2f} s, "
                      f"hang {t['hang_s']:.2f} s")
    out = Path(args.out)
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("Fig. 5 curves need text2anim[plot] (matplotlib); skipped", file=sys.stderr)
    else:
        out.mkdir(parents=True, exist_ok=True)
        written = plot_fig5(rows, out)
        print(f"\nFig. 5 speed curves: {len(written)} PNGs in {out}/")
    print(f"total: {time.process_time():.1f} s CPU, {time.perf_counter() - t0:.1f} s wall")
    if args.json:
        doc = {"pairs": [{k: v for k, v in r.items() if not k.startswith("_")} for r in rows], "sentences": sent, "scenes": scenes,
               **{f"{name}_on_rigs": these for name, these in rigged.items()}}
        Path(args.json).write_text(json.dumps(doc, ensure_ascii=False, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
