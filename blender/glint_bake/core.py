# The add-on's work, apart from its user interface (__init__.py): what glint offers (its
# options and maps, asked of glint itself), Blender meshes to arrays, the bake through glint
# (the module, or the command where the module cannot load) on a worker thread, the maps
# into Blender images, and the wiring of the low poly's material.
#
# Nothing here re-implements glint: the maps, their labels and help, the sample counts, the
# size limits and the defaults come from glint.bake_options() (or `glint bake --describe`);
# the command's fallback hands it meshes through Blender's own glTF exporter and reads its
# --json report for the UDIM tiles it wrote.
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

import bpy
import numpy as np


class BakeError(Exception):
    """A failure to show the artist as a one-line report."""


class Cancelled(Exception):
    """The artist stopped the bake (Esc, or the Cancel button)."""


def json_text(value):
    return json.dumps(value)


# ------------------------------------------------------------------ where glint is
def load_module(preferences):
    """The glint module, or None where it cannot load (or the command is asked for)."""
    if preferences is not None and preferences.use_command:
        return None
    folder = bpy.path.abspath(preferences.module_path) if preferences is not None and preferences.module_path else ""
    if folder and folder not in sys.path:
        sys.path.insert(0, folder)
    try:
        import glint
        return glint
    except ImportError:
        return None


def command_path(preferences):
    """The glint command's path, or None."""
    name = preferences.command if preferences is not None else "glint"
    command = bpy.path.abspath(name) if os.sep in name else name
    return shutil.which(command)


def backend_description(preferences):
    module = load_module(preferences)
    if module is not None:
        return f"Bakes through the glint module {module.__version__} ({os.path.dirname(module.__file__)})"
    found = command_path(preferences)
    return f"Bakes through the glint command ({found})" if found else "glint not found: set the module or the command"


_TABLE = {}


def bake_table(preferences):
    """glint's own description of its bake (glint.bake_options(), or `glint bake --describe`):
    the maps, each option's help and default, the sample counts, the size range. None when
    glint is not found. Asked once per backend."""
    module = load_module(preferences)
    key = ("module", module.__file__) if module is not None else ("command", command_path(preferences))
    if key in _TABLE:
        return _TABLE[key]
    table = None
    if module is not None:
        table = module.bake_options()
    elif key[1]:
        result = subprocess.run([key[1], "bake", "--describe"], capture_output=True, text=True)
        if result.returncode == 0:
            table = json.loads(result.stdout)
    _TABLE[key] = table
    return table


def offered_maps(table):
    """The maps the add-on offers: those a bake from Blender's meshes can make (not the ones
    read from a high poly's parts, which arrays do not carry)."""
    return [m for m in table["maps"] if not m["parts"] and m["name"] != "miss_mask"]


def default(table, option, fallback):
    entry = table["options"].get(option, {})
    return entry.get("default", fallback)


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
        # uint32, Blender's own type: foreach_get then copies the arrays whole (a 262k-triangle
        # mesh in 5 ms); any other dtype goes item by item (35 ms).
        corners = np.empty(triangles * 3, np.uint32)
        mesh.loop_triangles.foreach_get("loops", corners)
        vertex_of = np.empty(loops, np.uint32)
        mesh.loops.foreach_get("vertex_index", vertex_of)
        if shared:
            # Shared vertices: Blender's vertex normals are the corners' normals.
            corners = vertex_of[corners]
            normals = np.empty(vertices * 3, np.float32)
            source = mesh.vertex_normals if hasattr(mesh, "vertex_normals") else mesh.vertices
            source.foreach_get("vector" if hasattr(mesh, "vertex_normals") else "normal", normals)
            positions, normals = points, normals.reshape(-1, 3)
        else:
            if hasattr(mesh, "calc_normals_split"):  # Blender < 4.1; later ones keep them up to date
                mesh.calc_normals_split()
            normals = np.empty(loops * 3, np.float32)
            if hasattr(mesh, "corner_normals"):  # Blender 4.1+
                mesh.corner_normals.foreach_get("vector", normals)
            else:
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


def device_of(report):
    """Where glint traced a bake's rays ("cpu", "gpu"; "cpu" for a glint without --device),
    from its report: a UDIM bake's tiles each say (a tile's own bake)."""
    tiles = report.get("udim_tiles") or [report]
    devices = {tile.get("device", "cpu") for tile in tiles}
    return devices.pop() if len(devices) == 1 else "+".join(sorted(devices))


def chosen_maps(settings, table):
    maps = [m["name"] for m in offered_maps(table) if getattr(settings, "bake_" + m["name"], False)]
    if not maps:
        raise BakeError("glint: choose at least one map to bake")
    return maps


