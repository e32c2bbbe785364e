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
    "返る": "帰る",  # UniDic's lemma of 帰る (家に帰った): going home, a walk there
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
    "片手": "arm", "片腕": "arm", "片足": "leg", "片脚": "leg",
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
    張り切って 揃って そろって 改めて 初めて 続けて 気をつけて 注意して 並んで ならんで""".split()
)

#: Verbs that are states or formal verbs, not motions (compared by lemma); 始める / 終える / 続ける as a
#: main verb (試合を始めた) say when something happens, not what is done.
NON_ACTION_LEMMAS = frozenset(
    """居る 有る 在る 成る 出来る 思う 分かる 見える 聞こえる 要る 知る 似る 違う
    為る 御座る 居す 始める 始まる 終える 終わる 続ける 続く""".split()
)

#: Set greetings built on a motion verb (いらっしゃる, 行く, 帰る, 休む), as the phrase is written without its
#: punctuation: said to someone, not done by the one who says them (a shop's いらっしゃいませ is no 来る).
GREETINGS = frozenset(
    """いらっしゃいませ いらっしゃい いってらっしゃい 行ってらっしゃい いってらっしゃいませ 行ってらっしゃいませ
    おかえりなさい お帰りなさい おかえりなさいませ お帰りなさいませ おやすみなさい お休みなさい""".split()
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

#: Honorific verbs and the plain verb each stands for (docs/language.md §9, :mod:`keigo`).
#: いらっしゃる is also いる after a て-form; 召し上がる is 飲む with a drink (``DRINKS``).
HONORIFIC_VERBS = {"いらっしゃる": "来る", "召し上がる": "食べる", "仰る": "言う"}

#: Verbs that are honorific only inside お + 連用形 + になる: お見えになる, お越しになる, おいでになる (来る).
PREFIXED_HONORIFIC_VERBS = {"見える": "来る", "越す": "来る", "出でる": "来る"}

#: Drinks (by UniDic lemma): 召し上がる with one of them as its object is 飲む.
DRINKS = frozenset("茶 お茶 コーヒー 紅茶 水 お水 ジュース 牛乳 ミルク 酒 お酒 ビール ワイン スープ 味噌汁 湯".split())

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
    お兄さん お姉さん 兄ちゃん 姉ちゃん
    店長 社長 部長 課長 会長 校長 院長 駅長 署長 隊長 船長 監督 コーチ 審判 上司 部下 同僚 先輩 後輩
    社員 会社員 店主 教授 医者 医師 看護師 教師 講師 警察官 消防士 弁護士 運転手 係 係員 案内係 駅員
    選手 歌手 相手 助手 騎手 投手 捕手 役者 俳優 女優 記者 患者 客 お客 乗客 通行人 住人 隣人 村人 大人
    息子 娘 夫 妻 奥さん 旦那 旦那さん 祖父 祖母 孫 おじいちゃん おばあちゃん 赤ん坊 幼児 園児 児童
    小学生 中学生 高校生 大学生 留学生 新入生 転校生 同級生 王子 王女 姫 お姫様 女王 勇者 魔女 泥棒
    犯人 刑事 探偵 兄弟 姉妹 彼氏 おばちゃん おじちゃん パパ ママ 新人 仲間 恋人 親友 住民 市民 お年寄り
    人々 親 両親 主婦 美容師 漁師 職人 商人 旅人 料理人
    ピッチャー バッター キャッチャー ランナー プレイヤー プレーヤー キーパー ゴールキーパー ストライカー
    ドライバー パイロット シェフ ウェイター ウェイトレス スタッフ マネージャー リーダー メンバー ゲスト
    アイドル モデル ボクサー レスラー スケーター スイマー ピエロ マジシャン サンタ サンタクロース ヒーロー
    ヒロイン プリンセス プリンス ナース ドクター ガイド アナウンサー カメラマン チームメイト キャプテン
    警備員 係の人 お巡りさん 審判員 店の人
    兄貴 アニキ 姉貴 アネキ 親父 おやじ オヤジ おふくろ お袋 わし 友だち ダチ 嫁 相方
    坊や 甥 姪 いとこ 従兄弟 従姉妹 叔父 伯父 叔母 伯母 ワンコ わんこ にゃんこ""".split()
)

