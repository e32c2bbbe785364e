"""What a motion becomes for a user: files and pictures, made from :mod:`text2anim.core` motions.

Modules: ``bvh_write`` (BVH text), ``gltf`` (a GLB of stick figures), ``vrma`` (a VRM animation),
``viewer`` (the self-contained HTML player), ``plots`` (curves and timelines), ``sheet`` (contact
sheets of a clip), ``fonts`` (a font that draws Japanese). This package imports :mod:`text2anim.core`
only; the API and the command line use it. The readers (BVH, a user's glTF rig) are in the core.
"""
