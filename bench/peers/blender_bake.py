# Blender peer for `glint bench bake` (issue 6, item 10a): Cycles' "selected to active"
# tangent-space normal bake of the same OBJ files glint bakes, headless.
#
#   blender -b --factory-startup --python bench/peers/blender_bake.py -- \
#       LOW.obj HIGH.obj OUT.png SIZE SAMPLES MAX_DISTANCE
#
# SAMPLES is Cycles' sample count (1 = one ray per texel, like `glint bake --samples 1`);
# MAX_DISTANCE is both the cage extrusion and the maximum ray distance (scene units),
# matching glint's --max-front/--max-rear. Margin 16 px, as glint's default padding.
# Written for Blender 3.4 (Debian 12); uses the OBJ importer that version has.
import sys
import time

import bpy


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    low_path, high_path, out_path = argv[0], argv[1], argv[2]
    size, samples, distance = int(argv[3]), int(argv[4]), float(argv[5])

    bpy.ops.wm.read_factory_settings(use_empty=True)

    def load(path):
        before = set(bpy.data.objects)
        if hasattr(bpy.ops.wm, "obj_import"):
            bpy.ops.wm.obj_import(filepath=path)
        else:
            bpy.ops.import_scene.obj(filepath=path)
        return [o for o in bpy.data.objects if o not in before][0]

    start = time.time()
    low = load(low_path)
    high = load(high_path)
    for obj in (low, high):
        for polygon in obj.data.polygons:
            polygon.use_smooth = True

    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    bake = scene.render.bake
    bake.use_selected_to_active = True
    bake.cage_extrusion = distance
    if hasattr(bake, "max_ray_distance"):
        bake.max_ray_distance = 2.0 * distance
    bake.margin = 16
    bake.normal_space = "TANGENT"

    image = bpy.data.images.new("baked", size, size)
    material = bpy.data.materials.new("bake-target")
    material.use_nodes = True
    node = material.node_tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    material.node_tree.nodes.active = node
    low.data.materials.clear()
    low.data.materials.append(material)

    bpy.ops.object.select_all(action="DESELECT")
    high.select_set(True)
    low.select_set(True)
    bpy.context.view_layer.objects.active = low
    bpy.ops.object.bake(type="NORMAL", normal_space="TANGENT", use_selected_to_active=True,
                        cage_extrusion=distance, margin=16)
    image.filepath_raw = out_path
    image.file_format = "PNG"
    image.save()
    print(f"blender_bake: {time.time() - start:.2f} s in Blender (after startup)")


main()
