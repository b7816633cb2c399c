# The add-on's work, apart from its user interface (__init__.py): Blender meshes to arrays,
# the bake through glint (the module, or the command where the module cannot load), the maps
# into Blender images, and the wiring of the low poly's material.
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import bpy
import numpy as np

# (name, label, description) of the maps the panel offers: glint bake's names.
MAPS = [
    ("normal", "Normal", "Tangent-space normal map (OpenGL convention, as Blender's Normal Map node reads it)"),
    ("ao", "AO", "Ambient occlusion of the high poly"),
    ("curvature", "Curvature", "Mean curvature of the high poly: 0.5 flat, brighter convex"),
    ("thickness", "Thickness", "How thin the high poly is behind each texel"),
    ("height", "Height", "Distance from the low poly to the high poly: 0.5 on the low poly"),
    ("position", "Position", "Object-space position, scaled into the object's bounds"),
]
# Maps that hold data rather than colour: Blender must not decode them as sRGB.
DATA_MAPS = {"normal", "ao", "curvature", "thickness", "height", "position"}


class BakeError(Exception):
    """A failure to show the artist as a one-line report."""


def json_text(value):
    return json.dumps(value)


# ------------------------------------------------------------------ where glint is
def load_module(preferences):
    """The glint module, or None where it cannot load (or the command is asked for)."""
    if preferences.use_command:
        return None
    folder = bpy.path.abspath(preferences.module_path) if preferences.module_path else ""
    if folder and folder not in sys.path:
        sys.path.insert(0, folder)
    try:
        import glint
        return glint
    except ImportError:
        return None


def command_path(preferences):
    command = bpy.path.abspath(preferences.command) if os.sep in preferences.command else preferences.command
    found = shutil.which(command)
    if not found:
        raise BakeError(f"glint: neither the Python module nor the command '{preferences.command}' was found "
                        "(set them in the add-on's preferences)")
    return found


def backend_description(preferences):
    module = load_module(preferences)
    if module is not None:
        return f"Bakes through the glint module {module.__version__} ({os.path.dirname(module.__file__)})"
    found = shutil.which(preferences.command)
    return f"Bakes through the glint command ({found})" if found else "glint not found: set the module or the command"


