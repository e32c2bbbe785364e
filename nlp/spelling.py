"""Misspelt verbs read as the verb meant, or said to be unread (docs/language.md §9).

Run on each line's tokens before :mod:`casual` (whose わ typed for は must not read 座わって as
座は), it repairs what UniDic cannot tag as a verb and says every repair in ``notes``:

- **okurigana**: a verb's kanji followed by kana UniDic reads as something else (歩るいて: 歩 + る +
  いて; 座わって: 座 + わ + って) is tagged again with one kana after the kanji left out (歩いて),
  or with the one a user most often forgets put in (叩た -> 叩いた, 走て -> 走って);
  the repair stands when the kanji then opens a verb.  A kanji that opens a verb but that no such
  repair reads is said to be unread (``could not read 歩るて``), never dropped in silence;
- **drawn-out verbs**: ー or a small vowel after a verb's kana (おどろー, すわるぅ) is read as the
  vowel it draws out (おどろう) or left out, when that makes a verb UniDic did not see;
- **a kanji of the same sound**: a one-kanji noun and a verb that together sound like a library
  verb (指 + 刺した: ユビ + サス) are that verb (指さす).
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from .lexicon import LIBRARY_BY_READING, LIBRARY_VERBS
from .tagging import is_hiragana, katakana, tag
from .types import Token

#: What may follow a kanji that opens a misspelt verb: not a case or topic particle (手を, 前に, 本は)
#: nor a copula (本だ, 春らしい): those make the kanji a noun.
_NOUN_PARTICLES = frozenset(["格助詞", "係助詞", "接続助詞", "準体助詞"])
_COPULAS = frozenset(["だ", "です", "らしい", "ようだ", "みたい", "そうだ", "じゃ"])
#: Auxiliaries a repaired verb may end with (a verb read with any other is no repair: 歩っ + る + て).
_ENDINGS = frozenset("た だ ます ない ぬ ず れる られる せる させる たい う よう ちゃう じゃう てる とる はる です".split())
#: Kana a user leaves out after a verb's kanji, tried in this order after leaving one out fails.
_FORGOTTEN = ("い", "っ", "ん")
#: Endings a verb's dictionary form can have (does a kanji open a verb: 歩 + く).
_DICTIONARY_ENDINGS = "るくうむすぶつぐ"
#: Marks that draw a kana out, and the kana of the お row (drawn out, they stand for う: こー is こう).
_DRAWL = frozenset("ー〜～ぁぃぅぇぉ")
_O_ROW = frozenset("おこごそぞとどのほぼぽもよろょ")


def repair(line: str, offset: int, tokens: list[Token], notes: list[str]) -> list[Token]:
    """The tokens of ``line`` (starting at ``offset`` in the text) with misspelt verbs read as meant."""
    if "は" in line:
        tokens = _ha_verb(tokens, notes)
    if "んだ" in line or "んで" in line:
        tokens = _nasal_verb(tokens, notes)
    if "行ったり" in line:
        tokens = _to_and_fro(tokens)
    if "とお" in line or "とご" in line:
        tokens = _prefix_not_filler(tokens)
    drawn = not _DRAWL.isdisjoint(line)
    # both passes below read a one-character noun (or suffix) only: most lines have none
    singles = [k for k, t in enumerate(tokens) if len(t.surface) == 1 and t.pos1 in ("名詞", "接尾辞")]
    if not singles and not drawn:
        return tokens
    if any(k + 1 < len(tokens) and tokens[k + 1].pos1 == "動詞" for k in singles):
        tokens = _same_sound(tokens, notes)
    edited = None
    k = singles[0] if singles else len(tokens)  # no token before the first one-character noun is suspect
    while k < len(tokens):  # each repair tags the edited line again: read on from its tokens
        if len(tokens[k].surface) == 1 and _suspect(tokens, k):
            again = _okurigana(edited or _Line(line, offset), tokens[k], notes)
            if again is not None:
                edited, tokens = again
        k += 1
    return _drawn_out(edited or _Line(line, offset), tokens) if drawn else tokens


class _Line:
    """A line as repaired so far: its text, and where each of its characters was in the line as
    written (a character put in: where the one after it was), to put tokens back on the text."""

    __slots__ = ("text", "where", "length", "offset")

    def __init__(self, text: str, offset: int, where: list[int] | None = None, length: int | None = None):
        self.text, self.offset = text, offset
        self.where = list(range(len(text))) if where is None else where
        self.length = len(text) if length is None else length

    def at(self, pos: int) -> int:
        """Where the character written at ``pos`` (in the text) is in this line."""
        return self.where.index(pos - self.offset)

    def edited(self, at: int, kana: str) -> _Line:
        """This line with the character at ``at`` left out (``kana`` empty) or ``kana`` put in there."""
        if not kana:
            return _Line(self.text[:at] + self.text[at + 1:], self.offset, self.where[:at] + self.where[at + 1:],
                         self.length)
        return _Line(self.text[:at] + kana + self.text[at:], self.offset,
                     self.where[:at] + [self.place(at)] * len(kana) + self.where[at:], self.length)

    def place(self, i: int) -> int:
        """The position in the line as written of this line's character ``i`` (its end: the length)."""
        return self.where[i] if i < len(self.where) else self.length

    def tokens(self) -> list[Token]:
        """The line tagged, each token's offsets those of what it covers as written."""
        out = []
        for t in tag(self.text, 0):
            start, end = self.place(t.start), self.place(t.end) if t.end < len(self.text) else self.length
            out.append(replace(t, start=self.offset + start, end=self.offset + max(start, end)))
        return out


