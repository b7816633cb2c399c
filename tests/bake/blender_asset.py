# Blender's side of tests/bake/asset_blender_test.cpp (issue 35): a low/high pair made in
# Blender, and what Blender makes of the asset `glint bake --asset` writes.
#
#   blender -b --factory-startup --python-exit-code 1 --python blender_asset.py -- make DIR
#       DIR/low.obj: Suzanne, smart-UV-unwrapped, smooth; DIR/high.obj: the same head
#       subdivided three times and displaced by a procedural texture (the detail to bake).
#   blender -b --factory-startup --python-exit-code 1 --python blender_asset.py -- check ASSET.glb OUT.json
#       imports the asset with Blender's own glTF importer and writes what a test checks:
#       the material graph (the normal map node, its space, its UV map and image; what
#       feeds the occlusion) and, for every face corner, Blender's MikkTSpace tangent
#       (mesh.calc_tangents on the imported mesh) with the corner's position and UV.
import json
import sys

import bpy


def fail(message):
    print("blender_asset: " + message, file=sys.stderr)
    sys.exit(3)


def make(folder):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.mesh.primitive_monkey_add(size=2.0)
    low = bpy.context.active_object
    low.name = "suzanne"
    bpy.ops.object.shade_smooth()
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.uv.smart_project(island_margin=0.02)
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.ops.wm.obj_export(filepath=folder + "/low.obj", export_selected_objects=True, export_materials=False,
                          export_triangulated_mesh=True)
    high = low.copy()
    high.data = low.data.copy()
    bpy.context.collection.objects.link(high)
    subdivision = high.modifiers.new("subdivision", "SUBSURF")
    subdivision.levels = 3
    texture = bpy.data.textures.new("bumps", "CLOUDS")
    texture.noise_scale = 0.08
    displace = high.modifiers.new("displace", "DISPLACE")
    displace.texture = texture
    displace.strength = 0.06
    displace.mid_level = 0.5
    bpy.ops.object.select_all(action="DESELECT")
    high.select_set(True)
    bpy.context.view_layer.objects.active = high
    bpy.ops.wm.obj_export(filepath=folder + "/high.obj", export_selected_objects=True, export_materials=False,
                          export_triangulated_mesh=True, export_uv=False)


def linked_from(socket):
    return socket.links[0].from_node if socket.is_linked else None


def describe_material(material, uv_name):
    nodes = material.node_tree.nodes
    bsdf = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    info = {"name": material.name, "principled": bsdf is not None}
    if bsdf is None:
        return info
    normal_map = linked_from(bsdf.inputs["Normal"])
    if normal_map is not None and normal_map.type == "NORMAL_MAP":
        image = linked_from(normal_map.inputs["Color"])
        info["normal_map"] = {
            "space": normal_map.space,
            "uv_map": normal_map.uv_map,
            "uv_map_is_the_mesh_s": normal_map.uv_map in ("", uv_name),
            "image": image.image.name if image is not None and image.type == "TEX_IMAGE" else None,
            "colorspace": image.image.colorspace_settings.name if image is not None and image.type == "TEX_IMAGE" else None,
        }
    # The importer keeps glTF's occlusion in a "glTF Material Output" (or "glTF Settings")
    # group's Occlusion input, fed by the AO image's red channel.
    for node in nodes:
        if node.type == "GROUP" and "Occlusion" in node.inputs:
            source = linked_from(node.inputs["Occlusion"])
            while source is not None and source.type != "TEX_IMAGE":
                source = linked_from(source.inputs[0]) if source.inputs else None
            info["occlusion_image"] = source.image.name if source is not None else None
    return info


def check(asset, out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # Debian 12's Blender 3.4.1 glTF importer calls numpy.bool, an alias that Debian's numpy
    # 1.24 no longer has (set_poly_smoothing: "module 'numpy' has no attribute 'bool'"):
    # the alias put back, as the importer's later versions spell it themselves.
    import numpy
    if not hasattr(numpy, "bool"):
        numpy.bool = bool
    bpy.ops.import_scene.gltf(filepath=asset)
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if not meshes:
        fail("the importer made no mesh")
    result = {"objects": [], "materials": [], "corners": []}
    for obj in meshes:
        mesh = obj.data
        uv = mesh.uv_layers.active
        if uv is None:
            fail("the imported mesh has no UV map")
        if hasattr(mesh, "calc_normals_split"):  # Blender < 4.1; later ones keep the corners' normals up to date
            mesh.calc_normals_split()  # the corners' normals (the file's, kept as custom normals)
        uv_name = uv.name
        mesh.calc_tangents(uvmap=uv_name)
        # Asked again: computing tangents can move the mesh's corner data (Blender 4.3 did),
        # which leaves a UV layer fetched before pointing at freed memory.
        uv = mesh.uv_layers[uv_name]
        world = obj.matrix_world
        result["objects"].append({"name": obj.name, "uv_map": uv.name, "corners": len(mesh.loops),
                                  "custom_normals": mesh.has_custom_normals,
                                  # Blender 4.1 dropped auto smooth: corners are split where their normals differ
                                  "auto_smooth": getattr(mesh, "use_auto_smooth", True)})
        for slot in obj.material_slots:
            if slot.material is not None:
                result["materials"].append(describe_material(slot.material, uv.name))
        for loop in mesh.loops:
            p = world @ mesh.vertices[loop.vertex_index].co
            t = (world.to_3x3() @ loop.tangent).normalized()
            n = (world.to_3x3() @ loop.normal).normalized()
            u = uv.data[loop.index].uv
            result["corners"].append([p.x, p.y, p.z, u.x, u.y, t.x, t.y, t.z, loop.bitangent_sign, n.x, n.y, n.z])
    with open(out, "w") as f:
        json.dump(result, f)


args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(args) == 2 and args[0] == "make":
    make(args[1])
elif len(args) == 3 and args[0] == "check":
    check(args[1], args[2])
else:
    fail("usage: blender -b --python blender_asset.py -- make DIR | check ASSET.glb OUT.json")
