# What the Blender peers (blender_bake.py for speed, blender_bake_check.py for the quality
# cross-check) share: Cycles on the CPU without its denoiser, and the "selected to active"
# set-up of a bake from `high` onto `low`. Imported by both (they put this folder on
# sys.path: Blender runs each as a standalone script).
import bpy


def use_cycles(scene, samples):
    """Cycles on the CPU, `samples` per texel. Denoising off: Debian's Blender has no
    OpenImageDenoise, and a bake that asks for it leaves the image untouched while
    reporting success."""
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False


def bake_target(low, high, image=None):
    """Gives `low` a material whose active node is an image texture (the bake's target, set
    to `image`), selects `high` and `low` with `low` active, and returns the node."""
    material = bpy.data.materials.new("bake-target")
    material.use_nodes = True
    node = material.node_tree.nodes.new("ShaderNodeTexImage")
    if image is not None:
        node.image = image
    material.node_tree.nodes.active = node
    low.data.materials.clear()
    low.data.materials.append(material)
    bpy.ops.object.select_all(action="DESELECT")
    high.select_set(True)
    low.select_set(True)
    bpy.context.view_layer.objects.active = low
    return node
