"""The ``text2anim`` command line: a thin layer over the pipeline's stages."""
