# The Blender add-on, headless (issue 36; tests/blender/CMakeLists.txt runs it):
#
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/addon_test.py -- \
#       ADDON.zip EXTENSION.zip MODULE_DIR GLINT_COMMAND OUT_DIR DOCS_MD
#
# Installs the add-on as the Blender at hand takes it (an extension in 4.2+, from its legacy zip before), makes a low/high pair in Blender, bakes it with the
# add-on (through the module, then through the command), and checks: the images (size,
# pixels), the material's wiring (Normal Map node in tangent space on the low poly's UV
# map, AO multiplied into the base colour), the normal map against Blender's own Cycles bake
# of the same pair (mean angle ≤ 0.25°, the bound of tests/bake/bake_blender_test.cpp), the
# command's maps against the module's, saved files, UDIM tiles, and that errors come as
# Blender reports. Then runs the Python examples of docs/blender.md. Any failure raises:
# Blender exits 1 (--python-exit-code).
import math
import os
import re
import subprocess
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from support import install_addon, make_pair, pixels, select  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
ADDON_ZIP, EXTENSION_ZIP, MODULE_DIR, GLINT, OUT, DOCS = argv[:6]
SIZE = 128
DISTANCE = 0.06


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print("ok:", message)


def angles(a, b):
    na, nb = a[..., :3] * 2 - 1, b[..., :3] * 2 - 1
    na /= np.linalg.norm(na, axis=-1, keepdims=True)
    nb /= np.linalg.norm(nb, axis=-1, keepdims=True)
    return np.degrees(np.arccos(np.clip((na * nb).sum(-1), -1, 1)))


def cycles_normal(low, high):
    """Blender's own tangent-space normal bake of the pair (Cycles, selected to active)."""
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 1
    scene.cycles.use_denoising = False
    image = bpy.data.images.new("cycles-normal", SIZE, SIZE, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set(np.zeros(SIZE * SIZE * 4, np.float32))
    tree = low.active_material.node_tree
    node = tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    tree.nodes.active = node
    select(low, [high])
    bpy.ops.object.bake(type="NORMAL", normal_space="TANGENT", use_selected_to_active=True, cage_extrusion=DISTANCE,
                        max_ray_distance=2 * DISTANCE, margin=0, use_clear=False)
    tree.nodes.remove(node)
    return pixels(image)


# ------------------------------------------------------------------ install
ADDON = install_addon(ADDON_ZIP, EXTENSION_ZIP)  # an extension in Blender 4.2+, a legacy add-on before
preferences = bpy.context.preferences.addons[ADDON].preferences
preferences.module_path = MODULE_DIR
preferences.command = GLINT
check(hasattr(bpy.types.Scene, "glint_bake") and hasattr(bpy.ops.object, "glint_bake"), "the add-on installs from its zip")

# ------------------------------------------------------------------ the module's bake
low, high = make_pair()
settings = bpy.context.scene.glint_bake
settings.size = SIZE
settings.bake_normal = True
settings.bake_ao = True
settings.ao_samples = 8
settings.float_maps = True
settings.max_front = settings.max_rear = str(DISTANCE)
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "Bake with glint finishes")
report = __import__("json").loads(bpy.context.scene["glint_last_bake"])
check(report["backend"] == "module", "it baked through the module")
normal = bpy.data.images["Ball_low_normal"]
ao = bpy.data.images["Ball_low_ao"]
check(tuple(normal.size) == (SIZE, SIZE) and normal.is_float, "the normal map is a float image of the size asked")
check(normal.colorspace_settings.name == "Non-Color", "the normal map is non-colour data")
glint_normal = pixels(normal)
check(glint_normal[..., 2].mean() > 0.7, "the normal map points out (blue)")
ao_pixels = pixels(ao)[..., 0]
check(0.3 < ao_pixels.mean() <= 1.0 and ao_pixels.min() < ao_pixels.max(), "the AO map has shading")

