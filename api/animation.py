"""What :func:`text2anim.animate` returns: the time table, one motion per actor, the report, and what a user saves."""
from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from text2anim.core.atomic import Content, check_distinct, check_output_path, write_all

from text2anim.core.notice import Notice

from .wording import Terms

if TYPE_CHECKING:  # synthesis loads when a motion is made: text2anim.plan never imports it
    from text2anim.core.motion import Motion
    from text2anim.scene import Scene, Staging
    from text2anim.scheduler import TimeTable
    from text2anim.synthesis.result import Result

    from .planning import Planned

DEFAULT_ACTOR = "default"


@dataclass(frozen=True, eq=False)
class Animation:
    """The result of :func:`text2anim.animate`: time table, one motion per actor, the synthesis report.

    ``motions`` maps each actor's name (``"default"`` when the text names none)
    to its :class:`synthesis.Motion`, all on one clock starting at 0 s.
    """

    planned: Planned
    result: Result
    fps: float
    blend: str = "optimal"
    smoothness: float = 0.5
    synthesis_tracks: tuple = ()  # the synthesis input (source clips per element), for the report's join figures
    staging: Staging | None = None  # where the actors started (the staging stage)
    scene: Scene | None = None  # the actors placed where the text wants them, and the things (the scene stage)
    manners: tuple = ()  # manners.Styled per row with a manner: clip, modifiers or not shown (the manner stage)

    @property
    def text(self) -> str:
        return self.planned.analysis.text

    @property
    def table(self) -> TimeTable:
        return self.planned.table

    @property
    def motions(self) -> dict[str, Motion]:
        return {a or DEFAULT_ACTOR: m for a, m in self.result.motions.items()}

    @property
    def terms(self) -> Terms:
        """How the user names the synthesizer's elements and joins: the table's rows and verbs, seconds."""
        return Terms.of(self.table, self.synthesis_tracks)

    @property
    def warnings(self) -> tuple[str, ...]:
        """What the synthesizer could not honour, in the user's terms (:meth:`Terms.reword`), after the
        manners that are not shown (:mod:`text2anim.manners`): :attr:`notices`' sentences."""
        return tuple(n.text for n in self.notices)

    @property
    def notices(self) -> tuple[Notice, ...]:
        """:attr:`warnings` as :class:`core.notice.Notice` (a kind and its figures, for a front end to word): a
        manner not shown (``manner_not_shown``), then what the synthesizer could not honour (``synthesis``,
        ``row`` and ``verb`` of the first element it names when it names one)."""
        terms = self.terms
        unshown = tuple(n for n in (s.notice() for s in self.manners) if n is not None)
        return unshown + tuple(terms.notice(w) for w in self.result.warnings)

    @property
    def report(self) -> dict[str, Any]:
        """The synthesis report of docs/timetable.md §2, with the time table and per-element figures.

        ``actors`` holds each actor's whole-motion figures; every join gets ``quality``: the figures of
        :mod:`text2anim.quality` on a window around it next to its two source clips', all at 30 fps.
        """
        from text2anim.core.metrics import foot_skate

        from .quality import actor_quality, actor_series, join_quality, rounded

        per_actor = actor_series(self.result.motions)  # resampled and measured once for both
        whole = {}
        for (name, m), q in zip(self.motions.items(), actor_quality(self.result.motions, series_of=per_actor).values()):
            whole[name] = {"frames": m.n_frames, "duration": round(m.duration, 3),
                           "skating_ratio": round(q.skating_ratio, 4), "quality": rounded(q),
                           "foot_skate_cm_s": {s: round(f.mean_speed_cm_s, 3) for s, f in foot_skate(m).items()}}
        joins, terms = self.result.report()["joins"], self.terms
        for j, q in zip(joins, join_quality(self.result, self.synthesis_tracks, series_of=per_actor)):
            if q is not None:
                j["quality"] = q
            if "warnings" in j:
                j["warnings"] = [terms.reword(w if w.startswith("join ") else f"join {j['first']}→{j['second']}: {w}")
                                 for w in j["warnings"]]
        return {
            "text": self.text,
            "fps": self.fps,
            "synthesis": {"blend": self.blend, "smoothness": self.smoothness},
            "time_table": self.table.to_dict()["elements"],
            "joins": joins,
            "elements": {str(k): v.to_dict() for k, v in self.result.elements.items()},
            "actors": whole,
            **({"scene": self.scene.to_dict()} if self.scene is not None and not self.scene.empty else {}),
            **({"manners": [s.to_dict() for s in self.manners]} if self.manners else {}),
            "skipped": list(self.planned.skipped),
            **({"fallbacks": [f.to_dict() for f in self.planned.fallbacks]} if self.planned.fallbacks else {}),
            # what the text was read as where it differs from what is written (typos, 彼女 -> 花子)
            **({"notes": list(self.planned.analysis.notes)} if self.planned.analysis.notes else {}),
            "warnings": list(self.warnings),
        }

    # ---------------------------------------------------------------- for the viewer
    def tracks(self):
        from text2anim.output.viewer.types import Track

        return [Track(name, m) for name, m in self.motions.items()]

    def props(self):
        """The things of the scene as the viewer and the GLB draw them (:class:`output.viewer.types.Prop`)."""
        from text2anim.output.viewer.types import Prop

        if self.scene is None:
            return []
        return [Prop(t.name, t.shape, t.size, t.positions, t.rotations, self.fps, t.color) for t in self.scene.things]

    def spans(self):
        """Time-table elements and blend intervals as viewer spans."""
        from text2anim.output.viewer.types import Span

        out, terms = [], self.terms
        for e in self.table.elements:
            played = self.result.elements.get(e.id)
            start = played.start if played is not None and played.start is not None else e.start
            end = played.end if played is not None and played.end is not None else e.end
            part = f" [{e.body_part}]" if e.body_part else ""
            out.append(Span(e.actor or DEFAULT_ACTOR, f"{e.id} {e.verb} ({e.method}){part}", start, end, "element",
                            alt=f"{e.id} {e.clip} ({e.method}){part}"))
        for j in self.result.joins:
            actor = self.result.actor_of(j.second) or DEFAULT_ACTOR
            for iv in j.intervals:
                if iv.end > iv.begin:
                    out.append(Span(actor, f"{terms.label(j.first, j.second)} {iv.kind}", iv.begin, iv.end, "blend",
                                    iv.part))
        return out

    # ------------------------------------------------------------------- saving
    def bvh_paths(self, path: str | os.PathLike, suffix: str = ".bvh") -> dict[str, Path]:
        """Where :meth:`save_bvh` writes: ``path`` itself for one actor, ``stem_ACTOR.bvh`` for several
        (also the per-actor ``.glb`` on a glTF rig and ``.vrma`` files, with their ``suffix``)."""
        path = check_output_path(path)
        names = list(self.motions)
        if len(names) == 1:
            return {names[0]: path}
        return {n: path.with_name(f"{path.stem}_{n}{path.suffix or suffix}") for n in names}

    def outputs(self, *, bvh=None, html=None, glb=None, report=None, plot=None, export=None,
                vrma=None, top_view=None) -> dict[Path, Content]:
        """The files :meth:`save` writes, by path: their bytes (or, for the plots, a function that draws them).

        ``export`` (:class:`text2anim.export.ExportOptions`) applies to the BVH files (the user's rig,
        root motion or in place, units, loop), to the GLB (all but units; with a glTF/VRM rig, one file
        per actor: the user's character animated) and to the VRM Animation ``vrma`` (one per actor:
        the rig's proportions when it is a VRM avatar; loop and in place). The scene's :meth:`props` go
        into the viewer page, the GLB (where ``export`` puts the bodies: :meth:`exported_props`) and the
        ``top_view`` picture; the BVH and VRM Animation files are the bodies alone.
        """
        from text2anim.output.bvh_write import format_bvh

        files: dict[Path, Content] = {}

        def add(path, content) -> None:
            path = check_output_path(path)
            check_distinct([*files, path])
            files[path] = content

        moved = None  # each actor's motion as ``export`` asks, in metres: retargeted once for the BVH and the GLB
        if export is not None and not export.is_default and (bvh is not None or glb is not None):
            moved = self.exported_motions(export, units=False)
        if bvh is not None:
            from .export import in_units

            motions = self.motions if moved is None else {n: in_units(m, export) for n, m in moved.items()}
            for name, path in self.bvh_paths(bvh).items():
                add(path, format_bvh(motions[name]).encode())
        if html is not None:
            from text2anim.output.viewer import render_html

            add(html, render_html(self.tracks(), self.spans(), title=self.text, props=self.props()).encode())
        if glb is not None:
            from text2anim.output.gltf import glb_bytes

            if moved is None:
                add(glb, glb_bytes(self.tracks(), props=self.props()))
            else:
                from .export import glb_files

                out = glb_files(moved, export, self.exported_props(export))
                if isinstance(out, bytes):
                    add(glb, out)
                else:
                    for name, path in self.bvh_paths(glb, ".glb").items():
                        add(path, out[name])
        if vrma is not None:
            from text2anim.output.vrma import vrma_bytes

            from .export import ExportOptions, vrma_motion

            export = export or ExportOptions()
            self._check_loop(export)
            for name, path in self.bvh_paths(vrma, ".vrma").items():
                add(path, vrma_bytes(vrma_motion(self.motions[name], export)))
        if report is not None:
            add(report, (json.dumps(self.report, ensure_ascii=False, indent=2) + "\n").encode())
        if plot is not None:
            add(check_plot_path(plot), self._plot_writer(Path(plot).suffix))
        if top_view is not None:
            add(check_plot_path(top_view, TOP_VIEW), self._top_view_writer(Path(top_view).suffix))
        return files

    def exported_props(self, export=None) -> list:
        """The scene's :meth:`props` where ``export`` puts the bodies (:func:`text2anim.export.export_props`: scaled
        with a rig, none under ``--in-place`` or ``--loop``)."""
        if export is None:
            return self.props()
        from .export import export_props

        return export_props(self.props(), self.motions, export)

    def exported_motions(self, export=None, *, units: bool = True) -> dict[str, Motion]:
        """Each actor's motion as ``export`` asks for it (unchanged without one); ``units=False`` keeps metres."""
        if export is None or export.is_default:
            return self.motions
        from .export import export_motion

        self._check_loop(export)
        return {n: export_motion(m, export, units=units) for n, m in self.motions.items()}

    def _check_loop(self, export) -> None:
        """``--loop`` on a text that is not one cyclic motion: :class:`text2anim.export.ExportError`."""
        from .export import check_loopable

        if export.loop:
            check_loopable(list(self.table.elements),
                           {k: bool(getattr(c, "cyclic", False)) for k, c in self.planned.clips.items()})

    def save(self, *, bvh=None, html=None, glb=None, report=None, plot=None, export=None, vrma=None,
             top_view=None) -> list[Path]:
        """Write the chosen outputs all-or-nothing (:func:`core.atomic.write_all`); returns their paths.

        Two outputs on one path are refused before anything is written; if one
        file cannot be written, none is, and files that existed are left as they were.
        """
        return write_all(self.outputs(bvh=bvh, html=html, glb=glb, report=report, plot=plot, export=export,
                                      vrma=vrma, top_view=top_view))

    def save_bvh(self, path: str | os.PathLike, export=None) -> list[Path]:
        """One BVH file per actor (see :meth:`bvh_paths`), all-or-nothing; ``export`` as in :meth:`outputs`."""
        return self.save(bvh=path, export=export)

    def save_html(self, path: str | os.PathLike) -> Path:
        return self.save(html=path)[0]

    def save_glb(self, path: str | os.PathLike, export=None) -> list[Path]:
        """The GLB (one per actor on a glTF rig); ``export`` as in :meth:`outputs`."""
        return self.save(glb=path, export=export)

    def save_vrma(self, path: str | os.PathLike, export=None) -> list[Path]:
        """One VRM Animation file per actor; ``export`` as in :meth:`outputs`."""
        return self.save(vrma=path, export=export)

    def save_report(self, path: str | os.PathLike) -> Path:
        return self.save(report=path)[0]

    def save_plot(self, path: str | os.PathLike) -> Path:
        """Upper/lower-body speed curves (Fig. 5 of paper 000) with the blend intervals shaded."""
        return self.save(plot=path)[0]

    def save_top_view(self, path: str | os.PathLike) -> Path:
        """The scene seen from above (:mod:`output.topview`): the actors' paths and facings, the elements where they
        start, the props' footprints."""
        return self.save(top_view=path)[0]

    def _top_view_writer(self, suffix: str):
        """A function drawing the top view into the path it is given (format from ``suffix``)."""
        from text2anim.output.topview import plot_top_view

        tracks, spans, props = self.tracks(), self.spans(), self.props()
        return _drawn_into(suffix, lambda out: plot_top_view(tracks, out, spans, props, title=self.text))

    def _plot_writer(self, suffix: str):
        """A function drawing the speed plot into the path it is given (format from ``suffix``)."""
        from text2anim.output.plots import plot_speeds

        spans = self.spans()  # each motion labelled by its row and verb (else its clip), the blends shaded
        return _drawn_into(suffix, lambda out: plot_speeds(self.motions, out, spans, title=self.text))


