"""A self-contained HTML page that plays the animation: :func:`render_html`.

The page is one file that works offline from ``file://``: the template
(``viewer.html``), the player (``viewer.js``) and the motion data are inlined.

**Renderer: our own, on Canvas 2D, not three.js.** The page only has to show
stick figures (bones as shaded capsules, joints as dots), a few simple things,
a ground grid and a timeline, which a perspective projection plus
painter's-algorithm sorting of ~60 bones per actor draws in well under a
millisecond. Our template and player are ~41 KB, unminified (~11 KB more for
the things, only in a page that has some); three.js' minified module build alone is
~700 KB (plus its MIT notice) and would be inlined into *every* page a user
writes, to draw the same lines. Canvas 2D also needs no WebGL, so it renders identically in
headless Chromium without a GPU, on remote desktops and in old laptops' browsers.
Users who want meshes, lights and a real scene get the GLB
(:mod:`output.gltf`), which Blender and three.js load.

**Data.** Python does the forward kinematics: per actor, the world positions
of every joint and BVH end site, rounded to millimetres, root-relative
(``int16``) plus the root (``int32``), differenced over time, laid out per
coordinate, deflated and base64-encoded; the page inflates it with the
browser's ``DecompressionStream`` (Chrome 80, Firefox 113, Safari 16.4). A
10 s, 31-joint clip at 30 fps (end sites included) takes 21-30 KB instead of
~97 KB raw, so its whole page is 60-70 KB (``compress=False`` writes the
raw ``int16`` form, for browsers without ``DecompressionStream``).
Motions faster than ``max_fps`` are resampled to it (the page interpolates
between frames). Foot contacts (:mod:`core.contacts`) are shown as rings
on the floor.

**Things of the scene** (``props``: :class:`Prop`, a ball, a chair): under
``"props"`` in the data, only when there are some, each with its name, shape,
colour, size and the parts of its shape (:func:`output.shapes.parts`:
``[kind 0 box | 1 cylinder | 2 ellipsoid, cx, cy, cz, sx, sy, sz, axis]``,
metres in its own frame), and per frame (resampled to ``max_fps`` with the
actors) its centre in millimetres and its quaternion times 32767, as ``int32``
differences over time, one row per coordinate, deflated like the joints; a
thing that never moves is one frame. ``props.js`` is inlined into the player
(at :data:`PROPS_SLOT`) only then, so a page without things carries neither
their data nor their code. It draws each part face by face, the faces turned
away from the camera culled, lit from above (a ball as a shaded disc), and
sorts the parts in among the actors: before a part is drawn, every actor whose
picture it overlaps paints its bones farther than the part (so a sitter's
shins cover the chair's front legs, the chair's back hides a hand behind it).
Each thing has a soft shadow, its name above it and a round chip in the legend;
the home camera frames the things too.

**Japanese text** (the title, names, verbs, the time table) is drawn with a subset of the package's own
Japanese font embedded in the page for the characters it shows (:mod:`output.embedded_font`; 5.3 KB for
``太郎は走って、ボールを蹴る。``): on a machine without a Japanese font it showed as boxes. The page's CSS lists
that family first (it holds only CJK characters; Latin text falls through to the system's font).

Sizes, the seed sentence ``太郎は走って、ボールを蹴る。`` (one actor, 4 s): 54,548
bytes before things existed, 55,594 without things now (the hooks); the
two-actor test scene (7.3 s, 76.8 KB) with a ball in a waving hand and a still
chair: 91.8 KB, ``props.js`` 11.3 KB, the ball's data 3.3 KB (its turn on every
frame most of it), the chair's 0.6 KB.
"""
from __future__ import annotations

import base64
import html
import json
import math
import os
import re
import zlib
from importlib import resources

import numpy as np

from text2anim.core.atomic import atomic_write_text
from text2anim.core.motion import Motion
from .. import embedded_font
from .types import Prop, Span, Track, as_props, as_spans, as_tracks

__all__ = ["PALETTE", "Prop", "Span", "Track", "render_html", "viewer_data", "viewer_page"]

#: Actor colours, in order (chosen to stay distinct on the dark background and for colour-blind viewers).
PALETTE = ("#4f9cf9", "#f5884a", "#4cc38a", "#c678f5", "#f2c94c", "#ef5b7b", "#3dc9d6", "#a3a3a3")