#: Words that honour the person they name (先生, 社長, 田中様): such an actor doing a gesture with a
#: part of their own body in れる / られる form is spoken of in keigo, not passively (先生は生徒たちに
#: 手を振られた: the teacher waved; docs/language.md §9.3).
HONOURED_TITLES = frozenset(
    """先生 社長 部長 課長 係長 会長 校長 院長 店長 所長 理事長 監督 教授 先輩 様 さま 殿 陛下 殿下 お客様""".split()
)

#: Person nouns by sex, for the pronouns that name one (彼: a man, 彼女: a woman; docs/language.md §9).
#: Compared with each noun of a mention (お父さん: 父), so spelling variants are listed once each.
MALE_NOUNS = frozenset(
    """男 男性 少年 男の子 父 父親 兄 弟 お兄さん 兄ちゃん おじいさん おじいちゃん おじさん おじちゃん
    祖父 息子 夫 旦那 王様 王子 彼 彼氏 パパ 僧 紳士 兄貴 アニキ 親父 おやじ オヤジ 坊や 甥 叔父 伯父""".split()
)
FEMALE_NOUNS = frozenset(
    """女 女性 少女 女の子 母 母親 姉 妹 お姉さん 姉ちゃん おばあさん おばあちゃん おばさん おばちゃん
    祖母 娘 妻 奥さん 王女 姫 お姫様 女王 女優 魔女 彼女 ママ 姉貴 アネキ おふくろ お袋 嫁 姪 叔母
    伯母""".split()
)

#: Endings of given names read as a man's or a woman's (花子, 恵子, 美咲; 太郎, 健一, 健太): the
#: common patterns, not a dictionary; a name with none of them is either (docs/language.md §9).
MALE_NAME_ENDINGS = tuple("郎 男 夫 雄 太 介 助 輔 吉 彦 蔵 平 也 哉 樹 斗 翔 一 二 司 治 士 朗 之 人 ろう すけ".split())
FEMALE_NAME_ENDINGS = tuple("子 美 香 奈 恵 江 代 絵 菜 花 乃 華 咲 衣 莉 里 こ".split())

#: Verbs of the weather: their が-subject is rain or snow, even one that can be a name (ゆきが降る).
WEATHER_VERBS = frozenset("降る 降り出す 積もる 止む".split())

#: Given names often written in hiragana that UniDic reads as other words (はると: はる + と, あかり: 明かり),
#: each with the sex a reader takes it for (:mod:`kana_names`; words of everyday use such as ゆき, ひかり, そら,
#: はな, こころ are left out: ゆきが降った is snow).
KANA_NAMES = {
    **dict.fromkeys("""はると ゆうと そうた れん ゆうま はやと りく かいと たくみ こうき しょうた だいき ゆうき けんた たける りょう
    しょう あきら ひろし たろう じろう けんじ こうた そうま はるき ゆうた ゆうすけ しゅん まさと なおき たいが いつき
    みなと ひろと ゆいと おさむ まこと つよし たかし さとし けん じゅん かずき ともや りゅうせい こうすけ そうすけ
    けいた はじめ まさる しんじ ゆうじ とおる だいすけ しゅうと かける けんいち しんいち こうへい しゅうへい ひでき""".split(), "m"),
    **dict.fromkeys("""さくら あかり ゆい みお あおい ひな めい ゆな りこ ことは えま ほのか みゆ ゆあ さき まい あやか はるか なつみ
    ちひろ ももか りん かえで ゆり えみ あいり まな ゆか みき なな かな あや まゆ みさき はなこ はるな ゆみ ともこ
    なおこ けいこ よしこ まりこ あけみ ちか あすか まり りな みく あみ りさ さや ちなつ ひまり つむぎ いろは えり
    さえ まなみ ゆうか ゆうな みゆき なぎさ ゆきこ さちこ ようこ ひろみ まさみ""".split(), "f"),
}

#: Pronouns and demonstratives that refer back to one person (docs/language.md §9): word -> sex
#: ("m", "f" or "" for either).  その/あの/この + a person noun (その男, あの子) is read the same way.
PRONOUNS = {"彼": "m", "彼女": "f", "あいつ": "", "こいつ": "", "そいつ": "", "その人": "", "あの人": "",
            "この人": "", "その方": "", "あの方": "", "この方": "", "その子": "", "あの子": "", "この子": ""}

