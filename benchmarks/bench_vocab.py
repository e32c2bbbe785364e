"""Everyday action verbs against the motion library: clip, accepted fallback by meaning, or nothing.

Source of the verb list: the JLPT N5, N4 and N3 vocabulary lists of
jamsinclair/open-anki-jlpt-decks (src/n5.csv, n4.csv, n3.csv; MIT, after the
tanos.co.uk lists), verbs only ("to ..." entries), kept when the verb names a
visible bodily action a character could act out (states, mental, weather,
speech-only and commercial verbs left out: ある, 分かる, 曇る, 買う, ...).
Nothing here comes from the project's corpus.

For each verb: (a) the built-in library has a clip for it (by lemma, synonym or
reading, as the planner searches); else the nearest library verb by meaning
(``nlp.meaning``, cosine >= MIN_SIMILARITY) is what ``--fallback nearest`` plays,
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

#: My judgement of each fallback (verb -> stand-in shown by the run): would a native
#: speaker accept the stand-in as the animation of the verb?  Filled from a run of
#: this script; a verb missing here counts as not accepted.
JUDGE: dict[str, bool] = {
    "開く": False,  # -> 押す (0.57): no, a different action
    "遊ぶ": False,  # -> 散歩する (0.65): no, a different action
    "洗う": False,  # -> 下ろす (0.47): no, a different action
    "行く": False,  # -> 回る (0.67): no, a different action
    "歌う": False,  # -> 踊る (0.76): no, a different action
    "泳ぐ": False,  # -> はしゃぐ (0.54): no, a different action
    "降りる": True,  # -> 歩く (0.76): yes, going down is walked
    "帰る": False,  # -> 振る (0.58): no, a different action
    "書く": False,  # -> 見る (0.61): no, a different action
    "かぶる": False,  # -> 捕る (0.49): no, a different action
    "切る": False,  # -> 指す (0.62): no, a different action
    "着る": False,  # -> 踊る (0.49): no, a different action
    "来る": False,  # -> 待つ (0.65): no, a different action
    "閉める": False,  # -> 足を止める (0.57): no, a different action
    "吸う": False,  # -> 放る (0.51): no, a different action
    "出す": False,  # -> 引く (0.66): no, a different action
    "食べる": False,  # -> 散歩する (0.49): no, a different action
    "出る": False,  # -> 見る (0.66): no, a different action
    "並ぶ": False,  # -> 置く (0.61): no, a different action
    "脱ぐ": False,  # -> しゃがむ (0.59): no, a different action
    "寝る": False,  # -> 座る (0.64): no, a different action
    "登る": True,  # -> 歩く (0.67): yes, climbing a slope is walked
    "飲む": False,  # -> 座る (0.49): no, a different action
    "乗る": False,  # -> 走る (0.69): no, a different action
    "入る": False,  # -> 置く (0.65): no, a different action
    "吹く": False,  # -> 跳ぶ (0.57): no, a different action
    "持つ": False,  # -> 捕る (0.69): no, a different action
    "休む": True,  # -> 待つ (0.50): yes, resting shown as standing still
    "読む": False,  # -> 見る (0.61): no, a different action
    "渡す": False,  # -> 受け取る (0.77): no, a different action
    "渡る": True,  # -> 進む (0.46): yes, crossing is walked forward
    "踏む": False,  # -> ステップを踏む (1.00): no, a different action
    "折る": False,  # -> 持ち上げる (0.53): no, a different action
    "壊す": False,  # -> 足を止める (0.57): no, a different action
    "噛む": False,  # -> パンチする (0.54): no, a different action
    "触る": False,  # -> 後ずさりする (0.61): no, a different action
    "打つ": False,  # -> 投げる (0.68): no, a different action
    "滑る": True,  # -> 転ぶ (0.69): yes, a person's slip ends in the fall
    "下りる": True,  # -> 歩く (0.76): yes, going down is walked
    "運ぶ": False,  # -> 置く (0.55): no, a different action
    "集める": False,  # -> 捕る (0.50): no, a different action
    "落とす": False,  # -> 捕る (0.64): no, a different action
    "向かう": True,  # -> 歩く (0.66): yes, heading somewhere is walked
    "急ぐ": False,  # -> 待つ (0.65): no, a different action
    "戻る": True,  # -> 進む (0.54): yes, going back is walked forward
    "眠る": False,  # -> 起きる (0.55): no, a different action
    "上がる": False,  # -> 下がる (0.82): no, a different action
    "入れる": True,  # -> 置く (0.70): yes, putting in is putting down
    "消す": False,  # -> 押す (0.58): no, a different action
    "締める": False,  # -> 足を止める (0.57): no, a different action
    "返す": False,  # -> 礼をする (0.60): no, a different action
    "釣る": False,  # -> 持ち上げる (0.57): no, a different action
    "飾る": False,  # -> 置く (0.58): no, a different action
    "包む": False,  # -> 広げる (0.50): no, a different action
    "手伝う": False,  # -> 喜ぶ (0.50): no, a different action
    "騒ぐ": True,  # -> はしゃぐ (0.68): yes, romping is はしゃぐ
    "動く": False,  # -> 止まる (0.63): no, a different action
    "通る": True,  # -> 歩く (0.62): yes, passing through is walked
    "止める": False,  # -> 足を止める (1.00): no, a different action
    "起こす": False,  # -> 起きる (0.80): no, a different action
    "謝る": False,  # -> 泣く (0.60): no, a different action
    "見つける": True,  # -> 探す (0.74): yes, finding is shown by looking around
    "祈る": False,  # -> 喜ぶ (0.55): no, a different action
    "驚く": False,  # -> 見る (0.58): no, a different action
    "怒る": False,  # -> 泣く (0.68): no, a different action
    "呼ぶ": False,  # -> 指す (0.53): no, a different action
    "貼る": False,  # -> 置く (0.56): no, a different action
    "見せる": False,  # -> 見る (0.60): no, a different action
    "迎える": False,  # -> 振り返る (0.54): no, a different action
    "話す": False,  # -> 挨拶する (0.58): no, a different action
    "抱く": False,  # -> 突き飛ばす (0.60): no, a different action
    "畳む": False,  # -> 持ち上げる (0.51): no, a different action
    "握る": False,  # -> 振る (0.54): no, a different action
    "掴む": False,  # -> 引き寄せる (0.62): no, a different action
    "震える": False,  # -> 泣く (0.64): no, a different action
    "伸ばす": True,  # -> 広げる (0.68): yes, stretching the arms out
    "拭く": False,  # -> 下ろす (0.52): no, a different action
    "吐く": False,  # -> 抱え上げる (0.57): no, a different action
    "叫ぶ": False,  # -> 泣く (0.61): no, a different action
    "覗く": False,  # -> 見る (0.66): no, a different action
    "隠れる": False,  # -> 逃げる (0.52): no, a different action
    "隠す": False,  # -> 置く (0.47): no, a different action
    "避ける": False,  # -> 足を止める (0.63): no, a different action
    "押さえる": False,  # -> 下げる (0.64): no, a different action
    "戦う": True,  # -> 殴る (0.49): yes, fighting shown as punching
    "微笑む": False,  # -> 会釈する (1.00): no, a different action
    "組む": False,  # -> 見る (0.49): no, a different action
    "積む": True,  # -> 置く (0.53): yes, stacking is putting down
    "巻く": False,  # -> 引っ張る (0.55): no, a different action
    "抜く": False,  # -> 止まる (0.62): no, a different action
    "外す": False,  # -> 引っ張る (0.63): no, a different action
    "乗せる": False,  # -> 下ろす (0.65): no, a different action
    "流す": False,  # -> 叩く (0.51): no, a different action
    "掻く": False,  # -> 跳ねる (0.63): no, a different action
    "嗅ぐ": False,  # -> 後ずさりする (0.60): no, a different action
    "越える": False,  # -> 止まる (0.48): no, a different action
    "倒す": True,  # -> 殴る (0.69): yes, knocking down by a punch
    "触れる": False,  # -> 見る (0.50): no, a different action
    "擦る": False,  # -> 叩く (0.60): no, a different action
    "閉じる": False,  # -> 足を止める (0.58): no, a different action
    "飛び出す": False,  # -> 跳び上がる (0.64): no, a different action
    "繋ぐ": False,  # -> 捕る (0.56): no, a different action
    "沈む": False,  # -> 跳ねる (0.48): no, a different action
}


def classify(db) -> list[tuple[str, str, str, float | None]]:
    """(verb, class a|b|x|c, clip verb or stand-in, cosine) per verb; x = fallback judged wrong."""
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
        near = meaning.nearest(spec.verb, verbs, n=1, floor=meaning.MIN_SIMILARITY)
        if not near:
            out.append((verb, "c", "", None))
            continue
        used, score = near[0]
        out.append((verb, "b" if JUDGE.get(verb, False) else "x", used, score))
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
    count = {k: sum(1 for r in rows if r[1] == k) for k in "abxc"}
    print(f"{n} everyday action verbs (JLPT N5/N4/N3 lists, bodily actions)")
    print("| class | verbs | share |")
    print("| --- | ---: | ---: |")
    for k, label in (("a", "(a) has a clip"), ("b", "(b) fallback a native speaker accepts"),
                     ("c", "(c) nothing (no clip, nothing near in meaning)"),
                     ("x", "    fallback judged wrong (counted with neither)")):
        print(f"| {label} | {count[k]} | {100 * count[k] / n:.1f} % |")
    print(f"(a)+(b) = {100 * (count['a'] + count['b']) / n:.1f} %   wall {wall:.1f} s, CPU {cpu:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