def _resample_positions(pos: np.ndarray, fps: float, new_fps: float) -> np.ndarray:
    """Linear interpolation of world positions ``(T, N, 3)`` at ``new_fps``, same first and last time."""
    T = len(pos)
    if T < 2 or new_fps >= fps:
        return pos
    t_end = (T - 1) / fps
    n_new = int(math.floor(t_end * new_fps + 1e-9)) + 1
    t = np.arange(n_new) / new_fps * fps  # in old-frame units
    i0 = np.minimum(np.floor(t).astype(int), T - 2)
    w = (t - i0)[:, None, None]
    return pos[i0] * (1 - w) + pos[i0 + 1] * w


def _encode(arr: np.ndarray, compress: bool) -> str:
    data = arr.tobytes()
    if compress:
        data = zlib.compress(data, 6)  # zlib's default: 3 % larger than 9 on these frames, 8x faster (0.05 s a story)
    return base64.b64encode(data).decode("ascii")


#: The body's capsule radii (m, for a 1.7 m person) by body part, from the part's first bone outwards: a
#: drawn character with a body (shoulders, hips, limbs thinning to the hands and feet) instead of a stick figure.
BODY_RADII = {"torso": (0.12,), "hips": (0.11,), "head": (0.05,), "left_leg": (0.085, 0.075, 0.055, 0.04),
              "right_leg": (0.085, 0.075, 0.055, 0.04), "left_arm": (0.05, 0.045, 0.036, 0.03),
              "right_arm": (0.05, 0.045, 0.036, 0.03)}


def _body_radii(bm, parents: list[int], n_points: int, stick: np.ndarray, height: float) -> list[float]:
    """Per point, the radius (m) of the body's capsule for the bone ending there (:data:`BODY_RADII` by the part
    of the bone's parent joint and its depth in that part; at least the stick figure's; fingers as they are)."""
    part = {j: g for g in BODY_RADII for j in bm.groups.get(g, ())}
    hands = set(bm.hands.values())
    out = []
    for i in range(n_points):
        p = parents[i]
        depth, q = 0, parents[p] if p >= 0 else -1
        while q >= 0 and part.get(q) == part.get(p):
            depth, q = depth + 1, parents[q]
        radii = BODY_RADII.get(part.get(p, ""), ())
        below_hand = p in hands or any(a in hands for a in _ancestors(parents, p))
        r = stick[i] if p < 0 or not radii or below_hand else max(stick[i], radii[min(depth, len(radii) - 1)] * height / 1.7)
        out.append(round(float(r), 4))
    return out


def _ancestors(parents: list[int], j: int):
    while j >= 0:
        j = parents[j]
        if j >= 0:
            yield j


def _bone_info(motion: Motion, n_points: int, parents: list[int]) -> dict:
    """Per-point drawing hints: capsule radius (m) of the bone ending at each point, head point, feet."""
    skel = motion.skeleton
    rest = skel.rest_positions()
    ends = [rest[j] + o for j, o in skel.end_sites]
    rest_all = np.vstack([rest, *ends]) if ends else rest
    lengths = np.array([np.linalg.norm(rest_all[i] - rest_all[parents[i]]) if parents[i] >= 0 else 0.0
                        for i in range(n_points)])
    height = max(skel.height(), 1e-6)
    radius = np.clip(lengths * 0.22, 0.012 * height / 1.7, 0.045 * height / 1.7)
    info = {"radius": [round(float(r), 4) for r in radius], "head": -1, "headRadius": round(0.09 * height / 1.7, 4),
            "feet": [], "height": round(float(height), 3)}
    try:
        from text2anim.core.bodyparts import body_map

        bm = body_map(skel)
    except Exception:  # an unusual skeleton: draw it all the same, without the extras
        return info
    # Thicker torso and thighs, thinner hands and fingers.
    for g, scale in (("torso", 1.35), ("hips", 1.35)):
        for j in bm.groups.get(g, ()):
            for i in range(n_points):
                if parents[i] == j:
                    radius[i] *= scale
    for side in ("left", "right"):
        hand = bm.hands[side]
        below = {hand}
        for i in range(n_points):
            if parents[i] in below:
                below.add(i)
        for i in below - {hand}:
            radius[i] = min(radius[i], 0.014 * height / 1.7)
    info["radius"] = [round(float(r), 4) for r in radius]
    info["body"] = _body_radii(bm, parents, n_points, radius, height)
    head = bm.head
    kids = [i for i in range(n_points) if parents[i] == head]
    info["head"] = int(kids[0]) if kids else int(head)  # the head's end site: the sphere goes between
    info["headBase"] = int(head)
    info["feet"] = [[int(a), int(t)] for a, t in (bm.feet["left"], bm.feet["right"])]
    return info


