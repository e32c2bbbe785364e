"""Weight over the feet: a join's hips moved so the body's centre of mass stays over the feet that carry it.

A blend starts a walk from standing by mixing two poses: the swing foot lifts while the centre of mass is
still between the feet, moving slowly — a body that would fall (core.balance reads 6-9 cm outside its
support). A person shifts the weight onto the stance foot first. Over a join's region, on the frames the
balance figure judges (:func:`core.balance.balance_gaps`: a foot down, slow, not seated), the hips are moved
on the ground plane by the gap, made :data:`MARGIN` larger and smoothed over :data:`SHIFT_S` (a weight shift
begins before the foot lifts), fading to 0 at the region's ends; both legs are solved back onto their feet
(position and world rotation, :func:`synthesis.join.legsolve.feet_kept`), so no foot moves. Vectorised over
frames; deterministic.
"""
from __future__ import annotations

import numpy as np
from scipy.ndimage import gaussian_filter1d

from text2anim.core.balance import balance_gaps
from text2anim.core.easing import smootherstep
from text2anim.core.metrics import peak_hips_acceleration
from text2anim.core.motion import Motion

from .legsolve import feet_kept

#: s: the Gaussian's sigma over which the weight shift is spread
SHIFT_S = 0.12
#: the shift goes this much beyond the support area's edge (the smoothing takes some of it back)
MARGIN = 1.5
#: m: shifts smaller than this are left out
MIN_SHIFT = 0.002
#: the shares of the shift tried in turn, the first that keeps the hips' acceleration within the limit taken
SCALES = (1.0, 0.5, 0.25)


def over_feet(motion: Motion, lo: int, hi: int, pop_limit: float = float("inf")) -> tuple[Motion, float]:
    """``motion`` with its hips over ``[lo, hi)`` moved over the feet (module docstring), and the largest
    shift (m). The motion as it is where the body stands balanced. The shift is halved (down to a quarter,
    else left out) until the hips' acceleration around the region (:func:`core.metrics.peak_hips_acceleration`)
    stays within ``pop_limit`` m/s², or within what it was."""
    n = hi - lo
    if n < 4:
        return motion, 0.0
    region = motion[lo:hi]
    gaps = np.nan_to_num(balance_gaps(region), nan=0.0)  # (n, 2), body's own size
    if not np.abs(gaps).max() > 0.0:
        return motion, 0.0
    sigma = max(1.0, SHIFT_S * motion.fps)
    shift = gaussian_filter1d(MARGIN * gaps, sigma, axis=0, mode="constant")
    edge = min(n // 2, int(np.ceil(2.5 * sigma)))
    fade = np.ones(n)
    if edge > 0:
        ramp = smootherstep(np.arange(1, edge + 1) / (edge + 1))
        fade[:edge], fade[n - edge:] = ramp, ramp[::-1]
    shift *= fade[:, None]
    moved = np.linalg.norm(shift, axis=-1) > MIN_SHIFT
    if not moved.any():
        return motion, 0.0
    a0, b0 = max(0, lo - 3), min(motion.n_frames, hi + 3)
    limit = max(pop_limit, peak_hips_acceleration(motion.root_positions[a0:b0], motion.fps))
    for scale in SCALES:
        root = motion.root_positions.copy()
        root[lo:hi, 0] += scale * shift[:, 0]
        root[lo:hi, 2] += scale * shift[:, 1]
        if peak_hips_acceleration(root[a0:b0], motion.fps) <= limit:
            break
    else:
        return motion, 0.0
    shift = scale * shift
    frames = np.flatnonzero(moved)
    a, b = lo + int(frames[0]), lo + int(frames[-1]) + 1
    return feet_kept(motion, motion.replace(root_positions=root), a, b), float(np.linalg.norm(shift, axis=-1).max())