#: Words for a group of the persons named so far: word -> how many (0: all of them).  N人 and
#: N人とも are read from the number (三人 -> 3).
GROUP_WORDS = {"二人": 2, "ふたり": 2, "みんな": 0, "皆": 0, "みな": 0, "全員": 0, "皆さん": 0, "みなさん": 0,
               "皆様": 0, "みなさま": 0, "彼ら": 0, "彼女ら": 0, "彼女たち": 0, "あいつら": 0, "一同": 0}

#: One of the last group named (二人は歩いた。一人が止まった。もう一人は振り返った): its members in turn.
ONE_OF_GROUP = frozenset("一人 ひとり 1人 １人".split())

#: First- and second-person words: persons, but never what 彼 / その人 refers back to.
SPEAKERS = frozenset("私 僕 俺 わたし ぼく おれ あたし 自分 あなた 君 きみ お前 おまえ".split())

#: Suffixes that make a person of the noun before them (運転 + 手, 参加 + 者, 管理 + 人, 受付 + 係,
#: 警察 + 官), and endings of one-word nouns that name a person (駅員, 記者, 店長) except
#: ``PERSONLESS_NOUNS``: 〜長 is also a length (身長), 〜員 a count (定員).
PERSON_SUFFIXES = frozenset("員 長 者 手 係 人 官 士 師".split())
PERSON_ENDINGS = ("員", "者", "長")
PERSONLESS_NOUNS = frozenset(
    """身長 体長 全長 特長 波長 延長 成長 助長 最長 冗長 消長 定員 満員 欠員 人員 動員 増員 減員 前者 後者
    両者""".split()
)

#: Heads of a person noun phrase X + の + head (係の人, 隣の人, 近所の子, あちらの方).
PERSON_HEADS = frozenset("人 方 子".split())

#: Words that make the persons before them (花子と一緒に) or the group (みんなで, 二人で) act together
#: with the actor: the motion they modify is performed by every one of them, for the same time.
TOGETHER_WORDS = frozenset(
    """一緒に いっしょに 一緒になって 揃って そろって 共に ともに 二人で ふたりで みんなで 皆で みなで
    全員で 一斉に 並んで ならんで""".split()
)

#: Verbs whose て-form takes its を-persons along on the next motion (犬を連れて散歩する: the dog walks too).
TAKING_ALONG = frozenset("連れる 伴う".split())

#: Verbs of taking someone by the hand (手を引く, 手をつなぐ): in て-form, that person goes along on the walk or
#: run that follows (花子は太郎の手を引いて走った: both run).
LEADING_BY_HAND = frozenset("引く 繋ぐ つなぐ 取る 握る".split())

#: Animals among the persons: 鳴く is what they do (太郎が鳴く is 泣く, a typo; 犬が鳴く is not).
ANIMALS = frozenset("犬 猫 子犬 子猫 馬 鳥 熊 クマ 猿 サル うさぎ ウサギ パンダ 怪獣 鳩 ハト 金魚 小鳥".split())

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
#: and 時間が経つ is already no action: its subject is not a person);
#: "human" — when the actor is no animal (``ANIMALS``): 鳴く is what a dog does, 太郎が鳴く is 泣く.
HOMOPHONE_TYPOS = {
    "降る": ("振る", "object"),
    "経つ": ("立つ", "motion"),
    "振り替える": ("振り返る", "no object"),
    "鳴く": ("泣く", "human"),
}

#: Default delay of しばらくして, in seconds.
DEFAULT_PAUSE = CONNECTIVES["しばらくして"][3]

#: s: a lap round something (木の周りを三周歩く: 12 s of walking, three laps: scene.circling).
LAP_SECONDS = 4.0

#: Counters: unit -> (kind, factor to seconds or 1).
COUNTERS = {
    "回": ("repeat", 1), "度": ("repeat", 1), "周": ("duration", LAP_SECONDS), "歩": ("steps", 1),
    "秒間": ("duration", 1.0), "分間": ("duration", 60.0),
    "秒": ("seconds", 1.0), "分": ("seconds", 60.0),
}


# ---------------------------------------------------------------- the scene (docs/language.md §8)