def _facing(motion: Motion) -> float:
    """Heading (radians about +Y, 0 = facing +Z) of the character on its first frame; 0 if unknown."""
    try:
        from text2anim.core.bodyparts import body_map

        bm = body_map(motion.skeleton)
        left = [bm.feet["left"][0], bm.hands["left"]]
        right = [bm.feet["right"][0], bm.hands["right"]]
        p = motion.positions[0]
        across = p[left].mean(axis=0) - p[right].mean(axis=0)
    except Exception:
        return 0.0
    fwd = np.cross(across, [0.0, 1.0, 0.0])  # left × up points forward for a Y-up right-handed body
    if np.hypot(fwd[0], fwd[2]) < 1e-6:
        return 0.0
    return float(math.atan2(fwd[0], fwd[2]))


def _contacts(motion: Motion, n_out: int, fps_out: float) -> str:
    """Per output frame: ``"0"`` none, ``"1"`` left, ``"2"`` right, ``"3"`` both feet in contact; ``""`` if unknown."""
    try:
        from text2anim.core.contacts import detect_contacts

        state = detect_contacts(motion).state()
    except Exception:
        return ""
    idx = np.minimum(np.round(np.arange(n_out) / fps_out * motion.fps).astype(int), len(state) - 1)
    return "".join("0123"[int(s)] for s in state[idx])


def _actor_data(track: Track, color: str, max_fps: float, compress: bool) -> dict:
    m = track.motion
    skel = m.skeleton
    J = skel.n_joints
    pos = m.positions
    parents = [int(p) for p in skel.parents] + [int(j) for j, _ in skel.end_sites]
    if skel.end_sites:
        pos = np.concatenate([pos, m.end_site_positions()], axis=1)
    fps = float(m.fps)
    if fps > max_fps:
        out_fps = float(max_fps)
        pos = _resample_positions(pos, fps, out_fps)
    else:
        out_fps = fps
    if not np.all(np.isfinite(pos)):
        raise ValueError(f"track {track.name!r}: the motion has non-finite joint positions")
    q = np.round(pos * 1000.0).astype(np.int64)  # mm
    root = q[:, 0, :]
    rel = q - root[:, None, :]
    if np.abs(rel).max(initial=0) > 16000 or np.abs(root).max(initial=0) > 2**30:
        raise ValueError(f"track {track.name!r}: the character is more than 16 m across or 1000 km away")
    # Differences over time (small numbers deflate well), one row per coordinate.
    d_rel = np.diff(rel, axis=0, prepend=0).astype("<i2").transpose(1, 2, 0)  # (N, 3, T)
    d_root = np.diff(root, axis=0, prepend=0).astype("<i4").T  # (3, T)
    names = list(skel.names) + [f"{skel.names[j]}_end" for j, _ in skel.end_sites]
    return {
        "name": track.name,
        "color": color,
        "fps": out_fps,
        "frames": int(len(q)),
        "points": int(len(parents)),
        "joints": J,
        "parents": parents,
        "names": names,
        "root": _encode(np.ascontiguousarray(d_root), compress),
        "rel": _encode(np.ascontiguousarray(d_rel), compress),
        "contact": _contacts(m, len(q), out_fps),
        "facing": round(_facing(m), 4),
        **_bone_info(m, len(parents), parents),
    }


def _prop_data(prop: Prop, max_fps: float, compress: bool) -> dict:
    """A thing of the scene for the page: its parts (:func:`output.shapes.parts`: kind number, centre, size,
    axis) and per frame its centre in millimetres and its quaternion times 32767, both as int32 differences
    over time, one row per coordinate; a still thing is one frame."""
    from ..shapes import PART_KINDS, parts

    pos, rot, fps = prop.positions, prop.unit_rotations, float(prop.fps)
    if prop.is_static:
        pos, rot = pos[:1], rot[:1]
    elif fps > max_fps:
        pos = _resample_positions(pos[:, None], fps, max_fps)[:, 0]
        rot = _resample_positions(rot[:, None], fps, max_fps)[:, 0]
        rot = rot / np.linalg.norm(rot, axis=1, keepdims=True)
        fps = float(max_fps)
    mm = np.round(pos * 1000.0).astype(np.int64)
    if np.abs(mm).max(initial=0) > 2**30:
        raise ValueError(f"prop {prop.name!r} is more than 1000 km away")
    q = np.round(rot * 32767.0).astype(np.int64)
    return {
        "name": prop.name, "shape": prop.shape, "color": prop.color, "fps": fps, "frames": int(len(mm)),
        "size": [round(v, 4) for v in prop.size],
        "parts": [[PART_KINDS.index(p.kind), *(round(v, 4) for v in (*p.centre, *p.size)), p.axis]
                  for p in parts(prop.shape, prop.size)],
        "pos": _encode(np.ascontiguousarray(np.diff(mm, axis=0, prepend=0).astype("<i4").T), compress),
        "rot": _encode(np.ascontiguousarray(np.diff(q, axis=0, prepend=0).astype("<i4").T), compress),
    }


