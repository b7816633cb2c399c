# glint Bake: a Blender add-on that bakes with glint (docs/blender.md).
#
# The artist picks a low poly and one or more high polys (selected to active, or by their
# _low/_high names), the maps, size and samples, and presses Bake: glint bakes them through
# its Python module (`import glint`) or, where the module cannot load, through the `glint`
# command, on a worker thread while Blender stays responsive (progress in the status bar and
# the panel; Esc or Cancel stops it, leaving the scene as it was). The maps become Blender
# images packed into the .blend (or saved in a folder), and the low poly's material gets them
# wired. The panel's maps, sample counts, limits, defaults and help come from glint itself
# (glint.bake_options(), or `glint bake --describe`). Errors are Blender reports, not tracebacks.
bl_info = {
    "name": "glint Bake",
    "author": "glint",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > Sidebar > glint",
    "description": "Bake normal, AO and other maps from high polys onto a low poly with glint",
    "category": "Object",
}

import threading

import bpy

from . import core

# The bake running now (one at a time), read by the panel and the Cancel button.
RUNNING = {"bake": None, "fraction": 0.0, "text": "", "label": ""}


def _size_default(table):
    text = str(core.default(table, "size", "1024x1024"))
    return int(text.split("x")[0]) if "x" in text else int(text)


def _help(table, option, fallback=""):
    return table["options"].get(option, {}).get("help", fallback) if table else fallback


def settings_class(table):
    """The scene's bake settings as a PropertyGroup, its controls made from glint's own table
    (maps, labels, help, sample counts, limits, defaults); without glint, only what needs no table."""
    annotations = {
        "use_names": bpy.props.BoolProperty(
            name="Match by names", default=False,
            description="Bake every OBJECT_low from the objects named OBJECT_high (or OBJECT_high_*); otherwise the "
                        "active object is the low poly and the other selected meshes the high polys"),
        "float_maps": bpy.props.BoolProperty(
            name="32-bit float", default=False,
            description="Float maps (OpenEXR when saved) instead of 8-bit PNG: no banding in the normal map"),
        "save_folder": bpy.props.StringProperty(
            name="Save to", subtype="DIR_PATH", default="",
            description="A folder to save the maps in (UDIM tiles as NAME.<UDIM>.png), referenced relative to the "
                        ".blend; empty: packed into the .blend itself"),
        "wire": bpy.props.BoolProperty(name="Wire into the material", default=True,
                                       description="Connect the maps to the low poly's material"),
    }
    if table is not None:
        size = table["size"]
        annotations["size"] = bpy.props.IntProperty(
            name="Size", default=_size_default(table), min=size["min"], max=size["max"],
            description="Width and height of the maps in texels (" + _help(table, "size") + ")")
        samples = [str(n) for n in table["samples"]]
        annotations["samples"] = bpy.props.EnumProperty(
            name="Samples", default=str(core.default(table, "samples", samples[0])),
            items=[(n, n, f"{int(int(n) ** 0.5)}×{int(int(n) ** 0.5)} rays per texel") for n in samples],
            description=_help(table, "samples"))
        ao = table["ao_samples"]
        annotations["ao_samples"] = bpy.props.IntProperty(
            name="AO rays", default=int(core.default(table, "ao-samples", 16)), min=ao["min"], max=ao["max"],
            description=_help(table, "ao-samples"))
        if "device" in table["options"]:  # a glint that can bake on the GPU
            annotations["device"] = bpy.props.EnumProperty(
                name="Device", default=str(core.default(table, "device", "auto")),
                items=[("auto", "Auto", "The GPU when it is hardware and the bake fits its memory, else the CPU"),
                       ("cpu", "CPU", "Every core"),
                       ("gpu", "GPU", "The GPU, or an error without one")],
                description=_help(table, "device"))
        annotations["max_front"] = bpy.props.StringProperty(
            name="Max front", default=str(core.default(table, "max-front", "5%")), description=_help(table, "max-front"))
        annotations["max_rear"] = bpy.props.StringProperty(
            name="Max rear", default=str(core.default(table, "max-rear", "5%")), description=_help(table, "max-rear"))
        for m in core.offered_maps(table):
            annotations["bake_" + m["name"]] = bpy.props.BoolProperty(
                name=m["label"], default=m["name"] == "normal", description=m["summary"])
    return type("GlintBakeSettings", (bpy.types.PropertyGroup,), {"__annotations__": annotations})


def _preferences(context=None):
    addon = (context or bpy.context).preferences.addons.get(__package__)
    return addon.preferences if addon is not None else None