# The wiring.
tree = low.active_material.node_tree
shader = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
normal_link = shader.inputs["Normal"].links[0]
normal_map = normal_link.from_node
check(normal_map.type == "NORMAL_MAP" and normal_map.space == "TANGENT", "a tangent-space Normal Map node feeds the shader")
check(normal_map.uv_map == low.data.uv_layers.active.name, "on the low poly's UV map")
check(normal_map.inputs["Color"].links[0].from_node.image == normal, "fed by the baked normal map")
mix = shader.inputs["Base Color"].links[0].from_node
check(mix.type == "MIX_RGB" and mix.blend_type == "MULTIPLY", "AO multiplies the base colour")
check(mix.inputs["Color2"].links[0].from_node.image == ao, "with the baked AO map")

# Against Blender's own bake of the same pair: the texels Blender baked whose neighbours it
# baked too (the two rasterizers' coverage rules differ at island edges).
blender = cycles_normal(low, high)
covered = blender[..., 3] > 0.5
inner = covered.copy()
inner[1:-1, 1:-1] &= covered[:-2, 1:-1] & covered[2:, 1:-1] & covered[1:-1, :-2] & covered[1:-1, 2:]
inner[[0, -1], :] = False
inner[:, [0, -1]] = False
difference = angles(glint_normal, blender)[inner]
print(f"add-on vs Cycles: {inner.sum()} texels, mean {difference.mean():.4f}°, 99th percentile "
      f"{np.percentile(difference, 99):.4f}°, max {difference.max():.4f}°")
check(inner.sum() > SIZE * SIZE // 2, "Blender's bake covers the UV layout")
check(difference.mean() <= 0.25, f"the normal map agrees with Cycles' (mean {difference.mean():.4f}° ≤ 0.25°)")

# ------------------------------------------------------------------ the command's bake
preferences.use_command = True
settings.bake_ao = False
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "the command's bake finishes")
report = __import__("json").loads(bpy.context.scene["glint_last_bake"])
check(report["backend"] == "command", "it baked through the command")
command_normal = pixels(bpy.data.images["Ball_low_normal"])
command_difference = angles(command_normal, glint_normal)
print(f"command vs module: max {command_difference.max():.6f}°, {int((command_difference > 0).sum())} texels differ; "
      f"max channel difference {np.abs(command_normal[..., :3] - glint_normal[..., :3]).max():.3g}")
# Not bit for bit: the command reads the pair from the GLB files Blender's exporter writes,
# the module gets Blender's arrays. Where the exporter writes Blender's normals as they are
# (3.4), MikkTSpace's sums round differently, by a float ulp (1.2e-7 at 1): two ulps allowed.
# Blender 4.x's exporter rounds every normal to 4 decimals (so equal corners merge), up to
# 6.5e-5 here: the command bakes from those normals, and its map may differ by twice that.
import glint as glint_module  # noqa: E402  (MODULE_DIR is on the path: the add-on put it there)

core = sys.modules[ADDON + ".core"]
exported = os.path.join(OUT, "exported")
os.makedirs(exported, exist_ok=True)
rounding = 0.0
graph = bpy.context.evaluated_depsgraph_get()
for obj, with_uvs in ((low, True), (high, False)):
    positions, triangles, normals, _, _ = core.mesh_arrays(obj, graph, with_uvs)
    read = glint_module.load_mesh(core.export_gltf(bpy.context, [obj], os.path.join(exported, obj.name + ".glb")))
    check(np.array_equal(positions[triangles.ravel()], read.positions[read.indices.ravel()]),
          f"{obj.name}: Blender's exporter writes the positions glint bakes")
    rounding = max(rounding, float(np.abs(normals[triangles.ravel()] - read.normals[read.indices.ravel()]).max()))
# 3.4's exporter only renormalizes (1.8e-7: float ulps); 4.x's rounds to 4 decimals.
rounds = rounding > 1e-6
print(f"Blender {bpy.app.version_string}'s glTF exporter moves normals by up to {rounding:.3g}"
      f"{': it rounds them' if rounds else ' (float ulps)'}")
