"""Word lists of the nlp stage: the small lexicon the rules rely on.

Everything language-specific that is a *list* rather than a *rule* lives here,
so a reader can see at a glance which words the analyzer knows about.
"""
from __future__ import annotations

#: Verbs of the built-in motion library, in the spelling the motion database
#: uses.  The analyzer normalises every spelling variant to these lemmas.
LIBRARY_VERBS = frozenset(
    """歩く 走る 下がる スキップする 止まる 立ち止まる ジャンプする 跳ぶ 飛ぶ 転ぶ 倒れる
    回る 踊る 座る 立ち上がる 立つ しゃがむ 蹴る 殴る 構える 投げる 拾う 持ち上げる 置く 押す
    引く キャッチする 受け取る 振る 上げる 広げる 拍手する 叩く 指さす うなずく 見回す 見上げる
    お辞儀する 振り向く 振り返る 喜ぶ ガッツポーズする 泣く 笑う 伸びする 待つ""".split()
)

#: UniDic lemma (or written base form) -> library spelling, where they differ.
#: とぶ is read as a jump: a character on the ground jumps, it does not fly.
VERB_ALIASES = {
    "頷く": "うなずく",
    "指差す": "指さす",
    "とぶ": "跳ぶ",
    "屈む": "しゃがむ",
}

#: Reading (katakana, base form) -> library verb, for verbs written in
#: hiragana that UniDic reads as another word (たつ -> 経つ, but 立つ is meant).
#: トブ goes to 跳ぶ for the reason given at VERB_ALIASES.
LIBRARY_BY_READING = {
    "ウナズク": "うなずく", "シャガム": "しゃがむ", "アゲル": "上げる", "サガル": "下がる",
    "タオレル": "倒れる", "ウケトル": "受け取る", "タタク": "叩く", "ヨロコブ": "喜ぶ",
    "マワル": "回る", "ヒロゲル": "広げる", "スワル": "座る", "ヒク": "引く", "マツ": "待つ",
    "ナゲル": "投げる", "オス": "押す", "ヒロウ": "拾う", "モチアゲル": "持ち上げる",
    "ユビサス": "指さす", "フリムク": "振り向く", "フリカエル": "振り返る", "フル": "振る",
    "カマエル": "構える", "トマル": "止まる", "アルク": "歩く", "ナグル": "殴る", "ナク": "泣く",
    "タチアガル": "立ち上がる", "タチドマル": "立ち止まる", "タツ": "立つ", "ワラウ": "笑う",
    "オク": "置く", "ミアゲル": "見上げる", "ミマワス": "見回す", "ハシル": "走る",
    "トブ": "跳ぶ", "オドル": "踊る", "ケル": "蹴る", "コロブ": "転ぶ",
}

#: Body-part nouns (marked with を or で) -> body_part value.
#: Values: right_arm, left_arm, both_arms, arm (side unspecified),
#: right_leg, left_leg, leg (side unspecified or both), head, torso.
BODY_PARTS = {
    "右手": "right_arm", "右腕": "right_arm",
    "左手": "left_arm", "左腕": "left_arm",
    "両手": "both_arms", "両腕": "both_arms",
    "手": "arm", "腕": "arm",
    "右足": "right_leg", "右脚": "right_leg",
    "左足": "left_leg", "左脚": "left_leg",
    "足": "leg", "脚": "leg", "両足": "leg", "両脚": "leg",
    "頭": "head", "首": "head", "顔": "head",
    "腰": "torso", "体": "torso", "身体": "torso",
    "上体": "torso", "上半身": "torso", "背中": "torso", "胸": "torso",
    # kana spellings (て is 手 only when tokens._repair_kana made it a noun before を)
    "て": "arm", "うで": "arm", "みぎて": "right_arm", "ひだりて": "left_arm",
    "りょうて": "both_arms", "あし": "leg", "みぎあし": "right_leg", "ひだりあし": "left_leg",
    "あたま": "head", "くび": "head", "かお": "head", "こし": "torso", "からだ": "torso",
}

#: 右の手 / 左の足: a side noun + の before a body part.
SIDE_PREFIX = {"右": "right", "左": "left", "両方": "both", "みぎ": "right", "ひだり": "left",
               "りょうほう": "both"}

