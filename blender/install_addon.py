# Installing the glint Bake add-on into the running Blender, the way that Blender installs
# add-ons: as an extension in Blender 4.2 and later, as a legacy add-on before. Not part of the
# add-on: its tests (tests/blender) and `glint bench bake`'s Blender peer (bench/peers) use it.
import bpy


def install_addon(legacy_zip, extension_zip):
    """Installs and enables the add-on: as an extension in Blender 4.2 and later (its
    blender_manifest.toml; Install from Disk), as a legacy add-on before (its bl_info; Install...).
    Returns its module name, the key of bpy.context.preferences.addons."""
    if bpy.app.version >= (4, 2, 0):
        bpy.ops.extensions.package_install_files(filepath=extension_zip, repo="user_default", enable_on_install=True)
        return "bl_ext.user_default.glint_bake"
    bpy.ops.preferences.addon_install(filepath=legacy_zip, overwrite=True)
    bpy.ops.preferences.addon_enable(module="glint_bake")
    return "glint_bake"