# ------------------------------------------------------------------ meshes
def mesh_arrays(obj, depsgraph, with_uvs):
    """The object as glint wants it, in world space (as Blender's selected-to-active bake
    works), triangulated as Blender triangulates it, with Blender's own normals (smooth or
    flat as the artist shaded it). A high poly shaded smooth throughout keeps its shared
    vertices and their normals; otherwise, and for the low poly (whose UVs are per face
    corner), one vertex per face corner with that corner's normal and UV (the UV map the
    render uses). Returns (positions, triangles, normals, uvs or None, the UV map's name)."""
    evaluated = obj.evaluated_get(depsgraph)
    # A smooth high poly is read from the evaluated mesh itself (no copy: 8 ms saved on a
    # 262k-triangle mesh); a mesh whose split normals must be computed, from a copy.
    mesh = evaluated.data
    smooth = np.empty(len(mesh.polygons), bool)
    mesh.polygons.foreach_get("use_smooth", smooth)
    shared = not with_uvs and smooth.all() and not getattr(mesh, "has_custom_normals", False)
    if not shared:
        mesh = evaluated.to_mesh()
    try:
        mesh.calc_loop_triangles()
        loops, vertices, triangles = len(mesh.loops), len(mesh.vertices), len(mesh.loop_triangles)
        if triangles == 0:
            raise BakeError(f"glint: '{obj.name}' has no faces to bake")
        points = np.empty(vertices * 3, np.float32)
        mesh.vertices.foreach_get("co", points)
        points = points.reshape(-1, 3)
        uvs, uv_name = None, ""
        if shared:
            # Shared vertices: Blender's vertex normals are the corners' normals.
            # uint32, Blender's own type: foreach_get then copies the arrays whole (a
            # 262k-triangle mesh in 5 ms); any other dtype goes item by item (35 ms).
            corners = np.empty(triangles * 3, np.uint32)
            mesh.loop_triangles.foreach_get("loops", corners)
            vertex_of = np.empty(loops, np.uint32)
            mesh.loops.foreach_get("vertex_index", vertex_of)
            corners = vertex_of[corners]
            normals = np.empty(vertices * 3, np.float32)
            source = mesh.vertex_normals if hasattr(mesh, "vertex_normals") else mesh.vertices
            source.foreach_get("vector" if hasattr(mesh, "vertex_normals") else "normal", normals)
            positions, normals = points, normals.reshape(-1, 3)
        else:
            if hasattr(mesh, "calc_normals_split"):
                mesh.calc_normals_split()
            corners = np.empty(triangles * 3, np.uint32)
            mesh.loop_triangles.foreach_get("loops", corners)
            vertex_of = np.empty(loops, np.uint32)
            mesh.loops.foreach_get("vertex_index", vertex_of)
            normals = np.empty(loops * 3, np.float32)
            mesh.loops.foreach_get("normal", normals)
            positions, normals = points[vertex_of], normals.reshape(-1, 3)
            if with_uvs:
                layer = next((l for l in mesh.uv_layers if l.active_render), mesh.uv_layers.active)
                if layer is None:
                    raise BakeError(f"glint: the low poly '{obj.name}' has no UV map to bake into (UV > Unwrap)")
                uvs = np.empty(loops * 2, np.float32)
                layer.data.foreach_get("uv", uvs)
                uvs = uvs.reshape(-1, 2)
                uv_name = layer.name
    finally:
        if not shared:
            evaluated.to_mesh_clear()
    matrix = np.array(obj.matrix_world, dtype=np.float32)
    if not np.array_equal(matrix, np.identity(4, np.float32)):
        positions = positions @ matrix[:3, :3].T + matrix[:3, 3]
        normals = normals @ np.linalg.inv(matrix[:3, :3])  # by the inverse transpose
        normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-30)
    return positions, corners.reshape(-1, 3), normals, uvs, uv_name


def joined(parts):
    """Several (positions, triangles, normals) as one."""
    if len(parts) == 1:
        return parts[0][:3]
    positions, triangles, normals, base = [], [], [], 0
    for p, t, n, *_ in parts:
        positions.append(p)
        triangles.append(t.astype(np.int64) + base)
        normals.append(n)
        base += len(p)
    return np.concatenate(positions), np.concatenate(triangles), np.concatenate(normals)


def bake_pairs(context, settings):
    """[(low object, [high objects])]: the active object and the other selected meshes, or
    every OBJECT_low with the objects named OBJECT_high, OBJECT_high_*, OBJECT_high.001."""
    if settings.use_names:
        objects = [o for o in context.scene.objects if o.type == "MESH"]
        pairs = []
        for low in objects:
            if not low.name.endswith("_low"):
                continue
            stem = low.name[: -len("_low")]
            highs = [o for o in objects if o.name == stem + "_high" or o.name.startswith(stem + "_high_")
                     or o.name.startswith(stem + "_high.")]
            if not highs:
                raise BakeError(f"glint: '{low.name}' has no high poly named '{stem}_high'")
            pairs.append((low, highs))
        if not pairs:
            raise BakeError("glint: no object is named OBJECT_low (Match by names)")
        return pairs
    low = context.active_object
    if low is None or low.type != "MESH":
        raise BakeError("glint: make the low poly the active object (select the high polys, then the low poly last)")
    highs = [o for o in context.selected_objects if o is not low and o.type == "MESH"]
    if not highs:
        raise BakeError("glint: select one or more high polys besides the active low poly")
    return [(low, highs)]


def chosen_maps(settings):
    maps = [name for name, _, _ in MAPS if getattr(settings, "bake_" + name)]
    if not maps:
        raise BakeError("glint: choose at least one map to bake")
    return maps


