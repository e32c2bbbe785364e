"""The values the nlp stage hands to the next stage (the scheduler).

All are frozen dataclasses.  ``Analysis.to_dict()`` is the JSON object of
``docs/language.md`` §5, field for field.
"""
from __future__ import annotations

from dataclasses import dataclass, field

#: Methods a constraint can ask for (docs/timetable.md §1 uses the same names).
CONSTRAINT_METHODS = ("connection", "transition", "composition")


@dataclass(slots=True, eq=False)
class Token:
    """One morpheme of the NFKC-normalised text (offsets into that text).

    Never changed once made (a changed token is a new one, ``dataclasses.replace``), but not a
    frozen dataclass: a text makes and remakes dozens of them, and a frozen dataclass's
    ``__init__`` costs six times a plain one's (a sixth of the whole analysis).  It stays in the
    nlp stage."""

    surface: str
    pos1: str
    pos2: str
    pos3: str
    ctype: str
    cform: str
    lemma: str
    orth: str
    kana: str  # reading of the base form (kanaBase)
    start: int
    end: int
    value: float | None = None  # numbers only (merged digits / kanji numerals)
    kana_form: str = ""  # reading of the form as written (伸び -> ノビ)
    honorific: bool = False  # a verb keigo.py read from an honorific form (お立ちになる, いらっしゃる)

    @property
    def is_number(self) -> bool:
        return self.value is not None


@dataclass(frozen=True, slots=True)
class Bunsetsu:
    """A phrase: a content word plus its particles, auxiliaries, punctuation.

    ``head`` is the index of the bunsetsu this one depends on (``None`` for
    the last one of a sentence); ``role`` says what the analyzer made of it
    and ``why`` how the head was chosen, for ``parse --explain``.  ``persons``
    are the persons it names, by the names the actor field uses, pronouns and
    group words resolved (彼女に -> ("花子",), 二人で -> ("太郎", "花子");
    docs/language.md §9), whatever its particle.
    """

    index: int
    text: str
    span: tuple[int, int]
    sentence: int
    role: str = ""
    head: int | None = None
    why: str = ""
    persons: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class MotionSpec:
    """One motion the text asks an actor to perform (docs/language.md §1-§2)."""

    id: int
    actor: str | None
    verb: str
    object: str | None = None
    body_part: str | None = None
    repeat: int = 1
    speed: float = 1.0
    duration: float | None = None
    span: tuple[int, int] = (0, 0)
    hold: bool = False  # たまま: held at its end pose while the other motion plays
    reading: str = ""  # katakana reading of the verb, for a database fallback
    #: seconds before the motion starts when it opens its actor's track and the
    #: text opens with a delay (3秒後に太郎が歩く); later motions carry delays on
    #: their constraints instead.
    delay: float | None = None
    written: str = ""  # the verb as the user spelled it, dictionary form (登る for verb 上る)
    #: the verb with its を-noun as written, dictionary form (足を止める), when it has one: a clip
    #: that declares the phrase plays it (docs/language.md §2)
    phrase: str = ""
    #: a manner word the text gives the motion (大股で, 嬉しそうに; a mimetic in hiragana: よろよろ, §7.9)
    manner: str | None = None
    #: the style the manner word gives (§2.1: one of ``core.styles.STYLES``) and its intensity (1: plain)
    style: str | None = None
    intensity: float = 1.0
    #: whom or what the motion is directed at, as written (a person by the actor's name: 花子), its role
    #: (goal, source, addressee, patient, recipient, partner, support, destination, at) and the side of it
    #: (front, behind, beside, near, on, left, right): docs/language.md §8
    target: str | None = None
    target_role: str | None = None
    target_side: str | None = None
    target_person: bool = False  # the target is a person (a name, a person noun), not a thing or a place

    def to_dict(self, extra: bool = False) -> dict:
        d = {
            "id": self.id, "actor": self.actor, "verb": self.verb,
            "object": self.object, "body_part": self.body_part,
            "repeat": self.repeat, "speed": self.speed, "duration": self.duration,
            "span": [self.span[0], self.span[1]],
        }
        if extra or self.delay is not None:
            d["delay"] = self.delay  # the §5 object gains it only when the text opens with one
        if extra or self.manner is not None:
            d["manner"] = self.manner  # likewise only when the text gives one
        if extra or self.style is not None:
            d.update(style=self.style, intensity=self.intensity)
        if extra or self.target is not None:  # §8: only when the motion is directed at someone or something
            d.update(target=self.target, target_role=self.target_role, target_side=self.target_side,
                     target_person=self.target_person)
        if extra:
            d["hold"] = self.hold
            d["reading"] = self.reading
            d["written"] = self.written
            d["phrase"] = self.phrase
        return d


