"""Everyday action verbs against the motion library: clip, accepted fallback by meaning, or nothing.

Source of the verb list: the JLPT N5, N4 and N3 vocabulary lists of
jamsinclair/open-anki-jlpt-decks (src/n5.csv, n4.csv, n3.csv; MIT, after the
tanos.co.uk lists), verbs only ("to ..." entries), kept when the verb names a
visible bodily action a character could act out (states, mental, weather,
speech-only and commercial verbs left out: ある, 分かる, 曇る, 買う, ...).
Nothing here comes from the project's corpus.

For each verb: (a) the built-in library has a clip for it, found as the planner
finds it (``clip_search.DatabaseClips``: the verb as written, its lemma, a kana verb's
reading) and declaring that verb: its own verbs, or a near-synonym of
``motiondb/library/near.json``, where each carries the reason it is accepted (a
clip found only through the sound of another word, 吹く -> 拭く, counts as (h),
with neither share); else the stand-in ``--fallback nearest`` plays (``text2anim.fallback``:
a clip that does what the verb means, by WordNet through JMdict and by the word vectors),
and JUDGE holds my judgement as a native-level reader whether that stand-in is
acceptable (True) or not (False); (c) nothing: no clip and no verb near enough.
Usage: python benchmarks/bench_vocab.py [--list]
"""
from __future__ import annotations

import sys
import tempfile
import time

VERBS = """
開く 開ける 上げる 遊ぶ 浴びる 洗う 歩く 行く 歌う 起きる 置く 押す 泳ぐ 降りる 帰る 書く かぶる 切る 着る
来る 閉める 吸う 座る 出す 立つ 食べる 出る 飛ぶ 止まる 取る 並ぶ 脱ぐ 寝る 登る 飲む 乗る 入る 走る 引く
吹く 待つ 見る 持つ 休む 読む 渡す 渡る 踏む 折る 壊す 拾う 噛む 触る 捕まえる 逃げる 投げる 泣く 立てる
踊る 探す 進む 喜ぶ 打つ 滑る 下りる 笑う 運ぶ 集める 落とす 倒れる 向かう 急ぐ 戻る 下げる 眠る 上がる
入れる 消す 掛ける 磨く 締める 返す 並べる 釣る 焼く 塗る 飾る 包む 植える 片付ける 手伝う 騒ぐ 動く 通る
止める 起こす 謝る 見つける 祈る 驚く 怒る 呼ぶ 弾く 貼る 撮る 見せる 迎える 話す
抱く 抱える 叩く 畳む 立ち上がる 殴る 握る 掴む 振る 震える 伸ばす 拭く 掃く 吐く 蹴る 転ぶ 叫ぶ 覗く
眺める 隠れる 隠す 避ける 押さえる 持ち上げる 広げる 引っ張る 戦う 駆ける 溺れる 微笑む 組む 積む 注ぐ
混ぜる 刺す 巻く 破る 割る 結ぶ 抜く 外す 乗せる 降ろす 流す 刈る 掻く 嗅ぐ 越える 数える 倒す 触れる
擦る 受け取る 指す 閉じる 飛び出す 散らす 繋ぐ 沈む
""".split()

#: My judgement of each fallback: verb -> (the stand-in a run of this script chose, would a
#: native speaker accept that stand-in as the animation of the verb?).  A verb whose
#: stand-in has since changed counts as not accepted until judged again ("unjudged").
#: Empty since issue 27: the stand-ins judged acceptable here before (降りる, 滑る, 騒ぐ, 見つける,
#: 伸ばす, 刈る, 越える) became near-synonyms of their clips (near.json), the rule that picked the
#: seven judged wrong (泳ぐ -> 潜る, ...) is gone, and none of the 12 left has a stand-in now;
#: stand-ins are judged on tests/corpus/standin_set.json (benchmarks/bench_standins.py).
#: Issue 39 (clips described by more of what their bodies do, JMdict read further): 流す
#: ("to drain; to pour") plays the pour clip, as 水を流す pours water out: accepted.
JUDGE: dict[str, tuple[str, bool]] = {"流す": ("注ぐ", True)}


def classify(db) -> list[tuple[str, str, str, float | None]]:
    """(verb, class, clip or stand-in, cosine) per verb: a clip, b accepted fallback, x fallback
    judged wrong, u fallback not judged (stand-in changed), h a clip found only by the verb's
    reading (another word of the same sound: counted with neither), c nothing."""
    from text2anim.motiondb import UnknownVerbError
    from text2anim.fallback import find_stand_in
    from text2anim.nlp.analyze import analyze
    from text2anim.clip_search import DatabaseClips

    clips = db.clips()
    finder = DatabaseClips(db)  # the planner's own search: as written, lemma, then reading
    out = []
    for verb in VERBS:
        spec = analyze(verb + "。").motions[0]
        try:
            hit = finder.search(spec, None)
        except UnknownVerbError:
            hit = []
        if hit:
            declared = {spec.verb, spec.written, verb} & set(hit[0].verbs)
            out.append((verb, "a" if declared else "h", hit[0].name, None))
            continue
        standin, _ = find_stand_in(spec.verb, clips)
        if standin is None:
            out.append((verb, "c", "", None))
            continue
        used, score = standin.verb, standin.score
        judged = JUDGE.get(verb)
        cls = "u" if judged is None or judged[0] != used else ("b" if judged[1] else "x")
        out.append((verb, cls, used, score))
    return out


def main(argv: list[str]) -> int:
    from text2anim.motiondb import MotionDB

    t0, c0 = time.perf_counter(), time.process_time()
    with tempfile.TemporaryDirectory() as tmp, MotionDB.open(f"{tmp}/lib.sqlite") as db:
        rows = classify(db)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    if "--list" in argv:
        for verb, cls, used, score in rows:
            print(f"{verb}\t{cls}\t{used}\t{'' if score is None else f'{score:.2f}'}")
    n = len(rows)
    count = {k: sum(1 for r in rows if r[1] == k) for k in "abxcuh"}
    print(f"{n} everyday action verbs (JLPT N5/N4/N3 lists, bodily actions)")
    print("| class | verbs | share |")
    print("| --- | ---: | ---: |")
    for k, label in (("a", "(a) has a clip"), ("b", "(b) fallback a native speaker accepts"),
                     ("c", "(c) nothing (no clip, nothing near in meaning)"),
                     ("x", "    fallback judged wrong (counted with neither)"),
                     ("u", "    fallback not judged yet (counted with neither)"),
                     ("h", "    clip of a homophone only (counted with neither)")):
        print(f"| {label} | {count[k]} | {100 * count[k] / n:.1f} % |")
    print(f"(a)+(b) = {100 * (count['a'] + count['b']) / n:.1f} %   wall {wall:.1f} s, CPU {cpu:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
