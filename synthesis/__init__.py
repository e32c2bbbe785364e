"""Synthesis stage: clips of the time table joined into one motion per actor.

The joining methods (``registry.METHODS``, registered in ``registry.REGISTRY``): optimal blending
(paper 000, the default, :mod:`.optimal`), the constraint-based joins of paper 003
(:mod:`.constraint`), and the pose and crossfade baselines (:mod:`.baselines`), all on one shared join
layer (:mod:`.join`). The stage's input is :mod:`.tracks`, its output :mod:`.result`. They work on
:mod:`text2anim.core` motions and know nothing of Japanese.
"""
