# What the add-on's tests share (addon_test.py, gui_test.py): a low/high pair made in Blender,
# and installing the add-on the way the Blender at hand installs it (blender/install_addon.py).
import os
import sys
import bpy
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender"))
from install_addon import install_addon  # noqa: E402,F401  (re-exported)


def make_pair(segments=32, rings=16, subdivisions=6):
    """A smooth UV sphere (Blender's own UVs) and a bumpy, finer ice sphere, the low selected
    last (active). Any earlier objects, meshes, materials and images are removed first."""
    # (not read_factory_settings: it would reset the preferences, the add-on with them)
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.images):
        for item in list(collection):
            collection.remove(item)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=rings, radius=1.0)
    low = bpy.context.active_object
    low.name = "Ball_low"
    bpy.ops.object.shade_smooth()
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=subdivisions, radius=1.0)
    high = bpy.context.active_object
    high.name = "Ball_high"
    co = np.empty(len(high.data.vertices) * 3, np.float32)
    high.data.vertices.foreach_get("co", co)
    p = co.reshape(-1, 3)
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    theta, phi = np.arctan2(p[:, 1], p[:, 0]), np.arccos(np.clip(p[:, 2], -1, 1))
    p *= (1.0 + 0.03 * np.sin(8 * theta) * np.sin(6 * phi))[:, None]
    high.data.vertices.foreach_set("co", p.ravel())
    high.data.update()
    bpy.ops.object.shade_smooth()
    select(low, [high])
    return low, high


def select(low, highs):
    bpy.ops.object.select_all(action="DESELECT")
    for h in highs:
        h.select_set(True)
    low.select_set(True)
    bpy.context.view_layer.objects.active = low


def pixels(image):
    """RGBA floats, rows bottom first (Blender's order)."""
    w, h = image.size
    out = np.empty(w * h * 4, np.float32)
    image.pixels.foreach_get(out)
    return out.reshape(h, w, 4)
