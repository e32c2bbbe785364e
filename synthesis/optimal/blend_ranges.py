"""Ranges of the blend intervals, paper 000 §4.2, eqs. (1)–(9).

Each method of :mod:`synthesis.optimal.method_select` blends the lower and the upper
body in separate intervals; this module gives, for each, the range its start
``t0`` and end ``t1`` may take (track frames, both ends included), the blend
kind, what is blended with what, and which ``Q_t`` applies (eq. (11) with the
foot-moving interval's length, or eq. (12)). :mod:`synthesis.optimal.blend_search`
then picks ``t0``, ``t1`` inside.

Discretisation: times are whole output frames. The paper's strict
inequalities become inclusive bounds on frames because a blend leaves frame
``t0`` as the first motion and frame ``t1`` as the second (``w(t0) = 0``,
``w(t1) = 1``): ``t_c0,end < t_s,begin`` is ``t0 >= c0_end`` when ``c0_end``
is the first frame after the core, and ``t_s,end < t_c1,begin`` is
``t1 <= c1_begin``. Every blend lasts at least ``min_len`` frames.

Sources: ``A`` is the track so far (the first motion, held on its last frame
after it ends), ``B`` the next motion as placed, ``Bad`` the next motion with
its lower body adapted to the first motion's feet (§4.2.3). The next motion
is only blended in where it is being played (``t1 >= b_first``).

Per method (``P0``/``P1`` the steps of :class:`~synthesis.optimal.method_select.Choice`):

- transition, eq. (1) lower ``motion-motion``, eq. (2) upper ``pose-pose``::

      c0_end <= t0 <= p1_end - 1,   p0_begin + 1 <= t1 <= c1_begin

  ``Q_t`` of the lower blend against the mean length of ``P0`` and ``P1``;
- connection, eq. (3) lower ``motion-pose`` from ``P0``'s lift, eq. (4) upper::

      t0 = p0_begin,                p0_begin + 1 <= t1 <= c1_begin      (3)
      p0_begin + 1 <= t0, t1 <= c1_begin                                (4)

- adaptation, eq. (5) lower ``pose-pose`` onto the adapted next motion, eq. (6)
  upper; eq. (5) fixes ``t0 = p0_begin``, but an adaptation is chosen exactly
  when the first motion has no step after its core: ``t0`` is searched from the
  first motion's core end up to its last frame (or the next motion's start if
  that is later) — the same lower bound eq. (6) gives the upper body::

      c0_end <= t0 <= max(a_end, b_first),  t1 <= m1_end - 1 (and <= p1_begin with a step)   (5)
      c0_end <= t0, t1 <= c1_begin                                                  (6)

  then eq. (7)/(9): the adapted lower body plays from ``t1(S0)`` to ``t0(S3)``
  (or to the end of the motion, eq. (9)); and with a step, eq. (8), the
  ``pose-motion`` blend back to the motion's own lower body over ``P1``::

      max(p1_begin, c1_begin, t1(S0)) <= t0 <= p1_end - min_len,  t1 = p1_end      (8)

  (``p1_begin`` added: the foot must be in the air while its place changes;
  ``c1_begin`` dropped when ``P1`` ends before the core).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from .method_select import Choice


@dataclass(frozen=True)
class Bounds:
    """Track frames a join's ranges are built from.

    ``c0_end``: first frame after the first core; ``c1``: ``[begin, end)`` of the second core;
    ``a_end``: one past the first motion's last scheduled frame; ``b_first``: the first frame of the
    second motion; ``m1_end``: one past its last; ``floor``: the earliest frame a blend may start
    (eq. (17)); ``min_len``: the shortest blend in frames.
    """

    c0_end: int
    c1: tuple[int, int]
    a_end: int
    b_first: int
    m1_end: int
    floor: int = 0
    min_len: int = 3


@dataclass(frozen=True)
class Range:
    """One blend interval to search: ``name`` (``S0``, ``S1``, ``S3``), ``part`` (``lower``/``upper``),
    ``kind``, inclusive ranges ``t0``/``t1`` (frames), ``p_len`` the foot-moving interval's length for
    eq. (11) (``None``: eq. (12)), ``src`` (from, to) among ``A``/``B``/``Bad``, ``eq`` the equation."""

    name: str
    part: str
    kind: str
    t0: tuple[int, int]
    t1: tuple[int, int]
    p_len: int | None
    src: tuple[str, str]
    eq: str
    relaxed: bool = False

    def feasible(self, min_len: int) -> bool:
        return self.t0[0] <= self.t0[1] and self.t1[0] <= self.t1[1] and self.t1[1] - self.t0[0] >= min_len

    def relax(self, min_len: int) -> "Range":
        """The range widened just enough to hold a blend of ``min_len`` frames (into a core if it must)."""
        t0 = (self.t0[0], max(self.t0)) if self.t0[1] < self.t0[0] else self.t0
        t1_hi = max(self.t1[1], t0[0] + min_len)
        t1 = (min(self.t1[0], t1_hi), t1_hi)
        return replace(self, t0=t0, t1=t1, relaxed=True)


def ranges(choice: Choice, b: Bounds) -> list[Range]:
    """The blend intervals of ``choice`` with their ranges (see the module docstring).

    For an adaptation with a step, ``S3``'s ``t0`` lower bound does not yet include ``t1(S0)``: the
    caller raises it once ``S0`` is found (:func:`after`).
    """
    c1b, _ = b.c1
    L = b.min_len
    lo = max(b.c0_end, b.floor)
    m = choice.method
    if m == "motion_transition":
        p0, p1 = choice.p0, choice.p1
        assert p0 is not None and p1 is not None  # a transition blends the steps P0 and P1
        t0 = (max(lo, b.b_first), p1.end - 1)
        t1 = (max(p0.begin + 1, b.b_first), c1b)
        p_len = int(round(0.5 * (p0.frames + p1.frames)))
        return [Range("S0", "lower", "motion-motion", t0, t1, p_len, ("A", "B"), "(1)"),
                Range("S1", "upper", "pose-pose", (lo, c1b - L), (max(p0.begin + 1, b.b_first), c1b),
                      None, ("A", "B"), "(2)")]
    if m == "motion_connection":
        p0 = choice.p0
        assert p0 is not None  # a connection blends the step P0
        t0 = (p0.begin, p0.begin)
        t1 = (max(p0.begin + 1, b.b_first), c1b)
        s1_lo = max(p0.begin + 1, b.floor)
        return [Range("S0", "lower", "motion-pose", t0, t1, p0.frames, ("A", "B"), "(3)"),
                Range("S1", "upper", "pose-pose", (s1_lo, c1b - L), (max(s1_lo, b.b_first), c1b),
                      None, ("A", "B"), "(4)")]
    if m in ("motion_adaptation_step", "motion_adaptation"):
        t0_hi = max(b.a_end - 1, b.b_first, lo)
        t1_hi = b.m1_end - 1
        if m == "motion_adaptation_step":
            assert choice.p1 is not None  # the step returned from
            t1_hi = min(t1_hi, choice.p1.begin)
        out = [Range("S0", "lower", "pose-pose", (lo, t0_hi), (max(lo + 1, b.b_first), t1_hi), None,
                     ("A", "Bad"), "(5)"),
               Range("S1", "upper", "pose-pose", (lo, c1b - L), (max(lo + 1, b.b_first), c1b), None,
                     ("A", "B"), "(6)")]
        if m == "motion_adaptation_step":
            p1 = choice.p1
            assert p1 is not None
            s3_lo = max(p1.begin, c1b) if max(p1.begin, c1b) <= p1.end - L else p1.begin
            out.append(Range("S3", "lower", "pose-motion", (s3_lo, p1.end - L), (p1.end, p1.end), p1.frames,
                             ("Bad", "B"), "(8)"))
        return out
    raise ValueError(f"unknown method {m!r}")


def after(r: Range, frame: int, min_len: int) -> Range:
    """``r`` with its start no earlier than ``frame`` (eq. (7): S3 begins after S0 ends)."""
    lo = max(r.t0[0], frame)
    hi = max(r.t0[1], lo) if r.t1[1] - lo >= min_len else lo
    return replace(r, t0=(lo, hi))