#: Manner adverbs -> speed factor (1.0 = the clip's own speed).
#: Slower: ゆっくり 0.6 is a clearly slower but still natural pace.
#: Faster: 1.5 for "quickly / in a hurry", 1.3 for a brisk but not rushed one.
SPEED_WORDS = {
    "ゆっくり": 0.6, "ゆっくりと": 0.6, "ゆったり": 0.6, "ゆったりと": 0.6,
    "のんびり": 0.7, "のんびりと": 0.7, "そっと": 0.8, "静かに": 0.8,
    "素早く": 1.5, "すばやく": 1.5, "速く": 1.5, "早く": 1.5, "はやく": 1.5,
    "急いで": 1.5, "慌てて": 1.5, "あわてて": 1.5, "全力で": 1.5,
    "さっと": 1.3, "勢いよく": 1.3, "元気よく": 1.3,
}

#: て-forms used as manner adverbs: never a motion of their own.
MANNER_TE = frozenset(
    """急いで 慌てて あわてて 黙って だまって 落ち着いて 頑張って がんばって 思い切って
    張り切って 揃って そろって 改めて 初めて 続けて 気をつけて 注意して""".split()
)

#: Verbs that are states or formal verbs, not motions (compared by lemma).
NON_ACTION_LEMMAS = frozenset(
    """居る 有る 在る 成る 出来る 思う 考える 分かる 見える 聞こえる 要る 知る 似る 違う
    為る 御座る 居す""".split()
)

#: Auxiliary verbs after a て-form, by UniDic lemma (every spelling of one
#: auxiliary meets on its lemma: ください / 下さい -> 下さる, くれる / 呉れる ->
#: 呉れる, もらう / 貰う -> 貰う, しまう / 仕舞う -> 仕舞う, おく -> 置く, みる -> 見る,
#: あげる -> 上げる, いく / 行く -> 行く, くる / 来る -> 来る): folded into the verb.
AUX_AFTER_TE = frozenset(
    "居る 有る 置く 見る 仕舞う 行く 来る 貰う 上げる 呉れる 下さる 遣る 頂く 為さる 御座る".split()
)

#: Of those, the ones that are also main verbs of the library: written in kanji
#: after て they stay main verbs (持ち上げて置く = put it down, 振り向いて見る,
#: 拾って上げる = lift it); in kana (置いておく, 歩いてみる, 振ってあげる) they
#: are auxiliaries.
AUX_KANJI_MAIN = frozenset("置く 見る 上げる".split())

#: Aspect auxiliaries after a 連用形 verb (written base form): folded.
#: なさる (座りなさい) is the polite imperative, not an action of its own.
ASPECT_AUX = frozenset(
    """始める はじめる 続ける つづける 出す だす 終わる おわる 終える おえる 始まる かける
    なさる 為さる""".split()
)

#: Polite request auxiliaries after an お + 連用形 verb (お座りください, お待ち下さい),
#: by lemma: the request is the verb before it, not a motion of its own.
POLITE_AFTER_RENYOU = frozenset("下さる 為さる".split())

#: Nouns that name a person (or another creature that can be an actor).
PERSON_NOUNS = frozenset(
    """男 女 男性 女性 少年 少女 子供 子ども こども 男の子 女の子 人 先生 生徒 学生 選手
    父 母 兄 姉 弟 妹 父親 母親 友達 友人 赤ちゃん 老人 おじいさん おばあさん お父さん お母さん
    ロボット 主人公 犬 猫 王様 騎士 忍者 ダンサー 彼 彼女 私 僕 俺 あなた 彼ら 自分
    わたし ぼく おれ あたし 家族 店員 客 観客 警官 兵士 侍 魔法使い
    子犬 子猫 馬 鳥 熊 クマ 猿 サル うさぎ ウサギ パンダ 怪獣 ゾンビ 宇宙人 おじさん おばさん
    お兄さん お姉さん 兄ちゃん 姉ちゃん 相手""".split()
)

#: Script headings that open a line like a speaker label (ト書き：花子が座る) but name no
#: one: the line is a stage direction, its actor is found as in any other sentence.
SCRIPT_HEADINGS = frozenset(
    """ト書き 場面 シーン 注意 説明 演出 メモ 備考 場所 時間 背景 設定 ナレーション ナレーター 状況 舞台
    動作 動き アクション 指示 例 補足 タイトル""".split()
)

