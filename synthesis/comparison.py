"""The figures of ``docs/timetable.md`` §3 of one joining method's result, to set methods side by side.

``text2anim compare`` synthesises the same tracks once per method (the pipeline's stages after the
tracks, :mod:`text2anim.pipeline`); :func:`figures` reduces a :class:`~synthesis.result.Result` to one row:

- ``foot_skate_cm_s``: mean horizontal speed of the feet while in contact,
  over every actor's whole motion (weighted by contact frames), cm/s;
- ``slide_cm``: the distance the feet slide while in contact, summed, cm;
- ``skating_ratio``: the GMD foot-skating ratio of the whole motion (worst actor);
- ``join_skating_ratio``: the largest skating ratio of a join's blend;
- ``jerk_max`` / ``jerk_rms``: the largest jerk in any blend, and the RMS over
  the blends (each join's RMS, pooled), m/s³; ``source_jerk_max`` the largest
  jerk of the clips joined, for scale;
- ``core_fidelity_cm``: the largest joint error inside an element's core against
  its clip (whole-body elements), cm;
- ``duration_s``: the longest actor's animation;
- ``joins`` and ``not_executed``: how many joins, how many dropped a motion.
"""
from __future__ import annotations

import numpy as np

from text2anim.core.metrics import foot_skate, skating_ratio


FIELDS = ("foot_skate_cm_s", "slide_cm", "skating_ratio", "join_skating_ratio", "jerk_max", "jerk_rms",
          "source_jerk_max", "core_fidelity_cm", "duration_s")


def figures(result) -> dict:
    """One row of figures for a :class:`~synthesis.result.Result` (see the module docstring)."""
    speed_sum = frames = slide = 0.0
    ratio = 0.0
    for m in result.motions.values():
        for f in foot_skate(m).values():
            speed_sum += f.mean_speed_cm_s * f.contact_frames
            frames += f.contact_frames
            slide += f.slide_cm
        ratio = max(ratio, skating_ratio(m))
    joins = [j for j in result.joins if j.metrics and "jerk_max" in j.metrics]
    fid = [v.core_fidelity_cm for v in result.elements.values() if v.core_fidelity_cm is not None]
    return {
        "foot_skate_cm_s": speed_sum / frames if frames else 0.0,
        "slide_cm": slide,
        "skating_ratio": ratio,
        "join_skating_ratio": max([j.metrics["skating_ratio"] for j in joins] or [0.0]),
        "jerk_max": max([j.metrics["jerk_max"] for j in joins] or [0.0]),
        "jerk_rms": float(np.sqrt(np.mean([j.metrics["jerk_rms"] ** 2 for j in joins]))) if joins else 0.0,
        "source_jerk_max": max([j.metrics.get("source_jerk_max", 0.0) for j in joins] or [0.0]),
        "core_fidelity_cm": max(fid or [0.0]),
        "duration_s": max([m.duration for m in result.motions.values()] or [0.0]),
        "joins": len(result.joins),
        "not_executed": sum(1 for j in result.joins if j.blend == "not_executed"),
    }