# ------------------------------------------------------------------ the bake
def bake_scene(context, settings, preferences, progress):
    """Bakes every pair, makes the images and wires them. Returns a report: what was baked,
    and the seconds of each phase (export, bake, import, wire)."""
    glint = load_module(preferences)
    maps = chosen_maps(settings)
    depsgraph = context.evaluated_depsgraph_get()
    report = {"backend": "module" if glint is not None else "command", "pairs": [],
              "seconds": {"export": 0.0, "bake": 0.0, "import": 0.0, "wire": 0.0}}
    seconds = report["seconds"]
    for low, highs in bake_pairs(context, settings):
        start = time.perf_counter()
        low_arrays = mesh_arrays(low, depsgraph, True)
        high_arrays = joined([mesh_arrays(h, depsgraph, False) for h in highs])
        seconds["export"] += time.perf_counter() - start
        options = {"samples": int(settings.samples), "max_front": settings.max_front, "max_rear": settings.max_rear}
        extension = ".exr" if settings.float_maps else ".png"
        if "ao" in maps:
            options["ao_samples"] = settings.ao_samples
        start = time.perf_counter()
        if glint is not None:
            baked = bake_with_module(glint, low_arrays, high_arrays, settings.size, maps, options, progress,
                                     32 if settings.float_maps else 8)
        else:
            baked = bake_with_command(command_path(preferences), low_arrays, high_arrays, settings.size, maps, options,
                                      extension)
        bake_seconds = time.perf_counter() - start
        seconds["bake"] += bake_seconds
        start = time.perf_counter()
        try:
            images = {name: make_image(glint, f"{low.name}_{name}", value, name, settings.save_folder, extension)
                      for name, value in baked.items()}
        except (OSError, RuntimeError) as error:  # an unwritable folder (glint.OutputError is both)
            raise BakeError(f"glint: {error}") from None
        seconds["import"] += time.perf_counter() - start
        start = time.perf_counter()
        if settings.wire:
            wire_material(low, images, low_arrays[4])
        seconds["wire"] += time.perf_counter() - start
        report["pairs"].append({"low": low.name, "high": [h.name for h in highs], "maps": sorted(images),
                                "images": {k: v.name for k, v in images.items()}, "bake_seconds": bake_seconds})
    names = ", ".join(p["low"] for p in report["pairs"])
    report["summary"] = (f"glint baked {', '.join(maps)} at {settings.size}² for {names} in "
                         f"{sum(seconds.values()):.2f} s (bake {seconds['bake']:.2f} s)")
    return report


def bake_with_module(glint, low_arrays, high_arrays, size, maps, options, progress, bits):
    positions, triangles, normals, uvs, _ = low_arrays
    low = glint.Mesh(positions, triangles, normals, uvs)
    high = glint.Mesh(*high_arrays)
    try:
        result = glint.bake(low, high, size=size, maps=maps, progress=progress, bits=bits, **options)
    except glint.Error as error:
        raise BakeError(f"glint: {error}") from None
    return dict(result)


def write_obj(path, positions, triangles, normals, uvs=None):
    """An OBJ file of one vertex per corner (v, vn and vt alike, so every face is i/i/i)."""
    with open(path, "w") as out:
        np.savetxt(out, positions, fmt="v %.9g %.9g %.9g")
        np.savetxt(out, normals, fmt="vn %.9g %.9g %.9g")
        if uvs is not None:
            np.savetxt(out, uvs, fmt="vt %.9g %.9g")
        f = triangles.astype(np.int64) + 1
        if uvs is not None:
            np.savetxt(out, np.repeat(f, 3, axis=1), fmt="f %d/%d/%d %d/%d/%d %d/%d/%d")
        else:
            np.savetxt(out, np.repeat(f, 2, axis=1), fmt="f %d//%d %d//%d %d//%d")