#: Verbs that take the actor somewhere: a に / へ / まで noun is where they go (the ``goal``).
LOCOMOTION_VERBS = frozenset(
    """歩く 走る 駆ける 駆け出す 駆け寄る 駆け込む 走り寄る 近付く 近寄る 歩み寄る 寄る 行く 来る 向かう 戻る
    帰る 入る 進む 前進する 移動する 急ぐ 逃げる 離れる 下がる 後ずさりする 後退りする スキップする 歩き出す
    走り出す 出る 出掛ける 這う 飛び込む 近寄る 立つ 隠れる 回り込む 詰め寄る 駆け上がる 駆け下りる 駆け降りる
    駆け回る 走り回る 歩き回る 追いかける 追い掛ける 追う 着く 到着する 辿り着く たどり着く 渡る 横切る 下る
    集まる 駆けつける 駆け付ける 散歩する 別れる 現れる 現われる 姿を現す 去る 立ち去る 歩き去る 走り去る 駆け去る 逃げ去る 逃げ出す""".split()
)

#: Verbs that take the body down off its feet (besides ``SUPPORT_VERBS``): after them 立つ is rising, before
#: them 花子の前に立つ is going to stand there (a walk).
LOWERING_VERBS = frozenset(
    "しゃがむ しゃがみ込む 屈む かがむ 転ぶ 倒れる ひざまずく 跪く 伏せる 寝転ぶ 横になる 座り込む うずくまる".split()
)

#: Verbs of a jump: 着地する right after one of them by the same actor is that jump's landing, no second jump.
JUMP_VERBS = frozenset(
    "ジャンプする 跳ぶ 飛ぶ 跳ねる 飛び跳ねる 跳び上がる 飛び上がる 飛び降りる 飛び下りる 跳び降りる 跳び下りる 飛び乗る 飛び込む 飛び越える".split()
)
#: The verb of landing (the end of a jump).
LANDING_VERB = "着地する"

#: Verbs of rising: their を-seat is where they rise from (席を立つ); opening an actor's track with no seat
#: named, they rise from one too (生徒たちは立ってお辞儀をした: a class rising, not a crouch).
RISING_VERBS = frozenset("立つ 立ち上がる 起立する".split())

#: Things sat on: rising from one (椅子から立つ) starts seated.
SEATS = frozenset("椅子 いす イス チェア ソファ ソファー ベンチ 長椅子 席 座席 腰掛け 切り株".split())

#: Verbs whose に-thing holds the body up (the ``support``): 椅子に座る, ベッドに寝る.
SUPPORT_VERBS = frozenset(
    """座る 腰掛ける 着席する 座り込む 寝る 横になる 寝転ぶ 寝そべる 乗る 登る 上る 上がる 寄り掛かる
    もたれる""".split()
)

#: Verbs of getting down off something: their から-thing held the body up before (台から飛び降りる, 馬から降りる).
OFF_VERBS = frozenset("降りる 下りる 飛び降りる 飛び下りる 跳び降りる 跳び下りる 駆け下りる 駆け降りる 滑り降りる".split())

#: Verbs that send a thing to a person (the に-person is the ``recipient``) or to a place (``destination``).
TRANSFER_VERBS = frozenset(
    """渡す 手渡す 差し出す 投げる 放る 放り投げる 蹴る パスする 返す 見せる 上げる 送る 届ける 配る
    投げ渡す 転がす 差し上げる 呉れる 貸す 蹴り返す 投げ返す""".split()
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
    "近く": "near", "側": "near", "脇": "beside", "周り": "near", "まわり": "near", "周囲": "near",
    "上": "on", "うえ": "on", "下": "under",
    "左": "left", "右": "right",
}
#: Side nouns that, marked を, say a way round the noun before them (木の周りを歩く: ``around``); with に they
#: are only near it (先生の周りに集まる).
AROUND_NOUNS = frozenset("周り まわり 周囲".split())

#: Nouns after 〜の that only say "where X is" (花子のところへ, 花子の方へ, 花子のもとへ).
PLACE_OF_NOUNS = frozenset("ところ 所 とこ トコ 方 ほう もと 元 側".split())

#: て-forms that say which way the next motion goes, no motion of their own (花子に向かって走る).
DIRECTION_TE = frozenset("向かう 向ける".split())

#: Verbs by which two people face each other (二人は向かい合ってお辞儀する): no motion of their own.
FACING_VERBS = frozenset("向かい合う 向き合う 対面する".split())