def viewer_data(tracks, spans=(), title: str = "", *, max_fps: float = 30.0, compress: bool = True,
                props=()) -> dict:
    """The JSON document the page reads (exposed for tests and other front ends); ``"props"`` only when there
    are ``props`` (:class:`Prop`)."""
    tracks = as_tracks(tracks)
    spans = as_spans(spans)
    props = as_props(props)
    if not max_fps > 0:
        raise ValueError(f"max_fps must be positive, got {max_fps}")
    actors = [_actor_data(t, PALETTE[i % len(PALETTE)], max_fps, compress) for i, t in enumerate(tracks)]
    things = [_prop_data(p, max_fps, compress) for p in props]
    duration = max((a["frames"] - 1) / a["fps"] for a in actors + things)
    duration = max(duration, max((s.end for s in spans), default=0.0))
    rows = [t.name for t in tracks] + sorted({s.actor for s in spans} - {t.name for t in tracks})
    return {
        "version": 1,
        "title": title,
        "encoding": "deflate" if compress else "raw",
        "duration": round(float(duration), 4),
        "actors": actors,
        "rows": rows,
        "spans": [{"actor": s.actor, "label": s.label, "start": round(s.start, 4), "end": round(s.end, 4),
                   "kind": s.kind, "part": s.part, "lane": s.lane} for s in spans],
        **({"props": things} if things else {}),
    }


def _asset(name: str) -> str:
    return resources.files(__package__).joinpath(name).read_text(encoding="utf-8")


def _script_json(obj) -> str:
    """JSON safe inside ``<script type="application/json">``: no ``</script>``, no ``<!--``."""
    text = json.dumps(obj, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


#: Where ``props.js`` goes into ``viewer.js`` when the page has props.
PROPS_SLOT = "/* props.js */"


def render_html(tracks, spans=(), title: str = "", path: str | os.PathLike | None = None, *,
                max_fps: float = 30.0, compress: bool = True, props=(), props_code: bool = False) -> str:
    """The viewer page for ``tracks`` (a list of :class:`Track`, a ``{name: Motion}`` dict or one Motion).

    ``spans`` (:class:`Span`) are drawn on the timeline under the 3D view:
    time-table elements as bars, blend intervals shaded (upper / lower body
    lanes); ``props`` (:class:`Prop`) in the 3D view with the actors. Returns the HTML text; when ``path`` is
    given it is also written there atomically (:class:`~core.atomic.OutputError` if it cannot be).
    ``props_code``: :func:`viewer_page`'s.
    """
    data = viewer_data(tracks, spans, title, max_fps=max_fps, compress=compress, props=props)
    page = viewer_page(data, props_code=props_code)
    if path is not None:
        atomic_write_text(path, page)
    return page


def viewer_page(data: dict, *, props_code: bool = False) -> str:
    """The page playing ``data`` (:func:`viewer_data`'s document). ``props_code`` inlines ``props.js`` even when
    ``data`` has no things: a page whose animation is replaced in place (``window.__t2a.load(data)``, the
    studio) may be handed one that has."""
    script = _asset("viewer.js")
    if "props" in data or props_code:
        script = script.replace(PROPS_SLOT, _asset("props.js"), 1)
    if re.search(r"</script", script, re.I):  # pragma: no cover - guards edits of viewer.js
        raise RuntimeError("viewer.js must not contain '</script'")
    fields = {
        "TITLE": html.escape(data["title"] or "text2anim"),
        "DATA": _script_json(data),
        "SCRIPT": script,
        "FONT": "",
    }
    template = _asset("viewer.html")
    page = re.sub(r"\{\{(TITLE|DATA|SCRIPT|FONT)\}\}", lambda mt: fields[mt.group(1)], template)
    fields["FONT"] = embedded_font.font_face_css(page)  # the glyphs of what the page shows, names and verbs
    return re.sub(r"\{\{(TITLE|DATA|SCRIPT|FONT)\}\}", lambda mt: fields[mt.group(1)], template)