def reload_settings(self=None, context=None):
    """(Re)registers the settings from glint's table: at start, and when the preferences
    name another module or command."""
    table = core.bake_table(_preferences(context))
    if hasattr(bpy.types.Scene, "glint_bake"):
        del bpy.types.Scene.glint_bake
    old = getattr(bpy.types, "GlintBakeSettings", None)
    if old is not None:
        bpy.utils.unregister_class(old)
    cls = settings_class(table)
    bpy.utils.register_class(cls)
    bpy.types.Scene.glint_bake = bpy.props.PointerProperty(type=cls)


class GlintBakePreferences(bpy.types.AddonPreferences):
    bl_idname = __package__
    module_path: bpy.props.StringProperty(
        name="glint Python module", subtype="DIR_PATH", default="", update=reload_settings,
        description="The folder that holds the glint package, when Blender's Python does not find it "
                    "(e.g. <prefix>/lib/python3.11/dist-packages)")
    command: bpy.props.StringProperty(
        name="glint command", subtype="FILE_PATH", default="glint", update=reload_settings,
        description="The glint command, used where the module cannot load")
    use_command: bpy.props.BoolProperty(name="Always use the command", default=False, update=reload_settings)

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "module_path")
        layout.prop(self, "command")
        layout.prop(self, "use_command")
        layout.label(text=core.backend_description(self))


class OBJECT_OT_glint_bake(bpy.types.Operator):
    """Bake the selected high polys onto the active low poly with glint (Esc cancels)"""
    bl_idname = "object.glint_bake"
    bl_label = "Bake with glint"
    bl_options = {"REGISTER", "UNDO"}

    def _start(self, context):
        try:
            bake = core.Bake(context, context.scene.glint_bake, _preferences(context))
            bake.prepare(context)
        except core.BakeError as error:
            self.report({"ERROR"}, str(error))
            return None
        return bake

    def _finish(self, context, bake):
        try:
            report = bake.apply()
        except core.BakeError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        self.report({"INFO"}, report["summary"])
        context.scene["glint_last_bake"] = core.json_text(report)
        return {"FINISHED"}

    def execute(self, context):
        """From a script (or Blender without a window): the whole bake, then return."""
        bake = self._start(context)
        if bake is None:
            return {"CANCELLED"}
        try:
            bake.run()
        except core.BakeError as error:
            bake.cleanup()
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        except (core.Cancelled, KeyboardInterrupt):
            bake.cleanup()
            self.report({"WARNING"}, "glint bake interrupted: nothing changed")
            return {"CANCELLED"}
        return self._finish(context, bake)

    def invoke(self, context, event):
        """From the panel: the bake on a worker thread; Blender keeps drawing and answering."""
        if bpy.app.background or context.window is None:
            return self.execute(context)
        if RUNNING["bake"] is not None:
            self.report({"WARNING"}, "glint is baking already (Esc or Cancel stops it)")
            return {"CANCELLED"}
        bake = self._start(context)
        if bake is None:
            return {"CANCELLED"}
        bake.leave_a_core()
        self._bake, self._error = bake, None

        def work():
            try:
                bake.run()
            except BaseException as error:  # reported on Blender's thread
                self._error = error

        self._thread = threading.Thread(target=work, name="glint bake", daemon=True)
        RUNNING.update(bake=bake, fraction=0.0, text="glint: starting", label="Starting")
        window_manager = context.window_manager
        window_manager.progress_begin(0, 1000)
        self._timer = window_manager.event_timer_add(0.1, window=context.window)
        window_manager.modal_handler_add(self)
        self._thread.start()
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        bake = self._bake
        if event.type == "ESC" and event.value == "PRESS":
            bake.cancel.set()
            return {"RUNNING_MODAL"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}  # the viewport, menus and other tools keep working
        p = bake.progress
        pairs = len(bake.pairs)
        fraction = (p["pair"] + min(p["done"] / p["total"], 1.0)) / pairs
        names = ", ".join(low.name for low, _ in bake.pairs)
        text = f"glint: {p['label']} {names} {int(100 * fraction)}%" + (" (stopping)" if bake.cancel.is_set() else " — Esc cancels")
        RUNNING.update(fraction=fraction, text=text, label=f"{p['label'].capitalize()} {names}")
        context.window_manager.glint_bake_progress = 100.0 * fraction
        context.window_manager.progress_update(int(1000 * fraction))
        if context.workspace is not None:
            context.workspace.status_text_set(text)
        # Only the panels' regions: redrawing a whole viewport ten times a second would take
        # the time from Blender that the bake on its thread leaves it.
        for area in context.screen.areas if context.screen else []:
            if area.type in ("VIEW_3D", "PROPERTIES"):
                for region in area.regions:
                    if region.type in ("UI", "WINDOW") and (area.type == "PROPERTIES" or region.type == "UI"):
                        region.tag_redraw()
        if self._thread.is_alive():
            return {"RUNNING_MODAL"}
        self._end(context)
        error = self._error
        if isinstance(error, (core.Cancelled, KeyboardInterrupt)):
            bake.cleanup()
            self.report({"WARNING"}, "glint bake cancelled: nothing changed")
            return {"CANCELLED"}
        if isinstance(error, core.BakeError):
            bake.cleanup()
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        if error is not None:
            bake.cleanup()
            self.report({"ERROR"}, f"glint: {type(error).__name__}: {error}")
            return {"CANCELLED"}
        return self._finish(context, bake)

    def _end(self, context):
        window_manager = context.window_manager
        window_manager.event_timer_remove(self._timer)
        window_manager.progress_end()
        window_manager.glint_bake_progress = 0.0
        if context.workspace is not None:
            context.workspace.status_text_set(None)
        RUNNING.update(bake=None, fraction=0.0, text="", label="")
        for area in context.screen.areas if context.screen else []:
            area.tag_redraw()


