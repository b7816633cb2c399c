# Blender peer for `glint bench bake` (issue 6, item 10a): Cycles' "selected to active"
# tangent-space normal bake of the same OBJ files glint bakes, headless.
#
#   blender -b --factory-startup --python-exit-code 1 --python bench/peers/blender_bake.py -- \
#       LOW.obj HIGH.obj OUT.png SIZE SAMPLES MAX_DISTANCE [PASSES AO_SAMPLES AO_DISTANCE]
#
# SAMPLES is Cycles' sample count (1 = one ray per texel, like `glint bake --samples 1`);
# MAX_DISTANCE is both the cage extrusion and the maximum ray distance (scene units),
# matching glint's --max-front/--max-rear. Margin 16 px, as glint's default padding.
# PASSES (default "normal") is a comma-separated list of the maps Blender bakes that glint
# bakes too: normal (tangent space), ao, position; they are baked one after another, as an
# artist does in Blender, each into OUT with ".PASS" before its extension. AO uses
# AO_SAMPLES Cycles samples per texel (one AO ray each, as glint's --ao-samples rays) and the
# world's AO distance AO_DISTANCE (glint's --ao-distance).
# Written for Blender 3.4 (Debian 12); uses the OBJ importer that version has.
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_common import bake_target, use_cycles  # noqa: E402


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    low_path, high_path, out_path = argv[0], argv[1], argv[2]
    size, samples, distance = int(argv[3]), int(argv[4]), float(argv[5])
    passes = argv[6].split(",") if len(argv) > 6 else ["normal"]
    ao_samples = int(argv[7]) if len(argv) > 7 else 16
    ao_distance = float(argv[8]) if len(argv) > 8 else 0.1

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
    use_cycles(scene, samples)  # (denoiser off: blender_common.py)
    bake = scene.render.bake
    bake.use_selected_to_active = True
    bake.cage_extrusion = distance
    if hasattr(bake, "max_ray_distance"):
        bake.max_ray_distance = 2.0 * distance
    bake.margin = 16
    bake.normal_space = "TANGENT"

    if "ao" in passes:
        world = bpy.data.worlds.new("bake-world")
        scene.world = world
        world.light_settings.distance = ao_distance

    node = bake_target(low, high)
    for name in passes:
        image = bpy.data.images.new(f"baked-{name}", size, size, float_buffer=(name == "position"))
        node.image = image
        scene.cycles.samples = ao_samples if name == "ao" else samples
        kind = {"normal": "NORMAL", "ao": "AO", "position": "POSITION"}[name]
        bpy.ops.object.bake(type=kind, normal_space="TANGENT", use_selected_to_active=True,
                            cage_extrusion=distance, margin=16)
        if len(passes) == 1:
            image.filepath_raw = out_path
        else:
            stem, dot, ext = out_path.rpartition(".")
            image.filepath_raw = f"{stem}.{name}.{ext}"
        image.file_format = "OPEN_EXR" if name == "position" and out_path.endswith(".exr") else "PNG"
        image.save()
    print(f"blender_bake: {time.time() - start:.2f} s in Blender (after startup)")


main()