def _drawn_into(suffix: str, draw):
    """A writer for :func:`core.atomic.write_all` of a figure ``draw(path)`` writes: the plots pick the format from
    the name and write atomically, so it draws into a private folder under ``suffix``, then moves the picture
    onto the temporary it is given."""
    def write(tmp: Path) -> None:
        with tempfile.TemporaryDirectory(dir=tmp.parent, prefix=".t2a-plot.") as d:
            out = Path(d) / f"plot{suffix}"
            draw(out)
            os.replace(out, tmp)

    return write


#: What ``--plot`` and ``--top-view`` draw, as :func:`check_plot_path` names them.
SPEED_PLOT, TOP_VIEW = "a speed plot (--plot)", "a top view (--top-view)"


def check_plot_path(path: str | os.PathLike, what: str = SPEED_PLOT) -> Path:
    """A path for a figure (``what``: the speed plot, the top view): writable (:func:`core.atomic.check_output_path`),
    its suffix a picture format, and matplotlib installed (:func:`core.extras.require`)."""
    from text2anim.core import extras
    from text2anim.output.plots import FORMATS, PlotError

    path = check_output_path(path)
    extras.require("matplotlib", what)
    if path.suffix.lower().lstrip(".") not in FORMATS:
        raise PlotError(f"{path}: cannot tell the image format from the suffix; use one of "
                        + ", ".join("." + f for f in FORMATS))
    return path


__all__ = ["SPEED_PLOT", "TOP_VIEW", "Animation", "check_plot_path"]