#: Honorific suffixes stripped from actor names (花子さん -> 花子).
HONORIFICS = frozenset("さん 君 くん ちゃん 様 さま 氏 殿".split())

#: Formal nouns that turn a preceding predicate into a temporal connective
#: (instead of a relative clause).
FORMAL_NOUNS = frozenset(
    "まま 侭 後 あと 前 間 うち 内 時 とき 瞬間 途端 とたん 同時".split()
)

#: Sentence connectives and adverbs that adjust the link into the motion
#: they modify: (relation, overlap, method, delay seconds).
#: しばらくして waits 2.0 s (a noticeable pause); 少しして 1.0 s.
CONNECTIVES = {
    "そして": ("serial", False, "connection", None),
    "それから": ("serial", False, "connection", None),
    "その後": ("serial", False, "connection", None),
    "そのあと": ("serial", False, "connection", None),
    "次に": ("serial", False, "connection", None),
    "続いて": ("serial", False, "connection", None),
    "最後に": ("serial", False, "connection", None),
    "同時に": ("parallel", None, "composition", None),
    "それと同時に": ("parallel", None, "composition", None),
    "しばらくして": ("serial", False, "connection", 2.0),
    "しばらくすると": ("serial", False, "connection", 2.0),
    "少しして": ("serial", False, "connection", 1.0),
    "すぐに": ("serial", True, "transition", None),
    "すぐ": ("serial", True, "transition", None),
}

#: その間 / その間に (meanwhile): the motion starts with the previous one.
CONNECTIVES.update({k: ("parallel", None, "composition", None) for k in ("その間", "その間に", "そのあいだ",
                                                                         "そのあいだに", "その最中に")})

#: Words that ask for a motion several times without a number: "several" is 3
#: repeats, "a few times" (何度か) 2.
REPEAT_WORDS = {
    "何度も": 3, "何回も": 3, "繰り返し": 3, "繰り返して": 3, "くりかえし": 3, "何べんも": 3,
    "何度か": 2, "何回か": 2,
}

#: Verbs made of steps: N歩 before one of them is its repeat count, in steps
#: (3歩下がる: repeat 3).  Before any other verb N歩 is a distance, not a count.
STEPPING_VERBS = frozenset(
    """歩く 下がる 進む 後ずさりする 後退りする 後退る 前進する 後退する 踏み出す 出る 戻る 近づく
    近寄る 歩み寄る 離れる 退く 歩き出す""".split()
)

#: Homophones the IME offers for a library verb: written verb -> (meant verb, when).  The
#: written verb is read as the meant one only where it gives no plausible motion:
#: "object" — with a を-noun (降る takes none: 手を降る is 手を振る; 雨が降る is left alone);
#: "no object" — without one (振り替える needs one: 予定を振り替える);
#: "motion" — whenever it is still an action of the actor (経つ is said of time only,
#: and 時間が経つ is already no action: its subject is not a person).
HOMOPHONE_TYPOS = {
    "降る": ("振る", "object"),
    "経つ": ("立つ", "motion"),
    "振り替える": ("振り返る", "no object"),
}

#: Default delay of しばらくして, in seconds.
DEFAULT_PAUSE = CONNECTIVES["しばらくして"][3]

#: Counters: unit -> (kind, factor to seconds or 1).
COUNTERS = {
    "回": ("repeat", 1), "度": ("repeat", 1), "歩": ("steps", 1),
    "秒間": ("duration", 1.0), "分間": ("duration", 60.0),
    "秒": ("seconds", 1.0), "分": ("seconds", 60.0),
}


# ---------------------------------------------------------------- the scene (docs/language.md §8)

#: Verbs that take the actor somewhere: a に / へ / まで noun is where they go (the ``goal``).
LOCOMOTION_VERBS = frozenset(
    """歩く 走る 駆ける 駆け出す 駆け寄る 駆け込む 走り寄る 近付く 近寄る 歩み寄る 寄る 行く 来る 向かう 戻る
    帰る 入る 進む 前進する 移動する 急ぐ 逃げる 離れる 下がる 後ずさりする 後退りする スキップする 歩き出す
    走り出す 出る 出掛ける 這う 飛び込む 近寄る 立つ 隠れる 回り込む 詰め寄る""".split()
)

