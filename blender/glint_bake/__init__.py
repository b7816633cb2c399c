# glint Bake: a Blender add-on that bakes with glint (docs/blender.md).
#
# The artist picks a low poly and one or more high polys (selected to active, or by their
# _low/_high names), the maps, size and samples, and presses Bake: glint bakes them through
# its Python module (`import glint`) or, where the module cannot load, through the `glint`
# command; the maps become Blender images, and the low poly's material gets them wired (the
# normal map through a Normal Map node in tangent space on the low poly's UV map, AO
# multiplied into the base colour, the other maps as image nodes), optionally saved as files
# (UDIM tiles as <UDIM> files). Errors are Blender reports, not tracebacks.
bl_info = {
    "name": "glint Bake",
    "author": "glint",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > Sidebar > glint",
    "description": "Bake normal, AO and other maps from high polys onto a low poly with glint",
    "category": "Object",
}

import bpy

from . import core


def _map_items():
    return [(name, label, description) for name, label, description in core.MAPS]


class GlintBakeSettings(bpy.types.PropertyGroup):
    use_names: bpy.props.BoolProperty(
        name="Match by names", default=False,
        description="Bake every OBJECT_low from the objects named OBJECT_high (or OBJECT_high_*); "
                    "otherwise the active object is the low poly and the other selected meshes the high polys")
    size: bpy.props.IntProperty(name="Size", default=2048, min=8, max=16384,
                                description="Width and height of the maps in texels")
    samples: bpy.props.EnumProperty(
        name="Samples", default="1",
        items=[(str(n * n), f"{n * n}", f"{n}×{n} rays per texel") for n in (1, 2, 3, 4, 5, 6, 8)],
        description="Rays per texel for the normal map, a square grid (--samples)")
    ao_samples: bpy.props.IntProperty(name="AO rays", default=16, min=1, max=1024,
                                      description="Ambient-occlusion rays per texel (--ao-samples)")
    max_front: bpy.props.StringProperty(name="Max front", default="5%",
                                        description="How far in front of the low poly rays look: a distance, or a "
                                                    "share of the low poly's size (--max-front)")
    max_rear: bpy.props.StringProperty(name="Max rear", default="5%",
                                       description="How far behind the low poly rays look (--max-rear)")
    bake_normal: bpy.props.BoolProperty(name="Normal", default=True)
    bake_ao: bpy.props.BoolProperty(name="AO", default=False)
    bake_curvature: bpy.props.BoolProperty(name="Curvature", default=False)
    bake_thickness: bpy.props.BoolProperty(name="Thickness", default=False)
    bake_height: bpy.props.BoolProperty(name="Height", default=False)
    bake_position: bpy.props.BoolProperty(name="Position", default=False)
    float_maps: bpy.props.BoolProperty(
        name="32-bit float", default=False,
        description="Float maps (OpenEXR when saved) instead of 8-bit PNG: no banding in the normal map")
    save_folder: bpy.props.StringProperty(
        name="Save to", subtype="DIR_PATH", default="",
        description="A folder to save the maps in as PNG files (UDIM tiles as NAME.<UDIM>.png); empty: kept in the .blend")
    wire: bpy.props.BoolProperty(name="Wire into the material", default=True,
                                 description="Connect the maps to the low poly's material")


class GlintBakePreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    module_path: bpy.props.StringProperty(
        name="glint Python module", subtype="DIR_PATH", default="",
        description="The folder that holds the glint package, when Blender's Python does not find it "
                    "(e.g. <prefix>/lib/python3.11/dist-packages)")
    command: bpy.props.StringProperty(
        name="glint command", subtype="FILE_PATH", default="glint",
        description="The glint command, used where the module cannot load")
    use_command: bpy.props.BoolProperty(name="Always use the command", default=False)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "module_path")
        layout.prop(self, "command")
        layout.prop(self, "use_command")
        layout.label(text=core.backend_description(self))


class OBJECT_OT_glint_bake(bpy.types.Operator):
    """Bake the selected high polys onto the active low poly with glint"""
    bl_idname = "object.glint_bake"
    bl_label = "Bake with glint"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        settings = context.scene.glint_bake
        preferences = context.preferences.addons[__package__].preferences
        window_manager = context.window_manager
        status = {"started": False}

        def progress(label, done, total):
            if not status["started"]:
                window_manager.progress_begin(0, max(total, 1))
                status["started"] = True
            window_manager.progress_update(done)
            if context.workspace is not None:
                context.workspace.status_text_set(f"glint: {label} {done}/{total}")

        try:
            report = core.bake_scene(context, settings, preferences, progress)
        except core.BakeError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        except KeyboardInterrupt:
            self.report({"WARNING"}, "glint bake interrupted: nothing changed")
            return {"CANCELLED"}
        finally:
            if status["started"]:
                window_manager.progress_end()
            if context.workspace is not None:
                context.workspace.status_text_set(None)
        self.report({"INFO"}, report["summary"])
        context.scene["glint_last_bake"] = core.json_text(report)
        return {"FINISHED"}


class VIEW3D_PT_glint_bake(bpy.types.Panel):
    bl_label = "glint Bake"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "glint"

    def draw(self, context):
        draw_settings(self.layout, context)


class RENDER_PT_glint_bake(bpy.types.Panel):
    """The same settings inside Blender's own Bake panel (Render Properties > Bake)."""
    bl_label = "glint"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    bl_parent_id = "CYCLES_RENDER_PT_bake"
    bl_options = {"DEFAULT_CLOSED"}

    @classmethod
    def poll(cls, context):
        return hasattr(bpy.types, "CYCLES_RENDER_PT_bake")

    def draw(self, context):
        draw_settings(self.layout, context)


def draw_settings(layout, context):
    settings = context.scene.glint_bake
    layout.prop(settings, "use_names")
    if not settings.use_names:
        low = context.active_object
        highs = [o for o in context.selected_objects if o is not low and o.type == "MESH"]
        layout.label(text=f"Low: {low.name if low else '(none active)'}", icon="MESH_DATA")
        layout.label(text=f"High: {', '.join(o.name for o in highs) or '(select them)'}", icon="MESH_ICOSPHERE")
    column = layout.column(heading="Maps")
    for name in ("normal", "ao", "curvature", "thickness", "height", "position"):
        column.prop(settings, "bake_" + name)
    layout.prop(settings, "size")
    layout.prop(settings, "samples")
    if settings.bake_ao:
        layout.prop(settings, "ao_samples")
    row = layout.row()
    row.prop(settings, "max_front")
    row.prop(settings, "max_rear")
    layout.prop(settings, "float_maps")
    layout.prop(settings, "save_folder")
    layout.prop(settings, "wire")
    layout.operator(OBJECT_OT_glint_bake.bl_idname, icon="RENDER_STILL")


classes = (GlintBakeSettings, GlintBakePreferences, OBJECT_OT_glint_bake, VIEW3D_PT_glint_bake, RENDER_PT_glint_bake)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.glint_bake = bpy.props.PointerProperty(type=GlintBakeSettings)


def unregister():
    del bpy.types.Scene.glint_bake
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
