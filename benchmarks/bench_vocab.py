"""Everyday action verbs against the motion library: clip, accepted fallback by meaning, or nothing.

Source of the verb list: the JLPT N5, N4 and N3 vocabulary lists of
jamsinclair/open-anki-jlpt-decks (src/n5.csv, n4.csv, n3.csv; MIT, after the
tanos.co.uk lists), verbs only ("to ..." entries), kept when the verb names a
visible bodily action a character could act out (states, mental, weather,
speech-only and commercial verbs left out: ある, 分かる, 曇る, 買う, ...).
Nothing here comes from the project's corpus.

For each verb: (a) the built-in library has a clip for it (by lemma, synonym or
reading, as the planner searches); else the nearest library verb by meaning
(``nlp.meaning``: cosine >= MIN_SIMILARITY and among the verb's MAX_RANK nearest
vectors) is what ``--fallback nearest`` plays,
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
JUDGE: dict[str, tuple[str, bool]] = {
    "開く": ("押す", False),  # 0.57: no, a different action
    "遊ぶ": ("散歩する", False),  # 0.65: no, a different action
    "浴びる": ("帰る", False),  # 0.45: no, a different action
    "洗う": ("下ろす", False),  # 0.47: no, a different action
    "歌う": ("踊る", False),  # 0.76: no, a different action
    "泳ぐ": ("はしゃぐ", False),  # 0.54: no, a different action
    "降りる": ("向かう", True),  # 0.77: yes, going down on foot is walked
    "書く": ("見る", False),  # 0.61: no, a different action
    "かぶる": ("取る", False),  # 0.49: no, a different action
    "切る": ("指す", False),  # 0.62: no, a different action
    "着る": ("踊る", False),  # 0.49: no, a different action
    "閉める": ("引っ張る", False),  # 0.56: no, a different action
    "吸う": ("放る", False),  # 0.51: no, a different action
    "出す": ("引く", False),  # 0.66: no, a different action
    "食べる": ("帰る", False),  # 0.57: no, a different action
    "出る": ("来る", True),  # 0.75: yes, leaving a room is walked
    "並ぶ": ("置く", False),  # 0.61: no, a different action
    "脱ぐ": ("しゃがむ", False),  # 0.59: no, a different action
    "寝る": ("座る", False),  # 0.64: no, a different action
    "登る": ("歩く", True),  # 0.67: yes, climbing a slope is walked
    "飲む": ("帰る", False),  # 0.53: no, a different action
    "乗る": ("走る", False),  # 0.69: no, a different action
    "入る": ("置く", False),  # 0.65: no, a different action
    "吹く": ("跳ぶ", False),  # 0.57: no, a different action
    "休む": ("帰る", False),  # 0.59: no, a different action
    "読む": ("見る", False),  # 0.61: no, a different action
    "渡す": ("受け取る", False),  # 0.77: no, a different action
    "踏む": ("蹴る", False),  # 0.73: no, a different action
    "折る": ("持ち上げる", False),  # 0.53: no, a different action
    "壊す": ("倒れる", False),  # 0.52: no, a different action
    "噛む": ("パンチする", False),  # 0.54: no, a different action
    "触る": ("後ずさりする", False),  # 0.61: no, a different action
    "打つ": ("投げる", False),  # 0.68: no, a different action
    "滑る": ("転ぶ", True),  # 0.69: yes, a person's slip ends in the fall
    "下りる": ("向かう", True),  # 0.77: yes, going down on foot is walked
    "運ぶ": ("置く", False),  # 0.55: no, a different action
    "集める": ("持つ", False),  # 0.57: no, a different action
    "落とす": ("取る", False),  # 0.64: no, a different action
    "眠る": ("起きる", False),  # 0.55: no, a different action
    "上がる": ("下がる", False),  # 0.82: no, a different action
    "入れる": ("置く", True),  # 0.70: yes, putting in is putting down
    "消す": ("押す", False),  # 0.58: no, a different action
    "締める": ("引っ張る", False),  # 0.56: no, a different action
    "返す": ("受け取る", False),  # 0.56: no, a different action
    "釣る": ("持ち上げる", False),  # 0.57: no, a different action
    "飾る": ("置く", False),  # 0.58: no, a different action
    "包む": ("広げる", False),  # 0.50: no, a different action
    "手伝う": ("喜ぶ", False),  # 0.50: no, a different action
    "騒ぐ": ("はしゃぐ", True),  # 0.68: yes, romping is はしゃぐ
    "動く": ("止まる", False),  # 0.63: no, a different action
    "止める": ("止まる", False),  # 0.66: no, a different action
    "起こす": ("起きる", False),  # 0.80: no, a different action
    "見つける": ("探す", True),  # 0.74: yes, finding is shown by looking around
    "祈る": ("喜ぶ", False),  # 0.55: no, a different action
    "驚く": ("見る", False),  # 0.58: no, a different action
    "怒る": ("謝る", False),  # 0.78: no, a different action
    "呼ぶ": ("指す", False),  # 0.53: no, a different action
    "貼る": ("置く", False),  # 0.56: no, a different action
    "見せる": ("見る", False),  # 0.60: no, a different action
    "迎える": ("振り返る", False),  # 0.54: no, a different action
    "話す": ("謝る", False),  # 0.60: no, a different action
    "抱く": ("突き飛ばす", False),  # 0.60: no, a different action
    "畳む": ("持ち上げる", False),  # 0.51: no, a different action
    "握る": ("振る", False),  # 0.54: no, a different action
    "掴む": ("引き寄せる", False),  # 0.62: no, a different action
    "震える": ("泣く", False),  # 0.64: no, a different action
    "伸ばす": ("広げる", True),  # 0.68: yes, stretching the arms out
    "拭く": ("下ろす", False),  # 0.52: no, a different action
    "吐く": ("抱え上げる", False),  # 0.57: no, a different action
    "叫ぶ": ("泣く", False),  # 0.61: no, a different action
    "覗く": ("見る", False),  # 0.66: no, a different action
    "隠れる": ("逃げる", False),  # 0.52: no, a different action
    "隠す": ("置く", False),  # 0.47: no, a different action
    "避ける": ("取る", False),  # 0.52: no, a different action
    "押さえる": ("下げる", False),  # 0.64: no, a different action
    "戦う": ("殴る", True),  # 0.49: yes, fighting shown as punching
    "微笑む": ("会釈する", False),  # 1.00: no, a different action
    "組む": ("見る", False),  # 0.49: no, a different action
    "積む": ("置く", True),  # 0.53: yes, stacking is putting down
    "巻く": ("引っ張る", False),  # 0.55: no, a different action
    "結ぶ": ("渡る", False),  # 0.45: no, a different action
    "抜く": ("止まる", False),  # 0.62: no, a different action
    "外す": ("引っ張る", False),  # 0.63: no, a different action
    "乗せる": ("下ろす", False),  # 0.65: no, a different action
    "流す": ("叩く", False),  # 0.51: no, a different action
    "掻く": ("跳ねる", False),  # 0.63: no, a different action
    "嗅ぐ": ("後ずさりする", False),  # 0.60: no, a different action
    "越える": ("渡る", True),  # 0.59: yes, going over is walked
    "倒す": ("殴る", True),  # 0.69: yes, knocking down with a punch
    "触れる": ("見る", False),  # 0.50: no, a different action
    "擦る": ("叩く", False),  # 0.60: no, a different action
    "閉じる": ("立ち上がる", False),  # 0.56: no, a different action
    "飛び出す": ("跳び上がる", False),  # 0.64: no, a different action
    "繋ぐ": ("取る", False),  # 0.56: no, a different action
    "沈む": ("跳ねる", False),  # 0.48: no, a different action
}


def classify(db) -> list[tuple[str, str, str, float | None]]:
    """(verb, class, clip or stand-in, cosine) per verb: a clip, b accepted fallback, x fallback
    judged wrong, u fallback not judged (stand-in changed), c nothing."""
    from text2anim.motiondb import UnknownVerbError
    from text2anim.nlp import meaning
    from text2anim.nlp.analyze import analyze

    verbs = [v.lemma for v in db.verbs()]
    out = []
    for verb in VERBS:
        spec = analyze(verb + "。").motions[0]
        hit = None
        for key in (spec.verb, spec.reading, verb):
            try:
                hit = db.search(key, limit=1)
                break
            except UnknownVerbError:
                continue
        if hit:
            out.append((verb, "a", hit[0].name, None))
            continue
        near = meaning.nearest(spec.verb, verbs, n=1, floor=meaning.MIN_SIMILARITY, within=meaning.MAX_RANK)
        if not near:
            out.append((verb, "c", "", None))
            continue
        used, score = near[0]
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
    count = {k: sum(1 for r in rows if r[1] == k) for k in "abxcu"}
    print(f"{n} everyday action verbs (JLPT N5/N4/N3 lists, bodily actions)")
    print("| class | verbs | share |")
    print("| --- | ---: | ---: |")
    for k, label in (("a", "(a) has a clip"), ("b", "(b) fallback a native speaker accepts"),
                     ("c", "(c) nothing (no clip, nothing near in meaning)"),
                     ("x", "    fallback judged wrong (counted with neither)"),
                     ("u", "    fallback not judged yet (counted with neither)")):
        print(f"| {label} | {count[k]} | {100 * count[k] / n:.1f} % |")
    print(f"(a)+(b) = {100 * (count['a'] + count['b']) / n:.1f} %   wall {wall:.1f} s, CPU {cpu:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