tolerance = 2.4e-7 + (2 * rounding if rounds else 0.0)
check(np.abs(command_normal[..., :3] - glint_normal[..., :3]).max() <= tolerance,
      f"the command's map equals the module's to two float ulps and twice the exporter's rounding ({tolerance:.3g})")
preferences.use_command = False

# ------------------------------------------------------------------ every map, both ways
# The panel offers the maps glint's own table lists (glint.bake_options()); each is baked
# through the module and through the command (on the glTF files Blender's exporter writes),
# which must agree: within 1e-4 (a 40th of an 8-bit step: the two readings' positions differ
# in the last float bit, which curvature's many short rays sum up) on all but 1 % of the
# texels (where a ray's hit moves across an edge of the two readings' triangles). Where the
# exporter rounds normals (Blender 4.x, above), curvature, which differentiates the high
# poly's normals over a texel, moves by up to 1e-3: there, within a quarter of an 8-bit step.
agree = 1 / 1020 if rounds else 1e-4

offered = [m["name"] for m in glint_module.bake_options()["maps"] if not m["parts"] and m["name"] != "miss_mask"]
check({"normal", "ao", "bent_normal", "thickness", "curvature", "height", "position", "opacity"} <= set(offered),
      f"the panel offers glint's maps: {offered}")
for name in offered:
    check(hasattr(settings, "bake_" + name), f"a checkbox for {name}")
    setattr(settings, "bake_" + name, True)
check(settings.bl_rna.properties["samples"].enum_items.get("49") is not None, "49 samples, as glint takes them")
by_backend = {}
for use_command in (False, True):
    preferences.use_command = use_command
    check(bpy.ops.object.glint_bake() == {"FINISHED"}, f"every map through the {'command' if use_command else 'module'}")
    by_backend[use_command] = {name: pixels(bpy.data.images[f"Ball_low_{name}"]) for name in offered}
preferences.use_command = False
for name in offered:
    a, b = by_backend[False][name][..., :3], by_backend[True][name][..., :3]
    differ = (np.abs(a - b) > agree).any(axis=-1)
    print(f"{name}: command vs module: {int(differ.sum())} of {differ.size} texels differ, max {np.abs(a - b).max():.3g}")
    check(differ.mean() < 0.01, f"{name}: the command's map is the module's")

# ------------------------------------------------------------------ every map on the GPU
# The Device control (glint's --device) on "gpu" (llvmpipe here; the GPU on a GPU machine):
# the same pair, every map, through the module and the command, equal to the same backend's
# CPU bake above: within 1/255 on all but 0.1 % of the texels, AO's mean within 1/255.
check(hasattr(settings, "device") and settings.device == "auto", "a Device control, on auto")
settings.device = "gpu"
for use_command in (False, True):
    preferences.use_command = use_command
    way = "command" if use_command else "module"
    check(bpy.ops.object.glint_bake() == {"FINISHED"}, f"every map on the GPU through the {way}")
    last = __import__("json").loads(bpy.context.scene["glint_last_bake"])
    check(all(p["device"] == "gpu" for p in last["pairs"]), f"the {way}'s report says the GPU traced")
    for name in offered:
        gpu = pixels(bpy.data.images[f"Ball_low_{name}"])[..., :3]
        cpu = by_backend[use_command][name][..., :3]
        differ = (np.abs(gpu - cpu) > 1 / 255).any(axis=-1)
        print(f"{name}: GPU vs CPU through the {way}: {int(differ.sum())} of {differ.size} texels beyond 1/255, "
              f"max {np.abs(gpu - cpu).max():.3g}")
        check(differ.mean() <= 0.001, f"{name}: the GPU's map is the CPU's ({way})")
        if name == "ao":
            check(abs(float(gpu.mean()) - float(cpu.mean())) <= 1 / 255, f"AO's mean is the CPU's ({way})")