def _is_kanji(ch: str) -> bool:
    return "\u4e00" <= ch <= "\u9fff"


def _suspect(tokens: list[Token], k: int) -> bool:
    """A one-kanji noun (or suffix) right before kana that do not make it a noun of the sentence."""
    tok = tokens[k]
    if len(tok.surface) != 1 or not _is_kanji(tok.surface) or tok.pos1 not in ("名詞", "接尾辞"):
        return False
    if k + 1 >= len(tokens) or (k and tokens[k - 1].is_number):
        return False  # 3回する: a counter
    nxt = tokens[k + 1]
    if nxt.start != tok.end or not is_hiragana(nxt.surface[0]) or nxt.lemma == "為る":
        return False
    return not ((nxt.pos1 == "助詞" and nxt.pos2 in _NOUN_PARTICLES) or nxt.lemma in _COPULAS)


def _okurigana(line: _Line, kanji: Token, notes: list[str]) -> tuple[_Line, list[Token]] | None:
    """The line and its tokens with the kana after ``kanji`` repaired, or ``None`` (said when the kanji
    opens a verb)."""
    first = line.at(kanji.start)
    at = first + 1  # where the kana after the kanji start
    end = at
    while end < len(line.text) and is_hiragana(line.text[end]):
        end += 1
    for kana, shift in [("", -1)] + [(kana, +1) for kana in _FORGOTTEN]:
        new = line.edited(at, kana)
        again = tag(new.text, 0)
        if not _one_verb(again, first, end + shift):
            continue
        notes.append(f"read {line.text[first:end]} as {new.text[first:end + shift]} (a verb's okurigana)")
        return new, new.tokens()
    if _opens_verb(kanji.surface):
        notes.append(f"could not read {line.text[first:end]}: no verb of the dictionary is "
                     "written so (a misspelt verb?), it is left out")
    return None


def _one_verb(tokens: list[Token], start: int, end: int) -> bool:
    """Do ``tokens`` read ``[start, end)`` as one verb and its endings (歩い + て, 叩い + た), not a verb
    and leftovers (歩っ + る + て)?"""
    inside = [t for t in tokens if start <= t.start < end]
    if not inside or inside[0].start != start or inside[0].pos1 != "動詞" or inside[-1].end < end:
        return False
    return all((t.pos1 == "助動詞" and t.lemma in _ENDINGS) or (t.pos1 == "助詞" and t.pos2 in ("接続助詞", "終助詞"))
               or (t.pos1 == "動詞" and t.pos2 == "非自立可能") for t in inside[1:])


@lru_cache(maxsize=512)
def _opens_verb(kanji: str) -> bool:
    """Does ``kanji`` open a verb's dictionary form (歩 + く, 座 + る)?"""
    for ending in _DICTIONARY_ENDINGS:
        words = tag(kanji + ending, 0)
        if len(words) == 1 and words[0].pos1 == "動詞":
            return True
    return False


def _drawn_out(line: _Line, tokens: list[Token]) -> list[Token]:
    """おどろー -> おどろう, すわるぅ -> すわる: a drawl after kana read as a verb UniDic did not see."""
    text = line.text
    for q in range(1, len(text)):
        if text[q] not in _DRAWL or not is_hiragana(text[q - 1]):
            continue
        kana = line.place(q - 1) + line.offset  # the drawn-out kana, in the text
        if any(t.pos1 == "動詞" and t.start <= kana < t.end for t in tokens):
            continue  # すわるぅ: the verb is read already
        new = line.edited(q, "") if not (text[q - 1] in _O_ROW and text[q] == "ー") else \
            _Line(text[:q] + "う" + text[q + 1:], line.offset, line.where, line.length)  # the same length
        again = new.tokens()
        if any(t.pos1 == "動詞" and t.start <= kana < t.end for t in again):
            return again
    return tokens


