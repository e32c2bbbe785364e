"""The join layer every engine shares (the constraint engine, optimal blending, the baselines).

- records of a track being laid: :mod:`.placed` (a clip placed on a track), :mod:`.laid` (a track laid),
  :mod:`.laying` (the loop over a track's elements), :mod:`.commit` (a decided join committed to the track);
- preparing a clip: :mod:`.timing` (speed, repeats, hold, trim), :mod:`.cycles` and :mod:`.loopfeet` (loops);
- placing and blending: :mod:`.align` (rigid ground-plane moves), :mod:`.blend` (slerp),
  :mod:`.apply` (a join's blend window written, feet locked), :mod:`.footlock` and :mod:`.legsolve`
  (foot locks by leg IK), :mod:`.gait` (foot-moving intervals);
- compositions: :mod:`.composition` (paper 003 §4.4, a body part switched, sway transferred);
- the join post-pass: :mod:`.joinpass`, :mod:`.smoothing`, :mod:`.pruning`, :mod:`.inertialize`;
- measuring: :mod:`.measure` (``docs/timetable.md`` §3).
"""