#: Nouns that are the ground itself: a thing put there lies on the floor (箱を床に下ろす), no thing of its own.
GROUND_NOUNS = frozenset("床 ゆか 地面 地べた 床の上 足元 足下".split())

#: Verbs done to a door (ドアを引いて開ける): one written without its object is done to the door just handled
#: or gone to (ドアの前で立ち止まって、ノックした).
DOOR_VERBS = frozenset("開ける 開く 閉める 締める 閉じる ノックする".split())
#: Verbs that move a thing: one written without its object moves the thing just handled (台車を押して、運んだ).
MOVING_VERBS = frozenset("運ぶ 持ち運ぶ 押して行く".split())

#: Demonstratives that name the thing last named (花子はそれを投げた: the ball 太郎 handed her).
THING_ANAPHORS = frozenset("それ これ あれ そいつ".split())

#: A motion that hands a thing over implies its counterpart by the other person, played at the same time:
#: verb (lemma) -> (the counterpart's verb, its reading, the role the first motion's target has).
#: What the causer of a causative does (先生は生徒を前に進ませた: the teacher tells the student, who steps
#: forward): the verb and its reading.
TELLING = ("話す", "ハナス")

COUNTERPARTS = {
    "渡す": ("受け取る", "ウケトル", "recipient"), "手渡す": ("受け取る", "ウケトル", "recipient"),
    "貸す": ("受け取る", "ウケトル", "recipient"), "返す": ("受け取る", "ウケトル", "recipient"),
    "差し出す": ("受け取る", "ウケトル", "recipient"),
    "受け取る": ("渡す", "ワタス", "source"), "貰う": ("渡す", "ワタス", "source"),
}
#: Verbs of receiving from someone face to face (their ``source`` stands in front): a leaving right after
#: one leaves that person, turning away first (受け取って、走り去った).
RECEIVING_VERBS = frozenset(v for v, (_, _, role) in COUNTERPARTS.items() if role == "source")

#: Verbs done to a person by touching them: the person is the ``patient`` (close by), not an addressee.
CONTACT_VERBS = frozenset(
    """抱き締める 抱く 抱きつく 抱き付く 押す 叩く 殴る 撫でる 触る 触れる 起こす 揺り起こす 掴む 引く 引っ張る
    突き飛ばす 支える 担ぐ おんぶする 抱っこする くすぐる 捕まえる 捕らえる""".split()
)

#: Verbs two people do to each other: co-actors of one are each other's partner (太郎と花子は握手する).
RECIPROCAL_VERBS = frozenset(
    """握手する ハイタッチする 話す 話する おしゃべりする 会話する 話し合う 喧嘩する けんかする 戦う 乾杯する キスする 見つめ合う
    抱き合う 向かい合う 組み合う 繋ぐ つなぐ 手を繋ぐ 出会う 出合う 顔を見合わせる 見合わせる""".split()
)
#: Verbs whose を-person is where the motion ends, not whom it is done to: 男を追いかける runs up to him.
CHASING_VERBS = frozenset("追いかける 追い掛ける 追う 追い付く 追いつく".split())
#: Reciprocal verbs done side by side, the hands between the two: the first of the pair holds with the
#: right hand (its clip mirrored), the partner, on its right, with the left (the clip as keyframed).
HAND_IN_HAND = frozenset("繋ぐ つなぐ 手を繋ぐ".split())

#: Nouns before に / と that are no target (一緒に is "together", not a place).
#: Nouns of how much, said bare before a verb (一口飲んで: a sip), never its object.
AMOUNT_NOUNS = frozenset("一口 ひと口 ひとくち 一息 ひと息 一粒 ひと粒".split())
NOT_TARGETS = frozenset("一緒 いっしょ 共 とも 互い 同時 一斉 列 一列 輪 最後 最初 順番 順 前 後 後ろ 横 上 下 右 左 そば 隣".split())

#: Verbs that send a thing through the air to someone, and verbs that catch it: a catch of the thing another
#: person throws is timed by the flight (docs/language.md §8), not after the throw has ended.
THROWING_VERBS = frozenset("投げる 放る 放り投げる 投げ渡す パスする".split())
CATCHING_VERBS = frozenset("取る キャッチする 受け止める 捕まえる".split())
