"""The join post-pass finishes each join on its window of the track (:func:`synthesis.join.joinpass.finish_track`):
the track it returns, what it reports and its retimings are those of the pass run on the whole track, join after
join, bit for bit; and the foot contacts of a window, read with the whole track's floor levels, are the track's."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

import text2anim
from text2anim.core.contacts import contacts_within, detect_contacts, floor_levels, lowest_heights
from text2anim.synthesis.join import joinpass
from text2anim.synthesis.join.spliced import Spliced


def _whole_track_pass(motion, regions):
    """The post-pass as it ran before it had windows: each join finished on the whole track."""
    out, infos, warps, added = motion, [], [], 0
    for k, r in enumerate(regions):
        r = replace(r, w0=r.w0 + added, w1=r.w1 + added, r1=r.r1 + added, keep=(r.keep[0] + added, r.keep[1] + added),
                    brake_from=None if r.brake_from is None else r.brake_from + added,
                    seams=tuple(x + added for x in r.seams))
        out, info, warp = joinpass.finish_region(out, r, detect_contacts(out))
        infos.append(info)
        warps.append(warp)
        added += warp[2] - (warp[1] - warp[0])
        if r.into_core:
            end = regions[k + 1].w0 + added if k + 1 < len(regions) else out.n_frames
            out = joinpass.lift_off_floor(out, r.w0, min(end, out.n_frames))
    return out, infos, warps


def test_a_long_text_finished_join_by_join_on_windows_is_the_whole_track_pass(monkeypatch):
    calls = []
    real = joinpass.finish_track

    def recorded(motion, regions):
        out = real(motion, regions)
        calls.append((motion, regions, out))
        return out

    monkeypatch.setattr(joinpass, "finish_track", recorded)
    text2anim.animate("太郎は走る。" + "3秒後に歩く。" * 3)
    (motion, regions, (out, infos, warps)), = calls
    assert len(regions) >= 6 and motion.n_frames > 500  # joins late on a track, far from both its ends
    ref, ref_infos, ref_warps = _whole_track_pass(motion, regions)
    assert np.array_equal(out.rotations, ref.rotations) and np.array_equal(out.root_positions, ref.root_positions)
    assert infos == ref_infos
    for (lo, hi, n, src), (rlo, rhi, rn, rsrc) in zip(warps, ref_warps):
        assert (lo, hi, n) == (rlo, rhi, rn) and np.array_equal(src, rsrc)
    # contacts of windows inside the track, with its floor levels: the track's but near the windows' ends
    whole, floor = detect_contacts(motion), floor_levels(lowest_heights(motion))
    for r in regions:
        a, b = max(0, r.w0 - 60), min(motion.n_frames, r.r1 + 60)
        part = contacts_within(motion[a:b], floor)
        for side in ("left", "right"):
            assert np.array_equal(part.of(side)[10:-10], whole.of(side)[a + 10:b - 10])


def test_a_spliced_track_puts_each_edit_where_it_belongs():
    track = text2anim.animate("太郎は走る。3秒後に歩く。").motions["太郎"]
    m = track[:300]
    spliced = Spliced(m)
    spliced.put(100, 150, m[100:150])  # pieces [0, 100) [100, 150) [150, 300)
    spliced.put(150, 160, m[200:230])  # at a boundary, longer: [150, 160) becomes 30 frames
    spliced.put(0, 20, m[50:60])  # at the start, shorter
    want = [m[50:60], m[20:150], m[200:230], m[160:300]]
    got = spliced.motion()
    assert got.n_frames == sum(p.n_frames for p in want) == spliced.n_frames
    assert np.array_equal(got.rotations, np.concatenate([p.rotations for p in want]))
    assert np.array_equal(got.root_positions, np.concatenate([p.root_positions for p in want]))
    assert np.array_equal(spliced.window(5, 45).rotations, got.rotations[5:45])
    assert np.array_equal(spliced.floor(), floor_levels(lowest_heights(got)))
    heights = lowest_heights(got)
    assert spliced.lowest_outside(5, 45) == np.concatenate([heights[:5], heights[45:]]).min()
    assert spliced.lowest_outside(0, spliced.n_frames) == np.inf
