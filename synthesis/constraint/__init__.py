"""The constraint engine of paper 003 (Moriwaki, Kokubu, Oshita, §4.3): consecutive motions joined by
Connection and Transition through the support foot.

- :mod:`.switching`: switching frames from foot–ground contact (§4.3.1) and the key frames of a gait (§4.3.2);
- :mod:`.connection`: the Connection and Transition joins, each decided as a
  :class:`~synthesis.join.apply.Join`;
- :mod:`.engine`: a track laid by these joins, :func:`~.engine.synthesize` (``--blend constraint``).

Composition with sway transfer (§4.4) and foot locking (§4.3.2) are the join layer's
(:mod:`synthesis.join`): every engine lays partial clips and locks feet the same way.
"""
