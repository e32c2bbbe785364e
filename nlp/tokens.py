"""Tokens: NFKC normalisation with an offset map, tagging line by line (:mod:`tagging`),
re-tagging of list-item 連用形, and number merging.
"""
from __future__ import annotations

import unicodedata
from functools import lru_cache

from . import casual, kana_names, keigo, spelling, spoken
from .numbers import merge_numbers
from .lexicon import KANA_NAMES
from .tagging import as_verb, katakana, tag, tagger
from .types import Token

__all__ = ["OffsetMap", "is_name", "normalize", "tagger", "tokenize", "unwrap_direction", "script_label_end"]

#: Half-width voiced sound marks: NFKC composes them with the kana before.
_HALFWIDTH_MARKS = {"\uff9e", "\uff9f"}


class OffsetMap:
    """Maps ranges of the normalised text back to the original text."""

    __slots__ = ("starts", "ends", "length")

    def __init__(self, starts: list[int], ends: list[int], length: int):
        self.starts = starts  # original start of the piece each character came from
        self.ends = ends  # original end of that piece
        self.length = length

    def span(self, a: int, b: int) -> tuple[int, int]:
        """Original ``(start, end)`` of normalised ``[a, b)``."""
        if a >= len(self.starts):
            return (self.length, self.length)
        start = self.starts[a]
        return (start, self.ends[b - 1]) if b > a else (start, start)


def normalize(text: str) -> tuple[str, OffsetMap]:
    """NFKC-normalise ``text``; return it with the map back to ``text``.

    Each base character is normalised together with the combining marks after
    it, so every normalised range maps back to whole original characters
    (ﾀﾞ -> ダ, １０ -> 10, ㌢ -> センチ).  Control characters, surrogates and
    private-use characters become spaces (the tagger is a C library; a NUL
    would cut the string), CR a newline.
    """
    if text.isascii() or unicodedata.is_normalized("NFKC", text):
        n = len(text)
        return _sanitize(text), OffsetMap(list(range(n)), list(range(1, n + 1)), n)
    parts: list[str] = []
    starts: list[int] = []
    ends: list[int] = []
    seg_start = 0
    for i in range(1, len(text) + 1):
        if i < len(text) and (unicodedata.combining(text[i]) or text[i] in _HALFWIDTH_MARKS):
            continue
        piece = unicodedata.normalize("NFKC", text[seg_start:i])
        parts.append(piece)
        starts.extend([seg_start] * len(piece))
        ends.extend([i] * len(piece))
        seg_start = i
    return _sanitize("".join(parts)), OffsetMap(starts, ends, len(text))


def _sanitize(norm: str) -> str:
    if norm.isprintable():
        return norm
    out = []
    for ch in norm:
        if ch in "\n\r":
            out.append("\n")
        elif ch.isprintable():
            out.append(ch)
        elif unicodedata.category(ch) in ("Zs", "Zl", "Zp", "Cc", "Cf", "Cs", "Co", "Cn"):
            out.append(" ")
        else:
            out.append(ch)
    return "".join(out)


def tokenize(norm: str, notes: list[str] | None = None) -> list[Token]:
    """Tag ``norm`` line by line; newlines become sentence-end tokens.

    Casual writing is repaired per line (``casual.repair``); what was read
    differently is appended to ``notes``.
    """
    tokens: list[Token] = []
    pos = 0
    said = [] if notes is None else notes
    for line in norm.split("\n"):
        if line.strip():
            tagged = spelling.repair(line, pos, _tag_line(line, pos), said)
            if kana_names.may_apply(line):
                tagged = kana_names.read_names(line, pos, tagged, said)
            if casual.may_apply(line):
                tagged = casual.repair(tagged, said)
            tokens.extend(unwrap_direction(tagged) if "(" in line else tagged)
        end = pos + len(line)
        if end < len(norm):
            tokens.append(Token("\n", "補助記号", "句点", "*", "*", "*", "\n", "\n", "", end, end + 1))
        pos = end + 1
    tokens = merge_numbers(_join_phrasal_verbs(_retag_list_items(tokens)))
    if keigo.may_apply(norm, tokens):
        tokens = keigo.plain(tokens)
    return spoken.plain(tokens) if spoken.may_apply(norm, tokens) else tokens


