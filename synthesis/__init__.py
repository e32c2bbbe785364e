"""Synthesis stage: clips of the time table joined into one motion per actor.

The engines (``engines.METHODS``): optimal blending (paper 000, the default), the
constraint-based joins of paper 003, and the pose and crossfade baselines. They work on
:mod:`text2anim.core` motions and know nothing of Japanese.
"""
