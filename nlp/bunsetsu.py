"""Bunsetsu (phrases): sentence splitting and chunking of tokens.

A bunsetsu is a content word (with any prefix, compound nouns, サ変 する and
auxiliary verbs folded in) followed by its particles, auxiliaries and
punctuation.  Formal nouns that make temporal connectives (まま, 前, 後, 間,
うち, 同時, ...) stay in the bunsetsu of the predicate before them, so that
``座る前に`` or ``上げたまま`` is one phrase whose ending tells the link.
"""
from __future__ import annotations

from functools import lru_cache

from .lexicon import ASPECT_AUX, AUX_AFTER_TE, AUX_KANJI_MAIN, FORMAL_NOUNS, PERSON_NOUNS, POLITE_AFTER_RENYOU
from .pred import Pred
from .tagging import tag
from .types import Token

FUNCTION_POS = frozenset(["助詞", "助動詞", "接尾辞", "補助記号", "空白"])
_OPEN = frozenset("「『(（[“‘〈《【")
_CLOSE = frozenset("」』)）]”’〉》】")


class Phrase:
    """A mutable bunsetsu under analysis (``types.Bunsetsu`` is its frozen view)."""

    __slots__ = ("index", "tokens", "sentence", "group", "quoted", "role", "head",
                 "why", "pred", "persons", "key", "named")

    def __init__(self, index: int, tokens: list[Token], sentence: int, quoted: bool):
        self.index = index
        self.tokens = tokens
        self.sentence = sentence
        self.group = sentence  # clause group: a sentence, split at 終止形 + 、
        self.quoted = quoted
        self.role = ""
        self.head: int | None = None
        self.why = ""
        self.pred: Pred | None = None  # for predicate phrases
        #: the persons the phrase names, by their canonical names (彼女 -> ("花子",); 二人 ->
        #: ("太郎", "花子")): set by reference.resolve_persons for every phrase naming a person
        self.persons: tuple[str, ...] = ()
        #: the surface without trailing punctuation (for lexicon look-ups; tokens are fixed once chunked)
        self.key = _key(tokens)
        #: :func:`actors.person_name` of the phrase, kept once asked (``False``: not asked yet): several
        #: passes ask it of most phrases of every text
        self.named: str | None | bool = False

    @property
    def predicate(self) -> Pred:
        """``pred`` of a phrase known to be a predicate (a ``ValueError`` for any other)."""
        if self.pred is None:
            raise ValueError(f"phrase {self.index} is not a predicate")
        return self.pred

    @property
    def start(self) -> int:
        return self.tokens[0].start

    @property
    def end(self) -> int:
        return self.tokens[-1].end

    @property
    def surface(self) -> str:
        return "".join(t.surface for t in self.tokens)

    @property
    def content(self) -> list[Token]:
        return [t for t in self.tokens if t.pos1 not in FUNCTION_POS]

    def has_comma(self) -> bool:
        return any(t.pos2 == "読点" for t in self.tokens)

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"Phrase({self.index}:{self.surface}/{self.role}->{self.head})"


def _key(toks: list[Token]) -> str:
    n = len(toks)
    while n > 1 and toks[n - 1].pos1 == "補助記号":
        n -= 1
    return "".join(t.surface for t in toks[:n])


def split_sentences(tokens: list[Token]) -> list[list[Token]]:
    """Split after 。 ！ ？ . and newlines, never inside 「…」 quotes."""
    sentences: list[list[Token]] = []
    cur: list[Token] = []
    depth = 0
    for tok in tokens:
        if tok.surface in _OPEN:
            depth += 1
        elif tok.surface in _CLOSE and depth:
            depth -= 1
        if tok.pos2 == "句点" and depth == 0:
            if cur or not sentences:
                cur.append(tok)
                sentences.append(cur)
                cur = []
            else:
                sentences[-1].append(tok)  # 「！！」 or 。。: stays with its sentence
        else:
            cur.append(tok)
    if cur:
        sentences.append(cur)
    return [s for s in sentences if any(t.pos1 not in FUNCTION_POS for t in s)]


def chunk(sentences: list[list[Token]]) -> list[Phrase]:
    """Bunsetsu of all sentences, numbered across the whole text."""
    phrases: list[Phrase] = []
    for s_index, sent in enumerate(sentences):
        depth = 0
        cur: list[Token] = []
        quoted = False  # the current phrase's content lies inside 「…」
        prev: Token | None = None
        numunit = False  # the current phrase is a number (+ counter)
        for k, tok in enumerate(sent):
            if cur and (_starts_phrase(tok, prev, numunit) or (
                    len(cur) == 1 and prev is not None
                    and _name_then_thing(prev, tok, sent[k + 1] if k + 1 < len(sent) else None))):
                phrases.append(Phrase(len(phrases), cur, s_index, quoted))
                cur, numunit, quoted = [], False, False
            if tok.surface in _OPEN:
                depth += 1
            elif tok.surface in _CLOSE and depth:
                depth -= 1
            elif tok.pos1 not in FUNCTION_POS and depth:
                quoted = True
            numunit = numunit or tok.is_number
            cur.append(tok)
            prev = tok
        if cur:
            phrases.append(Phrase(len(phrases), cur, s_index, quoted))
    return phrases


