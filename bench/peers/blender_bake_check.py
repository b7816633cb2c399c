# Blender peer for the quality cross-check (issue 23, deliverable 5;
# tests/bake/bake_blender_test.cpp): Cycles' "selected to active" bake of one map that
# glint bakes too, from the same OBJ files, written so it can be compared texel by texel.
#
#   blender -b --factory-startup --python-exit-code 1 --python bench/peers/blender_bake_check.py -- \
#       LOW.obj HIGH.obj OUT MAP SIZE SAMPLES DISTANCE [AO_DISTANCE]
#
# MAP is one of
#   ao        Cycles' AO bake: SAMPLES Cycles samples of one AO ray each, the world's AO
#             distance AO_DISTANCE (glint's --ao-distance)
#   position  Cycles' POSITION bake (world space; the objects stay at the identity, so it
#             is object space, as glint's --position)
#   normal    Cycles' NORMAL bake in OBJECT space, swizzle +X +Y +Z: (n + 1) / 2
# OUT is an OpenEXR file (32-bit float RGBA), or, with <UDIM> in its name, one PNG
# (8-bit RGBA) per UDIM tile the low poly's UVs occupy, <UDIM> replaced by the number.
# Margin 0, and the image starts transparent and is not cleared: a texel Blender baked has
# alpha 1, every other alpha 0, so the comparison sees exactly the texels Blender covered
# (no padding).
# DISTANCE is both the cage extrusion and half the maximum ray distance, as
# bench/peers/blender_bake.py (glint's --max-front/--max-rear).
#
# What Blender does with the files (docs/bake.md, "Against Blender"): it casts the rays
# along the low poly's vertex normals computed from its topology (face normals weighted by
# corner angle), not along the file's vn; and it shades the OBJ's vn (imported as custom
# split normals) wrongly at vertices shared by several faces, so a high poly compared with
# glint is written unwelded. Its UV rasterizer moves texel centres by (0.001, 0.002) texels.
#
# Axes: Blender's OBJ importer turns OBJ's Y-up into Blender's Z-up by default
# (x, y, z) -> (x, -z, y). The meshes are imported with forward_axis="Y", up_axis="Z",
# which keeps every coordinate as the file has it, so positions and object-space normals
# are in the OBJ's own axes, the ones glint bakes in. Written for Blender 3.4 (Debian 12).
import math
import os
import sys
import time

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_common import bake_target, use_cycles  # noqa: E402


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    low_path, high_path, out_path, kind = argv[0], argv[1], argv[2], argv[3]
    size, samples, distance = int(argv[4]), int(argv[5]), float(argv[6])
    ao_distance = float(argv[7]) if len(argv) > 7 else 0.1
    if kind not in ("ao", "position", "normal"):
        raise SystemExit(f"blender_bake_check: unknown map {kind}")

    bpy.ops.wm.read_factory_settings(use_empty=True)

    def load(path):
        before = set(bpy.data.objects)
        bpy.ops.wm.obj_import(filepath=path, forward_axis="Y", up_axis="Z")
        objects = [o for o in bpy.data.objects if o not in before]
        if len(objects) != 1:
            raise SystemExit(f"blender_bake_check: {path} holds {len(objects)} objects, expected 1")
        return objects[0]

    start = time.time()
    low = load(low_path)
    high = load(high_path)
    for obj in (low, high):
        if obj.matrix_world != obj.matrix_world.Identity(4):
            raise SystemExit("blender_bake_check: the importer placed an object off the identity")
        for polygon in obj.data.polygons:
            polygon.use_smooth = True

    scene = bpy.context.scene
    use_cycles(scene, samples)
    world = bpy.data.worlds.new("bake-world")
    scene.world = world
    world.light_settings.distance = ao_distance
    bake = scene.render.bake
    bake.use_selected_to_active = True
    bake.cage_extrusion = distance
    bake.max_ray_distance = 2.0 * distance
    bake.margin = 0
    bake.use_clear = False

    udim = "<UDIM>" in out_path
    tiles = [1001]
    if udim:
        # A face belongs to the tile holding its UV centre (glint's rule; docs/bake.md).
        uvs = low.data.uv_layers.active.data
        found = set()
        for polygon in low.data.polygons:
            u = sum(uvs[i].uv[0] for i in polygon.loop_indices) / polygon.loop_total
            v = sum(uvs[i].uv[1] for i in polygon.loop_indices) / polygon.loop_total
            found.add(1001 + int(math.floor(u)) + 10 * int(math.floor(v)))
        tiles = sorted(found)
    image = bpy.data.images.new(f"baked-{kind}", size, size, alpha=True, float_buffer=not udim, tiled=udim)
    image.colorspace_settings.name = "Non-Color"
    if not udim:
        # Transparent where nothing is baked: the bake then runs without clearing (its
        # clear fills a float image with opaque black).
        image.pixels.foreach_set([0.0] * (4 * size * size))
    if udim:
        # Tiles made by tiles.new have no pixels ("Uninitialized image" when baking);
        # the image editor's Fill Tile operator gives each its buffer.
        image.tiles[0].number = tiles[0]
        for number in tiles[1:]:
            image.tiles.new(tile_number=number)
        for tile in image.tiles:
            image.tiles.active = tile
            with bpy.context.temp_override(edit_image=image):
                bpy.ops.image.tile_fill(color=(0.0, 0.0, 0.0, 0.0), width=size, height=size, float=False, alpha=True)

    bake_target(low, high, image)
    bpy.ops.object.bake(type={"ao": "AO", "position": "POSITION", "normal": "NORMAL"}[kind], normal_space="OBJECT",
                        normal_r="POS_X", normal_g="POS_Y", normal_b="POS_Z", use_selected_to_active=True,
                        cage_extrusion=distance, max_ray_distance=2.0 * distance, margin=0, use_clear=False)
    image.filepath_raw = out_path
    image.file_format = "PNG" if udim else "OPEN_EXR"
    image.save()
    print(f"blender_bake_check: {kind} {len(tiles)} tile(s) in {time.time() - start:.2f} s in Blender (after startup)")


main()