#: Verbs whose に-thing holds the body up (the ``support``): 椅子に座る, ベッドに寝る.
SUPPORT_VERBS = frozenset(
    """座る 腰掛ける 着席する 座り込む 寝る 横になる 寝転ぶ 寝そべる 乗る 登る 上る 上がる 寄り掛かる
    もたれる""".split()
)

#: Verbs that send a thing to a person (the に-person is the ``recipient``) or to a place (``destination``).
TRANSFER_VERBS = frozenset(
    """渡す 手渡す 差し出す 投げる 放る 放り投げる 蹴る パスする 返す 見せる 上げる 送る 届ける 配る
    投げ渡す 転がす 差し上げる 呉れる""".split()
)

#: Verbs that put a thing somewhere: the に-noun is its ``destination`` (机に置く).
PLACING_VERBS = frozenset(
    """置く 載せる 乗せる 入れる 掛ける 貼る 立て掛ける 仕舞う 戻す 並べる 下ろす 降ろす 積む 飾る 吊るす""".split()
)

#: Nouns after 〜の that say where, relative to the noun before them (花子の前に, 花子の隣に).
SIDE_NOUNS = {
    "前": "front", "まえ": "front", "正面": "front", "目の前": "front",
    "後ろ": "behind", "うしろ": "behind", "後": "behind", "背後": "behind",
    "隣": "beside", "となり": "beside", "横": "beside", "よこ": "beside", "そば": "near", "傍": "near",
    "近く": "near", "側": "near", "脇": "beside",
    "上": "on", "うえ": "on",
    "左": "left", "右": "right",
}

#: Nouns after 〜の that only say "where X is" (花子のところへ, 花子の方へ, 花子のもとへ).
PLACE_OF_NOUNS = frozenset("ところ 所 方 ほう もと 元 側".split())

#: て-forms that say which way the next motion goes, no motion of their own (花子に向かって走る).
DIRECTION_TE = frozenset("向かう 向ける".split())

#: Verbs by which two people face each other (二人は向かい合ってお辞儀する): no motion of their own.
FACING_VERBS = frozenset("向かい合う 向き合う 対面する".split())

#: Demonstratives that name the thing last named (花子はそれを投げた: the ball 太郎 handed her).
THING_ANAPHORS = frozenset("それ これ あれ そいつ".split())

#: A motion that hands a thing over implies its counterpart by the other person, played at the same time:
#: verb (lemma) -> (the counterpart's verb, its reading, the role the first motion's target has).
COUNTERPARTS = {
    "渡す": ("受け取る", "ウケトル", "recipient"), "手渡す": ("受け取る", "ウケトル", "recipient"),
    "差し出す": ("受け取る", "ウケトル", "recipient"),
    "受け取る": ("渡す", "ワタス", "source"), "貰う": ("渡す", "ワタス", "source"),
}

#: Verbs done to a person by touching them: the person is the ``patient`` (close by), not an addressee.
CONTACT_VERBS = frozenset(
    """抱き締める 抱く 抱きつく 抱き付く 押す 叩く 殴る 撫でる 触る 触れる 起こす 揺り起こす 掴む 引く 引っ張る
    突き飛ばす 支える 担ぐ おんぶする 抱っこする くすぐる""".split()
)

#: Verbs two people do to each other: co-actors of one are each other's partner (太郎と花子は握手する).
RECIPROCAL_VERBS = frozenset(
    """握手する ハイタッチする 話す 会話する 話し合う 喧嘩する けんかする 戦う 乾杯する キスする 見つめ合う
    抱き合う 向かい合う 組み合う""".split()
)

#: Nouns before に / と that are no target (一緒に is "together", not a place).
NOT_TARGETS = frozenset("一緒 いっしょ 共 とも 互い 同時 最後 最初 順番 順 前 後 後ろ 横 上 下 右 左 そば 隣".split())

#: Verbs that send a thing through the air to someone, and verbs that catch it: a catch of the thing another
#: person throws is timed by the flight (docs/language.md §8), not after the throw has ended.
THROWING_VERBS = frozenset("投げる 放る 放り投げる 投げ渡す パスする".split())
CATCHING_VERBS = frozenset("取る キャッチする 受け止める 捕まえる".split())