def bake_with_command(command, low_arrays, high_arrays, size, maps, options, extension):
    """The same bake through `glint bake`: OBJ files in, PNG (or EXR) files out, read back by Blender."""
    folder = tempfile.mkdtemp(prefix="glint-bake-")
    positions, triangles, normals, uvs, _ = low_arrays
    write_obj(os.path.join(folder, "low.obj"), positions, triangles, normals, uvs)
    write_obj(os.path.join(folder, "high.obj"), *high_arrays)
    udim = bool(uvs.size) and (uvs.min() < 0.0 or uvs.max() > 1.0)
    name = (lambda m: os.path.join(folder, f"{m}.<UDIM>{extension}")) if udim else (lambda m: os.path.join(folder, f"{m}{extension}"))
    arguments = [command, "bake", os.path.join(folder, "low.obj"), os.path.join(folder, "high.obj"),
                 "-o", name("normal"), "--size", f"{size}x{size}", "-q"]
    for m in maps:
        if m != "normal":
            arguments += ["--" + m, name(m)]
    for key, value in options.items():
        arguments += ["--" + key.replace("_", "-"), str(value)]
    result = subprocess.run(arguments, capture_output=True, text=True)
    if result.returncode != 0:
        lines = [line for line in result.stderr.splitlines() if line.strip()]
        raise BakeError(f"glint: {lines[-1] if lines else f'glint bake failed (exit {result.returncode})'}")
    baked = {}
    for m in maps:
        if udim:
            tiles = {}
            for file in sorted(os.listdir(folder)):
                number = file[len(m) + 1:-len(extension)]
                if file.startswith(m + ".") and file.endswith(extension) and number.isdigit():
                    tiles[int(number)] = os.path.join(folder, file)
            baked[m] = tiles
        else:
            baked[m] = os.path.join(folder, f"{m}{extension}")
    return baked


# ------------------------------------------------------------------ images
def make_image(glint, name, value, map_name, save_folder, extension=".png"):
    """A Blender image of one map: from an array (the module), a file (the command), or for
    UDIM a dict of either by tile. Saved in save_folder when given; otherwise, as Blender's
    own bake leaves its images, an image made from an array is unsaved (File > Save asks,
    Image > Pack keeps it in the .blend), and one read from a temporary file is packed."""
    folder = bpy.path.abspath(save_folder) if save_folder else ""
    if folder:
        os.makedirs(folder, exist_ok=True)
    # The image keeps the object's name; a file gets it cleaned (no "/", no line break).
    file_stem = bpy.path.clean_name(name)
    if isinstance(value, dict):  # UDIM: tiles as NAME.<tile>.png, loaded as one tiled image
        tile_folder = folder or tempfile.mkdtemp(prefix="glint-udim-")
        for tile, tile_value in value.items():
            path = os.path.join(tile_folder, f"{file_stem}.{tile}{extension}")
            if isinstance(tile_value, str):
                shutil.copyfile(tile_value, path)
            else:
                glint.write_image(path, tile_value)
        first = os.path.join(tile_folder, f"{file_stem}.{min(value)}{extension}")
        old = bpy.data.images.get(name)
        if old is not None:
            bpy.data.images.remove(old)
        image = bpy.data.images.load(first)
        image.name = name
        image.source = "TILED"
        image.colorspace_settings.name = "Non-Color" if map_name in DATA_MAPS else "sRGB"
        if not folder:
            packed(image, tile_folder)
        return image
    if isinstance(value, str) or folder:  # a file: the command's, or the module's array saved
        path = value
        if folder:
            path = os.path.join(folder, f"{file_stem}{extension}")
            if isinstance(value, str):
                shutil.copyfile(value, path)
            else:
                glint.write_image(path, value)
        old = bpy.data.images.get(name)
        if old is not None:
            bpy.data.images.remove(old)
        image = bpy.data.images.load(path)
        image.name = name
        image.colorspace_settings.name = "Non-Color" if map_name in DATA_MAPS else "sRGB"
        if not folder:
            packed(image, os.path.dirname(path))
        return image
    array = value
    height, width = array.shape[:2]
    floats = array.dtype == np.float32
    old = bpy.data.images.get(name)
    if old is not None and (tuple(old.size) != (width, height) or old.is_float != floats or old.source != "GENERATED"):
        bpy.data.images.remove(old)
        old = None
    image = old or bpy.data.images.new(name, width, height, alpha=False, float_buffer=floats)
    image.colorspace_settings.name = "Non-Color" if map_name in DATA_MAPS else "sRGB"
    image.pixels.foreach_set(glint.rgba_rows_up(array) if glint is not None else rgba_rows_up(array))
    image.update()
    return image