#: noun + に + なる read as one verb (the library's spelling): 横になる is lying down, not "becoming"
_PHRASAL = {"横": "横になる"}


def _join_phrasal_verbs(tokens: list[Token]) -> list[Token]:
    """横 + に + なって -> one verb token 横になって (lemma 横になる): UniDic reads なる as a state verb."""
    if not any(t.surface in _PHRASAL for t in tokens):
        return tokens
    out: list[Token] = []
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if (tok.surface in _PHRASAL and i + 2 < len(tokens) and tokens[i + 1].surface == "に"
                and tokens[i + 2].pos1 == "動詞" and tokens[i + 2].lemma == "成る"):
            v, verb = tokens[i + 2], _PHRASAL[tok.surface]
            out.append(Token(tok.surface + "に" + v.surface, "動詞", v.pos2, v.pos3, v.ctype, v.cform, verb, verb,
                             tok.kana + "ニナル", tok.start, v.end, None, tok.kana_form + "ニ" + v.kana_form))
            i += 3
            continue
        out.append(tok)
        i += 1
    return out


def unwrap_direction(tokens: list[Token]) -> list[Token]:
    """A stage direction wholly in brackets ((花子、窓を開ける), 花子:(座る), 行くぞ!(ボールを蹴る))
    is text to analyse, not a quotation: the brackets that wrap a whole sentence of the
    line (after a speaker label, a sentence end or a trailing mark such as 〜 or ♪, up to the
    line's or the sentence's end) are dropped; so are those right after a speaker label, wherever they close
    (母:(ため息をついて)もう、起きなさい: how the line is said, done)."""
    # a sentence ends at 。！？ and, in chat, at the mark it trails off with (いらっしゃいませ〜, やったー♪)
    label = script_label_end(tokens)
    starts = {label} | {k + 1 for k, t in enumerate(tokens)
                        if t.pos2 == "句点" or (t.pos1 == "補助記号" and t.pos2 == "一般")}
    drop = set()
    for s in starts:
        e = _direction_end(tokens, s, anywhere=s == label > 0)
        if e is not None:
            drop |= {s, e}
    return [t for k, t in enumerate(tokens) if k not in drop] if drop else tokens


def _direction_end(tokens: list[Token], s: int, anywhere: bool = False) -> int | None:
    """Index of the ``)`` closing a ``(`` at ``s`` when it closes the sentence (``(座る)。``; ``anywhere``: wherever it
    closes), else None."""
    if s >= len(tokens) or tokens[s].surface != "(":
        return None
    depth = 0
    for k in range(s, len(tokens)):
        depth += {"(": 1, ")": -1}.get(tokens[k].surface, 0)
        if depth == 0:  # the opening bracket closes here: a direction if the sentence ends with it
            ends = anywhere or k + 1 == len(tokens) or tokens[k + 1].pos2 == "句点"
            return k if ends and k - s >= 2 else None
    return None


def script_label_end(tokens: list[Token]) -> int:
    """Index just after a speaker label (花子:, お父さん:, 店員A:) opening the line, or 0."""
    for k, tok in enumerate(tokens[:8]):
        if tok.surface == ":" and k > 0:
            return k + 1
        if tok.pos1 not in ("名詞", "代名詞", "接頭辞", "接尾辞") or tok.pos2 == "数詞":
            return 0
    return 0


def _tag_line(line: str, offset: int) -> list[Token]:
    """Tag one line; repair the two ways kana-only text is mis-tagged (``_repair_kana``)."""
    return _repair_kana(line, offset, _tag_closed(line, offset))


def _tag_closed(line: str, offset: int) -> list[Token]:
    """Tag ``line`` as a sentence that ends: UniDic reads the last word of a line without a closing
    mark as it would read a word before more text (ボールけった: the noun けった; ボールけった。: the verb
    蹴っ + た), so such a line is tagged with 。 after it, and the 。 is left out again."""
    if line[-1] in _CLOSING:
        return tag(line, offset)
    tokens = tag(line + "。", offset)
    return tokens[:-1] if tokens[-1].surface == "。" and tokens[-1].start == offset + len(line) else tag(line, offset)