# ------------------------------------------------------------------ the bake, in two halves
class Bake:
    """One press of Bake with glint: prepare() on Blender's thread (the meshes as arrays, or
    as glTF files for the command), run() anywhere (glint's bake: no Blender data touched, so
    it may run on a worker thread while Blender stays responsive), apply() on Blender's
    thread once every pair has baked (images, packing, wiring). A cancel between or during
    pairs leaves the scene as it was: nothing is applied before every bake has finished."""

    def __init__(self, context, settings, preferences):
        self.glint = load_module(preferences)
        self.command = None if self.glint is not None else command_path(preferences)
        if self.glint is None and self.command is None:
            raise BakeError(f"glint: neither the Python module nor the command '{preferences.command}' was found "
                            "(set them in the add-on's preferences)")
        self.table = bake_table(preferences)
        if self.table is None:
            raise BakeError("glint: the glint found does not describe its bake (glint bake --describe): update it")
        self.maps = chosen_maps(settings, self.table)
        self.size = settings.size
        self.float_maps = settings.float_maps
        self.save_folder = settings.save_folder
        self.wire = settings.wire
        self.options = {"samples": int(settings.samples), "max_front": settings.max_front, "max_rear": settings.max_rear}
        if "ao" in self.maps or "bent_normal" in self.maps or "thickness" in self.maps:
            self.options["ao_samples"] = settings.ao_samples
        if hasattr(settings, "device"):
            self.options["device"] = settings.device
        self.pairs = bake_pairs(context, settings)
        self.backend = "module" if self.glint is not None else "command"
        self.seconds = {"export": 0.0, "bake": 0.0, "import": 0.0, "wire": 0.0}
        self.cancel = threading.Event()
        self.progress = {"label": "starting", "done": 0, "total": 1, "pair": 0}
        self.results = []
        self.devices = []  # where each pair's rays were traced ("cpu" or "gpu"), from glint's report
        self.folder = None  # the command's files
        self.threads = 0  # every core; the panel's bake leaves one to Blender (Bake.leave_a_core)

    def leave_a_core(self):
        """A bake from the panel runs beside Blender's window: one core is left to Blender
        (its drawing, its timers, the viewport) so the window stays responsive; on 16 cores
        the bake is 6 % slower, on 2 it takes twice as long."""
        self.threads = max(1, (os.cpu_count() or 2) - 1)

    # -------------------------------------------------------------- on Blender's thread
    def prepare(self, context):
        """The meshes of every pair, read from Blender now (the worker never touches bpy)."""
        start = time.perf_counter()
        depsgraph = context.evaluated_depsgraph_get()
        self.inputs = []
        if self.glint is not None:
            for low, highs in self.pairs:
                low_arrays = mesh_arrays(low, depsgraph, True)
                self.inputs.append((low_arrays, joined([mesh_arrays(h, depsgraph, False) for h in highs])))
        else:
            self.folder = tempfile.mkdtemp(prefix="glint-bake-")
            for index, (low, highs) in enumerate(self.pairs):
                uv_name = mesh_arrays(low, depsgraph, True)[4]  # checks the UV map, names it for the wiring
                low_file = export_gltf(context, [low], os.path.join(self.folder, f"low{index}.glb"))
                high_file = export_gltf(context, highs, os.path.join(self.folder, f"high{index}.glb"))
                self.inputs.append((low_file, high_file, uv_name))
        self.seconds["export"] += time.perf_counter() - start

    # -------------------------------------------------------------- anywhere
    def run(self):
        """Bakes every pair (glint's work; nothing of Blender's is read or written)."""
        for index, inputs in enumerate(self.inputs):
            if self.cancel.is_set():
                raise Cancelled()
            self.progress["pair"] = index
            start = time.perf_counter()
            if self.glint is not None:
                baked = self.bake_with_module(*inputs)
            else:
                baked = self.bake_with_command(index, *inputs)
            self.seconds["bake"] += time.perf_counter() - start
            self.results.append(baked)

    def on_progress(self, label, done, total):
        self.progress.update(label=label, done=done, total=max(total, 1))
        if self.cancel.is_set():
            raise Cancelled()  # glint stops its bake and raises it back

    def bake_with_module(self, low_arrays, high_arrays):
        glint = self.glint
        positions, triangles, normals, uvs, _ = low_arrays
        low = glint.Mesh(positions, triangles, normals, uvs)
        high = glint.Mesh(*high_arrays)
        try:
            result = glint.bake(low, high, size=self.size, maps=self.maps, progress=self.on_progress,
                                bits=32 if self.float_maps else 8, threads=self.threads, **self.options)
        except glint.Error as error:
            raise BakeError(f"glint: {error}") from None
        self.devices.append(device_of(result.report))
        return dict(result)

    def bake_with_command(self, index, low_file, high_file, uv_name):
        """`glint bake` on the glTF files Blender exported: a map file each (a file per UDIM
        tile, as its --json report lists them), read back by Blender."""
        extension = ".exr" if self.float_maps else ".png"
        by_option = {m["name"]: m["option"] for m in self.table["maps"]}
        # Every map named with <UDIM>: glint decides the tiles and its report lists them. Tile
        # 1001 alone is a bake inside the unit square, a plain image as the module gives it.
        name = lambda m: os.path.join(self.folder, f"{index}-{m}.<UDIM>{extension}")
        report_path = os.path.join(self.folder, f"{index}-report.json")
        arguments = [self.command, "bake", low_file, high_file, "-o", name("normal"), "--size", f"{self.size}x{self.size}",
                     "-q", "--json", report_path]
        for m in self.maps:
            if m != "normal":
                arguments += ["--" + by_option[m], name(m)]
        for key, value in self.options.items():
            arguments += ["--" + key.replace("_", "-"), str(value)]
        if self.threads:
            arguments += ["--threads", str(self.threads)]
        process = subprocess.Popen(arguments, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        self.progress.update(label="bake (command)", done=0, total=1)
        while process.poll() is None:
            if self.cancel.is_set():
                process.terminate()  # glint stops at once, leaving no partial file
                process.wait()
                raise Cancelled()
            time.sleep(0.05)
        errors = process.stderr.read()
        if process.returncode != 0:
            lines = [line for line in errors.splitlines() if line.strip()]
            raise BakeError(lines[-1] if lines else f"glint: glint bake failed (exit {process.returncode})")
        with open(report_path) as f:
            report = json.load(f)
        self.devices.append(device_of(report))
        tiles = [t["tile"] for t in report.get("udim_tiles", [])]
        baked = {}
        for m in self.maps:
            files = {t: name(m).replace("<UDIM>", str(t)) for t in tiles}
            baked[m] = files[1001] if tiles == [1001] else files
        return baked

    # -------------------------------------------------------------- on Blender's thread
    def apply(self):
        """The maps as Blender images (packed into the .blend, or saved in the folder), then the
        low polys' materials wired. Returns the report. Images first, for every pair: if one
        cannot be made (an unwritable folder), those made are removed and no material changes."""
        report = {"backend": self.backend, "pairs": [], "seconds": self.seconds}
        extension = ".exr" if self.float_maps else ".png"
        start = time.perf_counter()
        made, per_pair = [], []
        try:
            for (low, _), baked in zip(self.pairs, self.results):
                images = {}
                for m, value in baked.items():
                    images[m] = make_image(self.glint, f"{low.name}_{m}", value, self.colour(m), self.save_folder, extension)
                    made.append(images[m])
                per_pair.append(images)
        except (OSError, RuntimeError) as error:  # an unwritable folder (glint.OutputError is both)
            for image in made:
                bpy.data.images.remove(image)
            self.cleanup()
            raise BakeError(f"glint: {error}") from None
        self.seconds["import"] += time.perf_counter() - start
        start = time.perf_counter()
        for (low, highs), inputs, images in zip(self.pairs, self.inputs, per_pair):
            if self.wire:
                wire_material(low, images, inputs[0][4] if self.glint is not None else inputs[2])
            report["pairs"].append({"low": low.name, "high": [h.name for h in highs], "maps": sorted(images),
                                    "images": {k: v.name for k, v in images.items()},
                                    "device": self.devices[len(report["pairs"])]})
        self.seconds["wire"] += time.perf_counter() - start
        names = ", ".join(p["low"] for p in report["pairs"])
        report["summary"] = (f"glint baked {', '.join(self.maps)} at {self.size}² for {names} in "
                             f"{sum(self.seconds.values()):.2f} s (bake {self.seconds['bake']:.2f} s)")
        self.cleanup()
        return report

    def colour(self, map_name):
        return next((m["colour"] for m in self.table["maps"] if m["name"] == map_name), False)

    def cleanup(self):
        if self.folder:
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder = None


def export_gltf(context, objects, path):
    """The objects as Blender's own glTF exporter writes them (modifiers applied, Blender's
    triangulation and split normals, the UV maps; Z up kept: glint bakes in Blender's world
    space), for the command where the module cannot load. Blender writes the mesh format,
    glint reads it: the add-on writes none itself. The artist's selection is put back."""
    wanted = {"export_format": "GLB", "use_selection": True, "export_apply": True, "export_yup": False,
              "export_normals": True, "export_texcoords": True, "export_tangents": False, "export_materials": "NONE",
              "export_colors": False, "export_vertex_color": "NONE", "export_animations": False, "export_skins": False,
              "export_morph": False, "export_cameras": False, "export_lights": False, "export_extras": False}
    known = bpy.ops.export_scene.gltf.get_rna_type().properties.keys()  # the names differ between Blender versions
    options = {k: v for k, v in wanted.items() if k in known}
    layer = context.view_layer
    selected = [o for o in layer.objects if o.select_get()]
    active = layer.objects.active
    try:
        for o in layer.objects:
            o.select_set(o in objects)
        layer.objects.active = objects[0]
        bpy.ops.export_scene.gltf(filepath=path, **options)
    finally:
        for o in layer.objects:
            o.select_set(o in selected)
        layer.objects.active = active
    return path


# ------------------------------------------------------------------ images
def make_image(glint, name, value, colour, save_folder, extension=".png"):
    """A Blender image of one map: from an array (the module), a file (the command), or for
    UDIM a dict of either by tile. Saved in save_folder when given (its path relative to the
    .blend when the .blend is saved); otherwise packed into the .blend, so saving, closing
    and reopening the .blend shows the same map. Kept by a fake user either way: a map is
    not lost because no material uses it yet."""
    folder = bpy.path.abspath(save_folder) if save_folder else ""
    if folder:
        os.makedirs(folder, exist_ok=True)
    # The image keeps the object's name; a file gets it cleaned (no "/", no line break).
    file_stem = bpy.path.clean_name(name)
    old = bpy.data.images.get(name)
    if old is not None:
        bpy.data.images.remove(old)
    temporary = None  # a folder of files read only to be packed
    if isinstance(value, dict):  # UDIM: tiles as NAME.<tile>.ext, loaded as one tiled image
        tile_folder = folder or tempfile.mkdtemp(prefix="glint-udim-")
        temporary = None if folder else tile_folder
        for tile, tile_value in value.items():
            write_file(glint, os.path.join(tile_folder, f"{file_stem}.{tile}{extension}"), tile_value)
        image = bpy.data.images.load(os.path.join(tile_folder, f"{file_stem}.{min(value)}{extension}"))
        image.source = "TILED"
    elif folder:  # saved: the command's file copied, or the module's array written by glint
        path = os.path.join(folder, f"{file_stem}{extension}")
        write_file(glint, path, value)
        image = bpy.data.images.load(path)
    elif isinstance(value, str):  # the command's file, to be packed
        image = bpy.data.images.load(value)
    else:
        height, width = value.shape[:2]
        image = bpy.data.images.new(name, width, height, alpha=False, float_buffer=value.dtype == np.float32)
        # The colour space before the pixels: setting it on a generated image makes it again (black).
        image.colorspace_settings.name = "sRGB" if colour else "Non-Color"
        image.pixels.foreach_set(glint.rgba_rows_up(value))
        image.file_format = "OPEN_EXR" if value.dtype == np.float32 else "PNG"
        image.update()
    image.name = name
    if image.colorspace_settings.name != ("sRGB" if colour else "Non-Color"):
        image.colorspace_settings.name = "sRGB" if colour else "Non-Color"
    image.use_fake_user = True
    if folder:
        if bpy.data.filepath:  # beside the .blend: a path that moves with it
            image.filepath = bpy.path.relpath(image.filepath_raw)
    elif isinstance(value, np.ndarray):
        # Packed when the .blend is saved (pack_before_save): packing is compressing the map,
        # 0.1 s for a 2048² PNG, which a bake the artist looks at and bakes again need not wait for.
        image[PACK_ON_SAVE] = True
    else:
        image.pack()  # read from files about to go: inside the .blend now
        if temporary:
            shutil.rmtree(temporary, ignore_errors=True)
    return image


PACK_ON_SAVE = "glint_pack_on_save"


def pack_before_save(*_):
    """(bpy.app.handlers.save_pre) Packs the maps glint made from arrays into the .blend being
    saved, so saving, closing and reopening it shows the same maps."""
    for image in bpy.data.images:
        if image.get(PACK_ON_SAVE):
            if image.packed_file is None:
                image.pack()
            del image[PACK_ON_SAVE]


def write_file(glint, path, value):
    """A map into `path`: the command's file copied, or the module's array written by glint."""
    if isinstance(value, str):
        shutil.copyfile(value, path)
    else:
        glint.write_image(path, value)


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
