# `glint bench bake` (g): the glint Bake add-on's whole bake inside Blender against Blender's
# own Cycles bake of the same maps, in one Blender session, runs alternating (issue 36).
#
#   blender -b --factory-startup --python-exit-code 1 --python bench/peers/blender_addon_bench.py -- \
#       ADDON.zip EXTENSION.zip MODULE_DIR LOW.obj HIGH.obj SIZE REPEATS
#
# For each case (the normal map; the normal map and AO with 16 rays per texel) and each
# repeat: the add-on's operator, timed whole (meshes out of Blender, glint's bake, images
# in, wiring) with its own phases, then Cycles baking the same maps one after another
# (selected to active, 1 sample for the normal map, 16 one-ray samples for AO, the same
# ray distances, the same AO distance: 10 % of the low poly's diagonal, glint's default).
# Prints one line per run: RESULT {"case":..., "tool":..., "seconds":..., ...}.
# The caller sets BLENDER_USER_SCRIPTS and BLENDER_USER_EXTENSIONS to folders of its own (the
# add-on installs there).
import json
import math
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_common import bake_target, use_cycles  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
addon_zip, extension_zip, module_dir, low_path, high_path = argv[:5]
size, repeats = int(argv[5]), int(argv[6])
# The add-on's Device settings to time (glint bench bake asks for "cpu,gpu" on a hardware GPU):
# each is a tool of its own in the results, "addon-cpu", "addon-gpu"; the default one "addon".
devices = argv[7].split(",") if len(argv) > 7 else ["auto"]
DISTANCE = 0.06

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender"))
from install_addon import install_addon  # noqa: E402

addon = install_addon(addon_zip, extension_zip)
bpy.context.preferences.addons[addon].preferences.module_path = module_dir
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)


def load(path):
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")
    obj = [o for o in bpy.data.objects if o not in before][0]
    for polygon in obj.data.polygons:
        polygon.use_smooth = True
    # A mesh made in Blender has no custom split normals; the importer makes them from the
    # OBJ's vn (the same smooth normals): cleared, as an artist's sculpt would be.
    if hasattr(obj.data, "free_normals_split"):  # Blender < 4.1
        obj.data.free_normals_split()
    if obj.data.has_custom_normals:
        bpy.context.view_layer.objects.active = obj
        bpy.ops.mesh.customdata_custom_splitnormals_clear()
    return obj


low, high = load(low_path), load(high_path)
low.name, high.name = "Bench_low", "Bench_high"
diagonal = math.dist(low.bound_box[0], low.bound_box[6])
scene = bpy.context.scene
world = bpy.data.worlds.new("bench-world")
scene.world = world
world.light_settings.distance = 0.1 * diagonal

settings = scene.glint_bake
settings.size = size
settings.samples = "1"
settings.ao_samples = 16
settings.max_front = settings.max_rear = str(DISTANCE)
settings.save_folder = ""


def select():
    bpy.ops.object.select_all(action="DESELECT")
    high.select_set(True)
    low.select_set(True)
    bpy.context.view_layer.objects.active = low


def addon(maps, device):
    for name in ("normal", "ao"):
        setattr(settings, "bake_" + name, name in maps)
    if hasattr(settings, "device"):
        settings.device = device
    select()
    start = time.perf_counter()
    bpy.ops.object.glint_bake()
    seconds = time.perf_counter() - start
    return seconds, json.loads(scene["glint_last_bake"])["seconds"]


def cycles(maps):
    use_cycles(scene, 1)
    start = time.perf_counter()
    image = bpy.data.images.new("cycles-bake", size, size)
    node = bake_target(low, high, image)
    for name in maps:
        scene.cycles.samples = 16 if name == "ao" else 1
        bpy.ops.object.bake(type={"normal": "NORMAL", "ao": "AO"}[name], normal_space="TANGENT",
                            use_selected_to_active=True, cage_extrusion=DISTANCE, max_ray_distance=2 * DISTANCE,
                            margin=16)
    seconds = time.perf_counter() - start
    node.id_data.nodes.remove(node)
    bpy.data.images.remove(image)
    return seconds


for case, maps in (("normal", ("normal",)), ("normal+ao", ("normal", "ao"))):
    for i in range(repeats):
        for device in devices:
            seconds, phases = addon(maps, device)
            tool = "addon" if device == "auto" else "addon-" + device
            print("RESULT " + json.dumps({"case": case, "tool": tool, "seconds": seconds, "phases": phases}), flush=True)
        seconds = cycles(maps)
        print("RESULT " + json.dumps({"case": case, "tool": "cycles", "seconds": seconds}), flush=True)