#: Marks a line that ends a sentence may end with (after NFKC).
_CLOSING = frozenset("。.!?」』)")


#: Particles that mark an actor or join actors (a hiragana name is re-split before one of them).
_ACTOR_PARTICLES = {"は": "係助詞", "が": "格助詞", "も": "係助詞", "と": "格助詞"}


def _repair_kana(line: str, offset: int, tokens: list[Token]) -> list[Token]:
    """Kana-only text: たろうは is tagged 助動詞 だ + ろう and たろうはて as た + 果て;
    て (手) before を is tagged the particle て.

    A content word cannot start a sentence as an auxiliary or particle, so a
    hiragana run there that begins with a name (``is_name``) before は/が/も/と is
    re-split as name + particle + the rest; a て directly before を is the noun 手.
    """
    out: list[Token] = []
    for i, tok in enumerate(tokens):
        starts = i == 0 or tokens[i - 1].pos1 == "補助記号"
        if starts and tok.pos1 in ("助動詞", "助詞") and _ends_in_hiragana(tok.surface):
            fixed = _split_name(line, offset, tok.start - offset)
            if fixed is not None:
                out.extend(fixed)
                break
        out.append(tok)
    if "てを" not in line:
        return out  # no て right before を
    for i, tok in enumerate(out[:-1]):
        nxt = out[i + 1]
        if tok.surface == "て" and tok.pos1 in ("助詞", "記号") and nxt.surface == "を" and nxt.pos1 == "助詞":
            out[i] = _as_hand(tok)
    return out


def _split_name(line: str, offset: int, at: int) -> list[Token] | None:
    run = line[at:at + 12]
    for k in range(min(len(run) - 1, 8), 1, -1):
        name, particle = run[:k], run[k]
        if particle in _ACTOR_PARTICLES and _is_hiragana(name) and (name in KANA_NAMES or is_name(name)):
            a = offset + at
            rest = _repair_kana(line, offset, tag(line[at + k + 1:], a + k + 1)) if at + k + 1 < len(line) else []
            return [Token(name, "名詞", "固有名詞", "人名", "*", "*", name, name, katakana(name), a, a + k,
                          None, katakana(name)),
                    Token(particle, "助詞", _ACTOR_PARTICLES[particle], "*", "*", "*", particle, particle,
                          katakana(particle), a + k, a + k + 1, None, katakana(particle))] + rest
    return None


def _as_hand(tok: Token) -> Token:
    return Token(tok.surface, "名詞", "普通名詞", "一般", "*", "*", "手", "手", "テ", tok.start, tok.end,
                 None, "テ")


def _is_hiragana(s: str) -> bool:
    return all("\u3041" <= ch <= "\u309f" or ch == "ー" for ch in s)


def _retag_list_items(tokens: list[Token]) -> list[Token]:
    """走り、跳び、転ぶ: UniDic tags 跳び as a noun; ``跳びます`` shows the verb."""
    out = list(tokens)
    for i, tok in enumerate(tokens[:-1]):
        nxt = tokens[i + 1]
        if (tok.pos1 == "名詞" and tok.pos2 == "普通名詞" and nxt.pos2 == "読点"
                and _ends_in_hiragana(tok.surface)):
            verb = as_verb(tok)
            if verb is not None:
                out[i] = verb
    return out


def _ends_in_hiragana(s: str) -> bool:
    return "\u3041" <= s[-1] <= "\u309f"


@lru_cache(maxsize=4096)
def is_name(surface: str) -> bool:
    """Can ``surface`` be a person's name?  UniDic tags 太郎 as a common noun
    in some contexts (同時に太郎は); with an honorific after it, a word that
    can be a given name is tagged 人名, a common noun (ボール, 公園) is not."""
    words = tagger()(surface + "さん")
    if len(words) != 2 or words[0].surface != surface:
        return False
    f = words[0].feature
    if f.pos3 == "人名":
        return True
    # たろうさん: a kana spelling is tagged a common noun whose lemma (太郎) is a name
    lemma = f.lemma or ""
    return (f.pos1 == "名詞" and _is_hiragana(surface) and lemma != surface
            and not _is_hiragana(lemma) and is_name(lemma))