def _ha_verb(tokens: list[Token], notes: list[str]) -> list[Token]:
    """まで + はしって: kana after a particle read as the topic は + 知って, where は + the verb is a library
    verb's sound (ハシル: 走る) and the verb as read is none of the library's: the one verb, said."""
    out: list[Token] = []
    for tok in tokens:
        prev = out[-1] if out else None
        if (tok.pos1 == "動詞" and prev is not None and prev.surface == "は" and prev.pos1 == "助詞"
                and prev.end == tok.start and len(out) > 1 and out[-2].pos1 == "助詞"
                and all("\u3041" <= ch <= "\u309f" for ch in tok.surface) and tok.lemma not in LIBRARY_VERBS):
            meant = LIBRARY_BY_READING.get("ハ" + tok.kana)
            if meant is not None:
                notes.append(f"read は{tok.surface} as {meant} (kana the dictionary split after a particle)")
                out[-1] = replace(tok, surface="は" + tok.surface, start=prev.start, lemma=meant, orth=meant,
                                  kana="ハ" + tok.kana, kana_form="ハ" + tok.kana_form)
                continue
        out.append(tok)
    return out


def _nasal_verb(tokens: list[Token], notes: list[str]) -> list[Token]:
    """ころんだけど, ぴょんととんだ: a verb in kana with its ん-form read as an adverb (ころん + だ) or as the
    adnominal とんだ (outrageous), where the kana before ん + ぶ / む / ぬ is a library verb's sound (コロブ:
    転ぶ) and no noun follows: the verb and its た / て, said."""
    out: list[Token] = []
    k = 0
    while k < len(tokens):
        tok, nxt = tokens[k], tokens[k + 1] if k + 1 < len(tokens) else None
        stem, ending = "", None
        if (tok.pos1 == "副詞" and tok.surface.endswith("ん") and nxt is not None and nxt.surface in ("だ", "で")
                and nxt.start == tok.end):
            stem, ending = tok.surface[:-1], nxt
        elif tok.pos1 == "連体詞" and tok.surface.endswith("んだ") and (nxt is None or nxt.pos1 != "名詞"):
            stem = tok.surface[:-2]
        meant = _nasal_reading(stem) if stem and is_hiragana(stem) else None
        if meant is None:
            out.append(tok)
            k += 1
            continue
        verb_end = tok.start + len(stem) + 1
        out.append(replace(tok, surface=stem + "ん", end=verb_end, pos1="動詞", pos2="一般", pos3="*", ctype="五段",
                           cform="連用形-撥音便", lemma=meant[0], orth=meant[0], kana=meant[1],
                           kana_form=katakana(stem + "ん")))
        te = (ending or tok).surface[-1] == "で"
        out.append(Token("で" if te else "だ", "助詞" if te else "助動詞", "接続助詞" if te else "*", "*", "*", "*",
                         "て" if te else "た", "て" if te else "た", "テ" if te else "タ", verb_end, verb_end + 1,
                         None, "デ" if te else "ダ"))
        notes.append(f"read {stem}ん{out[-1].surface} as {meant[0]} (a verb's ん-form the dictionary read as "
                     "another word)")
        k += 2 if ending is not None else 1
    return out


def _nasal_reading(stem: str) -> tuple[str, str] | None:
    """(library verb, its reading) whose ん-form is ``stem`` + ん (ころ -> 転ぶ), if any."""
    for end in "ぶむぬ":
        reading = katakana(stem + end)
        if reading in LIBRARY_BY_READING:
            return LIBRARY_BY_READING[reading], reading
    return None


def _prefix_not_filler(tokens: list[Token]) -> list[Token]:
    """深々とお辞儀をした: after と UniDic may read the お of お辞儀 as a filler (おー); before a noun it is the
    honorific prefix."""
    out = list(tokens)
    for k, t in enumerate(tokens[:-1]):
        nxt = tokens[k + 1]
        if t.surface in ("お", "ご") and t.pos1 == "感動詞" and nxt.pos1 == "名詞" and t.end == nxt.start:
            out[k] = replace(t, lemma="御", pos1="接頭辞", pos2="*")
    return out


def _to_and_fro(tokens: list[Token]) -> list[Token]:
    """行ったり来たり: UniDic reads this 行っ as 行う (to hold an event); before たり and 来る it is 行く."""
    out = list(tokens)
    for k, t in enumerate(tokens[:-2]):
        if (t.lemma == "行う" and t.surface == "行っ" and tokens[k + 1].surface == "たり"
                and any(x.lemma == "来る" for x in tokens[k + 2:k + 4])):
            out[k] = replace(t, lemma="行く", orth="行く")
    return out


def _same_sound(tokens: list[Token], notes: list[str]) -> list[Token]:
    """指 + 刺した: a one-kanji noun and the verb right after it that sound like a library verb."""
    out: list[Token] = []
    for tok in tokens:
        prev = out[-1] if out else None
        if (tok.pos1 == "動詞" and prev is not None and prev.pos1 == "名詞" and len(prev.surface) == 1
                and prev.end == tok.start):
            meant = LIBRARY_BY_READING.get(prev.kana_form + tok.kana)
            if meant is not None and prev.surface + tok.orth != meant:
                notes.append(f"read {prev.surface}{tok.orth} as {meant} (a kanji of the same sound)")
                out[-1] = replace(tok, surface=prev.surface + tok.surface, start=prev.start, lemma=meant,
                                  orth=meant, kana=prev.kana_form + tok.kana)
                continue
        out.append(tok)
    return out
