"""The BVH readers compared by ``bench_speed.py`` and ``bench_bvh.py``, each given the same work.

Two outputs are timed, from the file's path (reading the file is part of every contender's time):

- ``rotations``: joint rotations as quaternions and the root's positions, per frame, what
  :func:`text2anim.core.read_bvh` returns (a ``Motion``: ``(T, J, 4)`` quaternions, ``(T, 3)`` root
  positions in metres, the skeleton). ``bvhio.readAsBvh`` builds the same per joint: a list of
  ``Pose(position, glm quaternion)`` per frame (Python objects, not arrays; no conversion to numpy is
  added to its time). The ``bvh`` package only splits the text into string tokens, so its entry adds
  the float conversion and our own vectorised Euler-to-quaternion kernel (one call per rotation order,
  the fastest way we know), so that it ends with the same arrays.
- ``raw``: the channel values ``(T, C)`` as float64 and the hierarchy, no rotations:
  :func:`text2anim.core.bvh.parse_channels` (every check of the reader included) against
  ``Bvh(text)`` + ``np.array(frames, float)``. bvhio has no raw mode (its frames always become poses).

Peers missing from the environment are left out with a note (``pip install -e '.[bench]'``).
"""
from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np

REPO = Path(__file__).resolve().parents[1]
CMU = REPO.parent / "shared" / "mocap" / "cmu"
BVH_FILES = ["02_01_walk", "16_35_run", "10_01_kick", "02_05_punch", "14_06_squat"]


def cmu_paths() -> list[Path]:
    return [CMU / f"{f}.bvh" for f in BVH_FILES if (CMU / f"{f}.bvh").exists()]


def _bvh_package_rotations(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """``bvh.Bvh`` + float array + one vectorised Euler conversion per order: ``(T, J, 4)``, ``(T, 3)``."""
    from bvh import Bvh

    from text2anim.core import quat

    mocap = Bvh(path.read_text())
    data = np.array(mocap.frames, dtype=float)
    names = mocap.get_joints_names()
    groups: dict[str, tuple[list[int], list[int]]] = {}
    root: np.ndarray = np.zeros((len(data), 3))
    col = 0
    for j, name in enumerate(names):
        chans = mocap.joint_channels(name)
        rot = [k for k, c in enumerate(chans) if c.endswith("rotation")]
        joints, cols = groups.setdefault("".join(chans[k][0] for k in rot), ([], []))
        joints.append(j)
        cols.extend(col + k for k in rot)
        if j == 0:
            root = data[:, [col + k for k, c in enumerate(chans) if c.endswith("position")]]
        col += len(chans)
    rotations = np.empty((len(data), len(names), 4))
    for order, (joints, cols) in groups.items():
        angles = data[:, cols].reshape(len(data), len(joints), len(order))
        rotations[:, joints] = quat.from_euler(order, angles)
    return rotations, root


def _bvh_package_raw(path: Path) -> np.ndarray:
    from bvh import Bvh

    return np.array(Bvh(path.read_text()).frames, dtype=float)


def contenders(paths: list[Path], output: str) -> tuple[dict[str, Callable[[], object]], list[str]]:
    """``name -> one call reading every path`` for ``output`` (``"rotations"`` or ``"raw"``), ours first;
    and notes for the peers that are not installed."""
    from text2anim.core import read_bvh
    from text2anim.core.bvh import parse_channels

    notes: list[str] = []
    if output == "rotations":
        out: dict[str, Callable[[], object]] = {"text2anim": lambda: [read_bvh(p) for p in paths]}
        try:
            import bvhio

            out["bvhio"] = lambda: [bvhio.readAsBvh(str(p)) for p in paths]
        except ImportError:
            notes.append("bvhio not installed (pip install -e '.[bench]')")
        try:
            import bvh  # noqa: F401

            out["bvh + from_euler"] = lambda: [_bvh_package_rotations(p) for p in paths]
        except ImportError:
            notes.append("bvh not installed (pip install -e '.[bench]')")
        return out, notes
    out = {"text2anim": lambda: [parse_channels(p.read_text(), str(p)) for p in paths]}
    try:
        import bvh  # noqa: F401

        out["bvh"] = lambda: [_bvh_package_raw(p) for p in paths]
    except ImportError:
        notes.append("bvh not installed (pip install -e '.[bench]')")
    return out, notes


def same_output(paths: list[Path]) -> str:
    """A check that the contenders really compute the same thing: the largest quaternion difference
    (up to sign) between ours and each peer on the first file, in the file's units for positions."""
    from text2anim.core.bvh import parse_bvh

    p = paths[0]
    ours = parse_bvh(p.read_text(), scale=1)
    notes = []
    try:
        rot, root = _bvh_package_rotations(p)
        dq = np.abs(np.abs(np.sum(rot * ours.rotations, axis=-1)) - 1).max()
        notes.append(f"bvh: |1-|q.q'|| max {dq:.1e}, root max diff "
                     f"{np.abs(root + ours.skeleton.offsets[0] - ours.root_positions).max():.1e}")
    except ImportError:
        pass
    try:
        import bvhio

        c = bvhio.readAsBvh(str(p))
        q = np.array([[k.Rotation.x, k.Rotation.y, k.Rotation.z, k.Rotation.w] for k in c.Root.Keyframes])
        dq = np.abs(np.abs(np.sum(q * ours.rotations[:, 0], axis=-1)) - 1).max()
        notes.append(f"bvhio: root joint |1-|q.q'|| max {dq:.1e}")
    except ImportError:
        pass
    return "; ".join(notes)
