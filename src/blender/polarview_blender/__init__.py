"""polarview for Blender: the exact limit surface of polar subdivision (C2PS, Myles & Peters 2009)
and of the other schemes of polarview, made from the active mesh with the polarview module shipped
inside this add-on (docs/blender.md)."""

bl_info = {
    "name": "polarview",
    "author": "polarview",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > polarview",
    "description": "Exact limit surfaces of polar subdivision (C2PS, RTS, BPS, Catmull-Clark) with curvature",
    "category": "Mesh",
}

import bpy  # noqa: E402

from . import live, operators, panel, settings  # noqa: E402
from .module import LOAD_ERROR  # noqa: E402

_CLASSES = (settings.PolarviewSettings,) + operators.CLASSES + panel.CLASSES


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Object.polarview = bpy.props.PointerProperty(type=settings.PolarviewSettings)
    live.register()
    if LOAD_ERROR:
        print(f"polarview add-on: {LOAD_ERROR}")


def unregister():
    live.unregister()
    del bpy.types.Object.polarview
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
