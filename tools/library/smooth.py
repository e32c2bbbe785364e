"""A zero-phase low-pass for capture takes that carry marker-solve glitches.

Some CMU takes have a joint that jumps between two consecutive 120 fps frames
(a marker swap in the solve): 16_01 (jump) moves the left hand 11 cm in 1/120 s
at 1.69 s where it otherwise moves 0.4-0.7 cm a frame; 16_35 (run) kicks the
right clavicle for two frames at 0.36 s. At 30 fps one such frame puts a joint's
jerk above 6,000 m/s^3, far beyond the motion around it. The cut list names the
clips that need it (``lowpass = Hz``); :func:`lowpass` runs a 2nd-order
Butterworth filter forwards and backwards (``scipy.signal.filtfilt``: no
phase lag, so contacts keep their timing) over every joint's local rotation
(quaternion components, made sign-continuous first, renormalised after) and the
root position. A cut-off of 10 Hz keeps the motion of the limbs (gait and
jumps are below 6-8 Hz, Winter, *Biomechanics and Motor Control of Human
Movement*, ch. 2) and spreads a glitch over ~0.1 s.

Shapes: rotations ``(T, J, 4)`` ``(x, y, z, w)``, root ``(T, 3)`` metres.
"""
from __future__ import annotations

import numpy as np
from scipy.signal import butter, filtfilt

from text2anim.core.motion import Motion, unroll_quaternions

#: Order of the Butterworth filter (run twice by filtfilt: 4th order in effect).
ORDER = 2


def lowpass(motion: Motion, hz: float) -> Motion:
    """``motion`` low-passed at ``hz`` (see the module docstring); too short a motion is returned as it is."""
    nyquist = motion.fps / 2
    if not 0 < hz < nyquist:
        raise ValueError(f"a low-pass cut-off must be between 0 and {nyquist:g} Hz, not {hz:g}")
    b, a = butter(ORDER, hz / nyquist)
    if motion.n_frames <= 3 * max(len(a), len(b)):  # filtfilt's padding needs this many frames
        return motion
    q = filtfilt(b, a, unroll_quaternions(np.asarray(motion.rotations, dtype=np.float64)), axis=0)
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    root = filtfilt(b, a, motion.root_positions, axis=0)
    return motion.replace(root_positions=root, rotations=q)