def packed(image, temporary_folder):
    """Packs an image read from a temporary folder into the .blend, then removes the folder."""
    image.pack()
    if len(image.packed_files) > 0:
        shutil.rmtree(temporary_folder, ignore_errors=True)


def rgba_rows_up(array):
    """(numpy's version of glint.rgba_rows_up, for the command's arrays) glint's rows (top first, 1–4 channels, uint8/uint16/float32) as Blender's pixels:
    RGBA floats, bottom row first."""
    scale = {np.dtype(np.uint8): 1.0 / 255.0, np.dtype(np.uint16): 1.0 / 65535.0}.get(array.dtype, 1.0)
    height, width = array.shape[:2]
    channels = 1 if array.ndim == 2 else array.shape[2]
    out = np.ones((height, width, 4), np.float32)
    source = array[::-1].reshape(height, width, channels)
    if channels == 1:
        out[..., :3] = source * np.float32(scale)
    else:
        out[..., : min(channels, 4)] = source[..., :4] * np.float32(scale)
    return out.ravel()


# ------------------------------------------------------------------ the material
def wire_material(low, images, uv_name):
    """The low poly's material with the maps in it: normal → Normal Map (tangent space, the
    baked UV map) → the shader's Normal; AO multiplied into the base colour; the rest as
    image nodes beside it. Made when the low poly has none; nodes from an earlier glint bake
    are reused."""
    material = low.active_material
    if material is None:
        material = bpy.data.materials.new(f"{low.name}_glint")
        low.data.materials.append(material)
    material.use_nodes = True
    tree = material.node_tree
    nodes, links = tree.nodes, tree.links
    shader = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    if shader is None:
        shader = nodes.new("ShaderNodeBsdfPrincipled")
        output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None) or nodes.new("ShaderNodeOutputMaterial")
        links.new(shader.outputs["BSDF"], output.inputs["Surface"])

    def node(kind, name, x, y):
        existing = nodes.get(name)
        if existing is not None and existing.bl_idname == kind:
            return existing
        made = nodes.new(kind)
        made.name = made.label = name
        made.location = (shader.location.x + x, shader.location.y + y)
        return made

    row = 0
    for map_name, image in images.items():
        texture = node("ShaderNodeTexImage", f"glint {map_name}", -700, 300 - 300 * row)
        texture.image = image
        row += 1
        if map_name == "normal":
            normal_map = node("ShaderNodeNormalMap", "glint normal map", -300, -200)
            normal_map.space = "TANGENT"
            normal_map.uv_map = uv_name
            links.new(texture.outputs["Color"], normal_map.inputs["Color"])
            links.new(normal_map.outputs["Normal"], shader.inputs["Normal"])
        elif map_name == "ao":
            multiply = node("ShaderNodeMixRGB", "glint ao multiply", -300, 200)
            multiply.blend_type = "MULTIPLY"
            multiply.inputs["Fac"].default_value = 1.0
            base = shader.inputs["Base Color"]
            if base.is_linked and base.links[0].from_node is not multiply:
                links.new(base.links[0].from_socket, multiply.inputs["Color1"])
            elif not base.is_linked:
                multiply.inputs["Color1"].default_value = base.default_value
            links.new(texture.outputs["Color"], multiply.inputs["Color2"])
            links.new(multiply.outputs["Color"], base)