def _starts_phrase(tok: Token, prev: Token | None, numunit: bool) -> bool:
    """Does ``tok`` begin a new bunsetsu after ``prev``?"""
    if prev is None:
        return False
    if tok.pos1 in FUNCTION_POS:
        return tok.surface in _OPEN  # 「 opens the phrase it quotes
    if prev.pos1 == "接頭辞":
        return False
    if tok.is_number:
        return True
    if numunit:
        # 3回 / 5秒間: a counter joins its number; anything else starts anew.
        return not (prev.is_number and tok.pos1 == "名詞" and tok.pos3 == "助数詞可能")
    if prev.pos1 == "連体詞" and tok.pos1 in ("名詞", "代名詞"):
        return False  # その後, その男
    if tok.pos1 == "名詞":
        if prev.pos1 == "名詞":
            # compound noun (ガッツ + ポーズ), not まま + 手, nor an adverb written as a
            # noun before it (うっかり + ボール, 今日 + ボール: UniDic's 副詞可能)
            return _is_formal(prev) or _adverbial(prev)
        if _is_formal(tok) and _ends_predicate(prev):
            return False  # 上げた + まま, 座る + 前, 上げると + 同時
        return True
    if tok.pos1 == "動詞":
        return not _attaches_verb(tok, prev)
    if tok.pos1 == "形容詞" and tok.lemma == "無い" and tok.pos2 == "非自立可能":
        return not (prev.pos1 == "動詞" or prev.lemma == "て")
    return True


def _is_formal(tok: Token) -> bool:
    if tok.surface == "間":
        return tok.kana == "アイダ"  # 間 (while), not 秒間 / 間 (ma)
    return tok.surface in FORMAL_NOUNS or tok.lemma in FORMAL_NOUNS


def _name_then_thing(prev: Token, tok: Token, after: Token | None) -> bool:
    """太郎 + ボールを, 花子 + 手を, まじで太郎 + ジャンプした opening a phrase: a person's name and a common noun
    with its own particle or する, no person (田中 + 先生 is one), are two phrases, the name's particle left out
    (docs/language.md §9).  The name must be one: tagged so here or on its own (UniDic tags 太郎 a
    common noun before ボール; 宇宙 of 宇宙遊泳 is none)."""
    return (tok.pos1 == "名詞" and tok.pos2 == "普通名詞" and prev.pos1 == "名詞" and tok.surface not in PERSON_NOUNS
            and after is not None and (after.pos1 == "助詞" or (tok.pos3 == "サ変可能" and after.lemma == "為る"))
            and (prev.pos3 == "人名" or _name_alone(prev.surface)))


@lru_cache(maxsize=1024)
def _name_alone(surface: str) -> bool:
    """Does the dictionary tag ``surface``, written on its own, a person's name?"""
    words = tag(surface, 0)
    return len(words) == 1 and words[0].pos3 == "人名"


def _adverbial(tok: Token) -> bool:
    """うっかり, しっかり, 今日, 毎日, 全部: a noun UniDic marks 副詞可能 before another
    noun is used as an adverb, not the first half of a compound noun (body parts
    such as 右手 and 前足 are single tokens)."""
    return tok.pos3 == "副詞可能"


def _ends_predicate(prev: Token) -> bool:
    if prev.pos1 == "助動詞" or prev.pos1 == "動詞":
        return True
    return prev.pos1 == "助詞" and prev.surface in ("と", "の")


def _attaches_verb(tok: Token, prev: Token) -> bool:
    if tok.lemma == "為る":
        if prev.pos1 == "動詞":
            return prev.cform.startswith("連用形")  # 伸びする: a 連用形 used as a noun
        return prev.pos1 in ("名詞", "副詞") and not prev.is_number
    if prev.pos1 == "動詞" and prev.cform.startswith("連用形") and (
            tok.orth in ASPECT_AUX or tok.lemma in POLITE_AFTER_RENYOU):
        return True
    return prev.pos1 == "助詞" and prev.lemma == "て" and is_aux_after_te(tok)


def is_aux_after_te(tok: Token) -> bool:
    """Is the verb ``tok`` (just after て) an auxiliary?  Compared on the lemma,
    so every spelling counts (ください, 下さい, くれ, 呉れる, もらっ, 貰う, ...);
    置く / 見る / 上げる written in kanji are main verbs (``AUX_KANJI_MAIN``)."""
    if tok.lemma not in AUX_AFTER_TE:
        return False
    return not (tok.lemma in AUX_KANJI_MAIN and _has_kanji(tok.surface))


def _has_kanji(s: str) -> bool:
    return any("\u4e00" <= ch <= "\u9fff" for ch in s)
