"""Synthesis stage: clips of the time table joined into one motion per actor.

The joining methods (``engines.METHODS``, registered in ``engines.REGISTRY``): optimal
blending (paper 000, the default), the constraint-based joins of paper 003, and the pose and
crossfade baselines. They work on
:mod:`text2anim.core` motions and know nothing of Japanese.
"""