class OBJECT_OT_glint_bake_cancel(bpy.types.Operator):
    """Stop the glint bake that is running; the scene stays as it was"""
    bl_idname = "object.glint_bake_cancel"
    bl_label = "Cancel"

    @classmethod
    def poll(cls, context):
        return RUNNING["bake"] is not None

    def execute(self, context):
        RUNNING["bake"].cancel.set()
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
    if RUNNING["bake"] is not None:  # baking: its progress, and the way to stop it
        layout.label(text=RUNNING.get("label", "Baking"), icon="RENDER_STILL")
        if hasattr(layout, "progress"):  # Blender 4.0+
            layout.progress(factor=RUNNING["fraction"], text=f"{int(100 * RUNNING['fraction'])}%")
        else:
            layout.prop(context.window_manager, "glint_bake_progress", text="Baked", slider=True)
        layout.operator(OBJECT_OT_glint_bake_cancel.bl_idname, icon="CANCEL")
        layout.label(text="Esc or Cancel: nothing changes")
        return
    settings = context.scene.glint_bake
    table = core.bake_table(_preferences(context))
    if table is None:
        layout.label(text="glint not found: set the module or the command", icon="ERROR")
        layout.label(text="in Edit > Preferences > Add-ons > glint Bake")
        return
    layout.prop(settings, "use_names")
    if not settings.use_names:
        low = context.active_object
        highs = [o for o in context.selected_objects if o is not low and o.type == "MESH"]
        layout.label(text=f"Low: {low.name if low else '(none active)'}", icon="MESH_DATA")
        layout.label(text=f"High: {', '.join(o.name for o in highs) or '(select them)'}", icon="MESH_ICOSPHERE")
    column = layout.column(heading="Maps")
    for m in core.offered_maps(table):
        column.prop(settings, "bake_" + m["name"])
    layout.prop(settings, "size")
    layout.prop(settings, "samples")
    if any(getattr(settings, "bake_" + name, False) for name in ("ao", "bent_normal", "thickness")):
        layout.prop(settings, "ao_samples")
    if hasattr(settings, "device"):
        layout.prop(settings, "device")
    row = layout.row()
    row.prop(settings, "max_front")
    row.prop(settings, "max_rear")
    layout.prop(settings, "float_maps")
    layout.prop(settings, "save_folder")
    layout.prop(settings, "wire")
    layout.operator(OBJECT_OT_glint_bake.bl_idname, icon="RENDER_STILL")


classes = (GlintBakePreferences, OBJECT_OT_glint_bake, OBJECT_OT_glint_bake_cancel, VIEW3D_PT_glint_bake,
           RENDER_PT_glint_bake)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    if core.pack_before_save not in bpy.app.handlers.save_pre:
        bpy.app.handlers.save_pre.append(core.pack_before_save)
    bpy.types.WindowManager.glint_bake_progress = bpy.props.FloatProperty(
        name="glint", subtype="PERCENTAGE", min=0.0, max=100.0, precision=0, description="How much of the bake is done")
    reload_settings()


def unregister():
    if RUNNING["bake"] is not None:
        RUNNING["bake"].cancel.set()
    if core.pack_before_save in bpy.app.handlers.save_pre:
        bpy.app.handlers.save_pre.remove(core.pack_before_save)
    del bpy.types.WindowManager.glint_bake_progress
    if hasattr(bpy.types.Scene, "glint_bake"):
        del bpy.types.Scene.glint_bake
    settings = getattr(bpy.types, "GlintBakeSettings", None)
    if settings is not None:
        bpy.utils.unregister_class(settings)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
