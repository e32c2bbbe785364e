"""Imports a .glb into Blender (the ``bpy`` module) and prints the armature's bone heads.

    PYTHON_WITH_BPY blender_check.py FILE.glb FPS '[frame, ...]'

Prints one line ``JSON{...}``: the import result, objects, actions, bone names and, per frame,
the world position of every pose bone's head (Blender coordinates, Z up).
"""
import sys, json
import bpy
glb, fps, frames = sys.argv[1], int(sys.argv[2]), json.loads(sys.argv[3])
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.context.scene.render.fps = fps
res = bpy.ops.import_scene.gltf(filepath=glb)
out = {"result": list(res), "objects": [(o.name, o.type) for o in bpy.data.objects], "actions": [a.name for a in bpy.data.actions], "frames": {}}
arm = [o for o in bpy.data.objects if o.type == "ARMATURE"][0]
out["bones"] = [b.name for b in arm.pose.bones]
out["frame_range"] = list(bpy.data.actions[0].frame_range) if bpy.data.actions else None
for f in frames:
    bpy.context.scene.frame_set(f)
    dg = bpy.context.evaluated_depsgraph_get()
    a = arm.evaluated_get(dg)
    out["frames"][str(f)] = [list(a.matrix_world @ pb.head) for pb in a.pose.bones]
print("JSON" + json.dumps(out))