@dataclass(frozen=True, slots=True)
class Constraint:
    """A temporal constraint between motion ``first`` and motion ``second``.

    ``relation`` is ``serial`` or ``parallel``; ``overlap`` is ``None`` for a
    parallel relation; ``delay`` is seconds or ``None``; ``method`` is what the
    time table records for ``second`` (see ``CONSTRAINT_METHODS``).  ``cue`` names the
    words that produced the constraint (only in the extended JSON).
    """

    first: int
    second: int
    relation: str
    overlap: bool | None
    delay: float | None
    method: str
    cue: str = ""

    def to_dict(self, extra: bool = False) -> dict:
        d = {
            "first": self.first, "second": self.second, "relation": self.relation,
            "overlap": self.overlap, "delay": self.delay, "method": self.method,
        }
        if extra:
            d["cue"] = self.cue
        return d


@dataclass(frozen=True, slots=True)
class Analysis:
    """The result of ``nlp.analyze``: motions, constraints and the phrases."""

    text: str
    motions: tuple[MotionSpec, ...]
    constraints: tuple[Constraint, ...]
    #: each phrase as ``(index, (start, end), sentence, role, head, why, persons)``, ``span`` in ``text``:
    #: the :class:`Bunsetsu` of :attr:`bunsetsu`, made when asked (``parse --explain``; most analyses never are)
    phrases: tuple[tuple, ...] = field(default=(), compare=False, repr=False)
    #: what was read differently from how it is written (typos: 太郎わ -> 太郎は, 手を降る ->
    #: 手を振る), one sentence each, for stderr and ``parse --explain``
    notes: tuple[str, ...] = field(default=(), compare=False)

    @property
    def bunsetsu(self) -> tuple[Bunsetsu, ...]:
        """The phrases of the text with the head each depends on and what the analyzer made of them."""
        return tuple(Bunsetsu(i, self.text[a:b], (a, b), sentence, role, head, why, persons)
                     for i, (a, b), sentence, role, head, why, persons in self.phrases)

    def to_dict(self, extra: bool = False) -> dict:
        """docs/language.md §5; ``extra`` adds ``hold``, ``reading``, ``written``, ``phrase`` and ``cue``."""
        return {
            "text": self.text,
            "motions": [m.to_dict(extra) for m in self.motions],
            "constraints": [c.to_dict(extra) for c in self.constraints],
        }

    def to_json(self, indent: int | None = 2, extra: bool = False) -> str:
        """The JSON text of ``to_dict``; with ``indent``, one motion or
        constraint a line, as docs/language.md §5 shows it."""
        import json  # lazy: keeps the import of the stage light for cold starts

        data = self.to_dict(extra)
        if indent is None:
            return json.dumps(data, ensure_ascii=False)
        pad = " " * indent

        def items(key: str) -> str:
            rows = [pad * 2 + json.dumps(x, ensure_ascii=False) for x in data[key]]
            return "[\n" + ",\n".join(rows) + "\n" + pad + "]" if rows else "[]"

        return ("{\n" + f'{pad}"text": {json.dumps(data["text"], ensure_ascii=False)},\n'
                + f'{pad}"motions": {items("motions")},\n'
                + f'{pad}"constraints": {items("constraints")}\n' + "}")
