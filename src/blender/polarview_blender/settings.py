"""What the add-on keeps on an object (Object.polarview): on a control mesh its scheme, level,
samples, the toggles, its result object and the last analysis; on a result the control mesh it
came from. Saved with the .blend file and undone with the rest."""
import bpy

from . import live
from .module import pv

# The schemes as the module's table lists them (the CLI's names and the viewer's labels); a fixed
# copy when the module did not load, so the panel still draws.
if pv is not None:
    SCHEME_ITEMS = [(row["name"], row["label"], f"{row['label']} ({'polar rules' if row['polar'] else 'no polar rules'})")
                    for row in pv.schemes()]
else:
    SCHEME_ITEMS = [(name, name, "") for name in ("cc", "c2ps", "c2ps-u", "rts", "rts-u", "bps")]


def _live_changed(self, context):
    live.changed(self.id_data)


class PolarviewSettings(bpy.types.PropertyGroup):
    scheme: bpy.props.EnumProperty(name="Scheme", items=SCHEME_ITEMS, default="c2ps",
                                   description="The subdivision scheme (docs/schemes.md)")
    level: bpy.props.IntProperty(name="Level", default=3, min=0, max=12, soft_max=7,
                                 description="Refinement levels before the limit patches are taken")
    samples: bpy.props.IntProperty(name="Samples", default=8, min=1, max=64, soft_max=16,
                                   description="Segments along each patch edge of the tessellation")
    ngon_to_fan: bpy.props.BoolProperty(
        name="N-gons to fans", default=False,
        description="Subdivide as if every face of 5 or more sides were a triangle fan around its centre "
                    "(Blender's triangle-fan fill): a cylinder's caps become poles. The control mesh is not changed")
    live: bpy.props.BoolProperty(name="Live", default=False, update=_live_changed,
                                 description="Make the surface again when the control mesh is edited")
    result: bpy.props.PointerProperty(type=bpy.types.Object, name="Result",
                                      description="The limit surface made of this control mesh")
    source: bpy.props.PointerProperty(type=bpy.types.Object, name="Control mesh",
                                      description="The control mesh this limit surface was made of")
    report: bpy.props.StringProperty(name="Analysis", default="", description="The last analysis (JSON)")
    error: bpy.props.StringProperty(name="Error", default="", description="Why the last live update failed")