settings.device = "auto"
preferences.use_command = False
for name in offered:
    setattr(settings, "bake_" + name, name in ("normal", "ao"))

# ------------------------------------------------------------------ kept in the .blend
# The default: no folder, so the maps are packed into the .blend. Saved, closed and opened
# in a new Blender process, the images hold the same pixels (an unpacked map made from an
# array would come back black and GENERATED).
settings.save_folder = ""
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a bake into the .blend finishes")
kept = {name: pixels(bpy.data.images[f"Ball_low_{name}"]) for name in ("normal", "ao")}
np.savez(os.path.join(OUT, "kept.npz"), **kept)
blend = os.path.join(OUT, "kept.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
for name in kept:
    image = bpy.data.images[f"Ball_low_{name}"]
    check(image.packed_file is not None and image.use_fake_user, f"{name}: packed into the .blend as it was saved, kept by a fake user")
    check(np.array_equal(pixels(image), kept[name]), f"{name}: the same pixels once packed")
reopen = subprocess.run(
    [bpy.app.binary_path, "-b", "--factory-startup", blend, "--python-exit-code", "1", "--python-expr",
     "import bpy, numpy as np\n"
     f"kept = np.load({os.path.join(OUT, 'kept.npz')!r})\n"
     "for name in ('normal', 'ao'):\n"
     "    image = bpy.data.images['Ball_low_' + name]\n"
     "    w, h = image.size\n"
     "    px = np.empty(w * h * 4, np.float32)\n"
     "    image.pixels.foreach_get(px)\n"
     "    assert image.source == 'FILE' and image.packed_file is not None, (name, image.source)\n"
     "    assert np.array_equal(px.reshape(h, w, 4), kept[name]), name + ': other pixels after reopening'\n"
     "print('reopened: the same maps')\n"],
    capture_output=True, text=True)
check(reopen.returncode == 0 and "reopened: the same maps" in reopen.stdout,
      f"saved, closed and reopened in a new Blender: the same maps ({reopen.stderr.strip()[-300:]})")

# ------------------------------------------------------------------ saved files, 8-bit
settings.float_maps = False
settings.save_folder = os.path.join(OUT, "maps")
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a bake saved as files finishes")
saved = os.path.join(OUT, "maps", "Ball_low_normal.png")
check(os.path.exists(saved) and bpy.path.abspath(bpy.data.images["Ball_low_normal"].filepath_raw) == saved,
      "the map is saved as PNG")
# With the .blend saved, the map's path is relative to it (the folder and the .blend move together).
bpy.ops.wm.save_as_mainfile(filepath=os.path.join(OUT, "beside.blend"))
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a bake beside a saved .blend finishes")
check(bpy.data.images["Ball_low_normal"].filepath.startswith("//"), "its path is relative to the .blend: "
      + bpy.data.images["Ball_low_normal"].filepath)
sys.path.insert(0, MODULE_DIR)
import glint  # noqa: E402

check(glint.read_image(saved).shape == (SIZE, SIZE, 3), "a 128×128 RGB PNG")
# An object's name with a slash, quotes, $(...) and a line break: the image keeps it, the
# file gets a clean name inside the folder, nothing runs.
low.name = 'Ball/"$(touch PWNED)"\nlow'
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a low poly with an odd name bakes")
odd = bpy.data.images[low.name + "_normal"]
check(os.path.dirname(bpy.path.abspath(odd.filepath_raw)) == os.path.join(OUT, "maps") and "\n" not in odd.filepath_raw,
      f"its file is in the folder with a clean name: {os.path.basename(odd.filepath_raw)}")
check(not os.path.exists(os.path.join(OUT, "PWNED")) and not os.path.exists("PWNED"), "no command ran")
low.name = "Ball_low"
settings.save_folder = "/proc/no-such-folder"
try:
    bpy.ops.object.glint_bake()
    raise AssertionError("a bake into an unwritable folder finished")
except RuntimeError as error:
    check("Traceback" not in str(error), f"an unwritable folder is a report: {str(error).strip()}")
settings.save_folder = ""

# ------------------------------------------------------------------ UDIM
uvs = low.data.uv_layers.active.data
uv = np.empty(len(uvs) * 2, np.float32)
uvs.foreach_get("uv", uv)
uv = uv.reshape(-1, 2)
for polygon in low.data.polygons:  # the right half's faces one tile over
    if polygon.center.x > 0:
        for i in polygon.loop_indices:
            uv[i, 0] += 1.0
uvs.foreach_set("uv", uv.ravel())
low.data.update()
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a UDIM bake finishes")
tiled = bpy.data.images["Ball_low_normal"]
print("UDIM image:", tiled.source, [t.number for t in tiled.tiles], tiled.filepath)
check(tiled.source == "TILED" and sorted(t.number for t in tiled.tiles) == [1001, 1002], "one tiled image, tiles 1001 and 1002")
check(tiled.packed_file is not None or len(tiled.packed_files) > 0, "its tiles packed into the .blend")
module_tiles = pixels(tiled)
preferences.use_command = True  # UDIM through the command: the tiles its --json report lists
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a UDIM bake through the command finishes")
tiled = bpy.data.images["Ball_low_normal"]
check(tiled.source == "TILED" and sorted(t.number for t in tiled.tiles) == [1001, 1002], "the command's: tiles 1001 and 1002")
check(np.abs(pixels(tiled) - module_tiles).max() <= 2.4e-7 or (np.abs(pixels(tiled) - module_tiles) > 1e-3).mean() < 0.01,
      "the command's first tile is the module's")
preferences.use_command = False

# ------------------------------------------------------------------ errors as reports
bpy.ops.mesh.primitive_cube_add()
cube = bpy.context.active_object
cube.name = "NoUvs"
while cube.data.uv_layers:
    cube.data.uv_layers.remove(cube.data.uv_layers[0])
cube.data.update()  # Blender 4.3's evaluated mesh keeps a removed UV map until the mesh is updated
select(cube, [high])
try:
    bpy.ops.object.glint_bake()
    raise AssertionError("a low poly without UVs baked")
except RuntimeError as error:
    text = str(error)
    check("no UV map" in text and "Traceback" not in text and text.count("\n") <= 1, f"an error is a report: {text.strip()}")
select(low, [])
try:
    bpy.ops.object.glint_bake()
    raise AssertionError("a bake without a high poly ran")
except RuntimeError as error:
    check("select one or more high polys" in str(error), "no high poly selected: said")

# ------------------------------------------------------------------ without the module
# The module cannot load (not on the path, not imported): the add-on bakes with the command.
for name in [m for m in sys.modules if m == "glint" or m.startswith("glint.")]:
    del sys.modules[name]
sys.path[:] = [p for p in sys.path if os.path.abspath(p) != os.path.abspath(MODULE_DIR)]
preferences.module_path = ""
preferences.use_command = False
select(low, [high])
check(bpy.ops.object.glint_bake() == {"FINISHED"}, "a bake without the module finishes")
report = __import__("json").loads(bpy.context.scene["glint_last_bake"])
check(report["backend"] == "command", "the module could not load: the command baked")
preferences.module_path = MODULE_DIR

# ------------------------------------------------------------------ docs/blender.md
text = open(DOCS).read()
blocks = re.findall(r"```python\n(.*?)```", text, re.S)
check(len(blocks) >= 2, "docs/blender.md has Python examples")
os.chdir(OUT)
for i, block in enumerate(blocks):
    print(f"docs/blender.md example {i + 1}")
    exec(compile(block, f"docs/blender.md example {i + 1}", "exec"), {"__name__": "__docs__", "GLINT": GLINT,
                                                                     "MODULE_DIR": MODULE_DIR})
print("addon_test: all checks passed")
