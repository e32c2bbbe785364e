"""The registry of joiners of consecutive motions (:data:`REGISTRY`) and one entry point for them all:
``synthesize_with(method, tracks, fps, ...)``. ``METHODS`` means these names and nothing else in the package.

=============== =================================================================
method          what joins consecutive whole-body motions
=============== =================================================================
``optimal``     paper 000, optimal blending (:mod:`synthesis.optimal`), default
``constraint``  paper 003 / [6], constraint-based (:mod:`synthesis.constraint.engine`)
``pose``        closest poses, fixed-length linear blend (:mod:`synthesis.baselines`)
``crossfade``   fixed-length linear crossfade at the start (:mod:`synthesis.baselines`)
=============== =================================================================

Compositions (a body part laid onto a motion) are the same for all of them.
All return a :class:`synthesis.result.Result`.

``optimal`` keeps planted feet planted above all: when one of an actor's
joins still skates after its own fallbacks (a run pulled into a stop) — its blend's GMD skating ratio
above its two source clips' larger + 0.01 — that
actor is rendered by ``constraint`` instead if that one does not skate, and
the report's warnings say so, and each of that actor's joins carries ``engine: "constraint"`` and
``fallback_from: "optimal"`` in its metrics. The constraint engine runs the same join post-pass
(:mod:`synthesis.join.joinpass`), so the fallback's joins are held to the same criteria.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the command line reads METHODS without paying for scipy: engines are imported when run
    from .tracks import Track
    from .result import Result


@dataclass(frozen=True)
class Options:
    """What a user may ask of every joiner; each uses what applies to it (see :func:`synthesize_with`)."""

    smoothness: float = 0.5
    lock_feet: bool = True
    sway: bool = True


@dataclass(frozen=True)
class JoinMethod:
    """One way of joining consecutive whole-body motions: its name (``--blend NAME``), what it stands for,
    and ``run(tracks, fps, options) -> Result``."""

    name: str
    summary: str
    run: Callable[[Sequence[Track], float, Options], Result]


def _optimal(tracks: Sequence[Track], fps: float, o: Options) -> Result:
    from .optimal import synthesize_optimal

    if not o.lock_feet:
        return synthesize_optimal(tracks, fps, o.smoothness, lock_feet=False, sway=o.sway)
    raw = synthesize_optimal(tracks, fps, o.smoothness, lock_feet=True, sway=o.sway, finished=False)
    return _feet_first(raw, tracks, fps, o.sway)


def _constraint(tracks: Sequence[Track], fps: float, o: Options) -> Result:
    from .constraint.engine import synthesize

    return synthesize(tracks, fps, lock_feet=o.lock_feet, sway=o.sway)


def _baseline(name: str) -> Callable[[Sequence[Track], float, Options], Result]:
    def run(tracks: Sequence[Track], fps: float, o: Options) -> Result:
        from .baselines import synthesize_baseline

        return synthesize_baseline(tracks, fps, name, sway=o.sway)

    return run


#: The joining methods by name, in the order of the table above (the only registry of them).
REGISTRY: dict[str, JoinMethod] = {m.name: m for m in (
    JoinMethod("optimal", "paper 000, optimal blending", _optimal),
    JoinMethod("constraint", "paper 003 / [6], constraint-based joins", _constraint),
    JoinMethod("pose", "closest poses, fixed-length linear blend", _baseline("pose")),
    JoinMethod("crossfade", "fixed-length linear crossfade at the start", _baseline("crossfade")),
)}
#: Their names: the choices of ``--blend`` and ``text2anim compare --methods``.
METHODS: tuple[str, ...] = tuple(REGISTRY)
DEFAULT = "optimal"


class UnknownMethodError(ValueError):
    """A joining method that does not exist."""

    user_facing = True


def check_method(method: str) -> str:
    if method not in REGISTRY:
        raise UnknownMethodError(f"unknown blending method {method!r}; choose one of {', '.join(METHODS)}")
    return method


def synthesize_with(method: str, tracks: Sequence[Track], fps: float = 30.0, smoothness: float = 0.5,
                    lock_feet: bool = True, sway: bool = True) -> Result:
    """Tracks → :class:`~synthesis.result.Result` with the joiner ``method`` (see the table above).

    ``smoothness`` (0 time first … 1 smoothness first) is used by ``optimal`` only; ``lock_feet`` by
    ``optimal`` and ``constraint`` (the baselines never lock feet: that is what they stand for).
    """
    check_method(method)
    if not 0.0 <= float(smoothness) <= 1.0:
        raise UnknownMethodError(f"smoothness must be between 0 and 1, got {smoothness}")
    return REGISTRY[method].run(tracks, fps, Options(smoothness, lock_feet, sway))


def _skating_actors(result: Result) -> dict[str | None, list[tuple[int, int]]]:
    """Actor → the joins (first, second) of theirs whose blends skate more than their sources allow: the GMD
    ratio of the blend above the two source clips' larger + 0.01 (:func:`synthesis.join.measure.skating_exceeds`),
    the rule the benchmark judges the whole output by."""
    from .join.measure import skating_exceeds

    out: dict[str | None, list[tuple[int, int]]] = {}
    for j in result.joins:
        if skating_exceeds(j.metrics.get("skating_ratio", 0.0), j.metrics.get("source_skating_ratio", 0.0)):
            actor = result.actor_of(j.second)
            out.setdefault(actor, []).append((j.first, j.second))
    return out


def _feet_first(result: Result, tracks: Sequence[Track], fps: float, sway: bool) -> Result:
    """``result`` (its motions not yet finished) with every skating actor re-rendered by the constraint
    engine when that one is clean; every actor's motion finished (:func:`synthesis.finish.finish`), once."""
    from dataclasses import replace

    from .finish import finish
    from .assemble import same_length
    from .constraint.engine import synthesize
    from .played import fitted

    bad = _skating_actors(result)
    other = synthesize(tracks, fps, lock_feet=True, sway=sway, finished=False) if bad else None
    still = _skating_actors(other) if other is not None else {}
    swap = [a for a in bad if a not in still]
    idles = {t.actor: t.idle for t in tracks}
    if other is None or not swap:
        return replace(result, motions={actor: finish(m, idle=idles[actor]) for actor, m in result.motions.items()})
    motions, elements = dict(result.motions), dict(result.elements)
    for actor in swap:
        motions[actor] = other.motions[actor]
        elements.update({k: v for k, v in other.elements.items() if v.actor == actor})
    # the two engines' post-passes give the joins different times: every actor as long as the longest again
    motions = {actor: finish(m, idle=idles[actor]) for actor, m in same_length(motions).items()}
    joins = [j for j in result.joins if result.actor_of(j.second) not in swap]
    joins += [replace(j, metrics={**j.metrics, "engine": "constraint", "fallback_from": "optimal"})
              for j in other.joins if other.actor_of(j.second) in swap]
    src = {actor: (other if actor in swap else result).placed_paths.get(actor) for actor in motions}
    paths = {actor: fitted(p, motions[actor].n_frames) for actor, p in src.items() if p is not None}
    warnings = list(result.warnings) + [
        f"{actor or 'default'}: optimal blending left feet skating at join "
        f"{', '.join(f'{a}→{b}' for a, b in bad[actor])}; rendered with the constraint engine instead"
        for actor in swap]
    return replace(result, motions=motions, joins=joins, elements=elements, warnings=tuple(warnings),
                   placed_paths=paths)
