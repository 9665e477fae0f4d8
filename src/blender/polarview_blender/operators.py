"""The add-on's operators: polarview.subdivide (the limit surface as a new object beside the control
mesh), polarview.analyse (poles, area and volume only) and polarview.export (STEP, IGES, glb, PLY
through the module's writers). Bad input is reported in Blender's UI (self.report), never raised."""
import os

import bpy
from bpy_extras.io_utils import ExportHelper

from . import live
from .module import LOAD_ERROR, pv
from .settings import SCHEME_ITEMS

# What the module raises for input it refuses (docs/python.md, Errors).
INPUT_ERRORS = (ValueError, MemoryError, TypeError, RuntimeError)


def refusal(source, error):
    """The line the UI shows for an error of the module about `source` (its arrays have no name of
    their own: "<arrays>" becomes the object's)."""
    text = str(error)
    if text.startswith("<arrays>: "):
        text = text[len("<arrays>: "):]
    return f"{source.name}: {text}"


def control_object(context):
    """The active object's control mesh (a result's source), or (None, why not)."""
    obj = context.active_object
    if obj is None:
        return None, "no active object: select a mesh"
    if obj.polarview.source is not None:
        obj = obj.polarview.source
    if obj.type != 'MESH':
        return None, f"{obj.name} is not a mesh (its type is {obj.type.lower()})"
    return obj, ""


def operand(operator, context):
    """The control mesh an operator works on, or None after reporting why there is none (the module
    did not load, or no mesh is active)."""
    if pv is None:
        operator.report({'ERROR'}, LOAD_ERROR)
        return None
    source, why = control_object(context)
    if source is None:
        operator.report({'ERROR'}, why)
    return source


def show_colours_in_solid_mode(context):
    """Solid mode shows the active colour attribute (Viewport Shading > Color > Attribute) in the 3D
    views of the current screen that showed material colours, so the K colours appear at once."""
    screen = context.screen
    for area in (screen.areas if screen else ()):
        if area.type == 'VIEW_3D':
            shading = area.spaces.active.shading
            if shading.color_type == 'MATERIAL':
                shading.color_type = 'VERTEX'


class POLARVIEW_OT_subdivide(bpy.types.Operator):
    """Make the exact limit surface of the active mesh as a new object beside it"""
    bl_idname = "polarview.subdivide"
    bl_label = "Subdivide"
    bl_options = {'REGISTER', 'UNDO'}

    scheme: bpy.props.EnumProperty(name="Scheme", items=SCHEME_ITEMS, default="c2ps")
    level: bpy.props.IntProperty(name="Level", default=3, min=0, max=12, soft_max=7)
    samples: bpy.props.IntProperty(name="Samples", default=8, min=1, max=64, soft_max=16)
    ngon_to_fan: bpy.props.BoolProperty(name="N-gons to fans", default=False)

    def execute(self, context):
        source = operand(self, context)
        if source is None:
            return {'CANCELLED'}
        # Arguments not given come from the control mesh's panel settings.
        settings = source.polarview
        for name in ("scheme", "level", "samples", "ngon_to_fan"):
            if not self.properties.is_property_set(name):
                setattr(self, name, getattr(settings, name))
        from .surface import subdivide
        try:
            result, summary = subdivide(context, source, self.scheme, self.level, self.samples, self.ngon_to_fan)
        except INPUT_ERRORS as error:
            self.report({'ERROR'}, refusal(source, error))
            return {'CANCELLED'}
        live.remember(source)
        show_colours_in_solid_mode(context)
        self.report({'INFO'}, summary)
        return {'FINISHED'}


class POLARVIEW_OT_analyse(bpy.types.Operator):
    """Find the poles of the active mesh and measure its limit surface (no new object)"""
    bl_idname = "polarview.analyse"
    bl_label = "Analyse"
    bl_options = {'REGISTER'}

    def execute(self, context):
        source = operand(self, context)
        if source is None:
            return {'CANCELLED'}
        import json
        from .surface import analyse, control_mesh, crease_count
        s = source.polarview
        try:
            mesh, fanned = control_mesh(source, s.ngon_to_fan)
            report = analyse(mesh, s.scheme, s.level, 0 if s.ngon_to_fan else fanned)
        except INPUT_ERRORS as error:
            self.report({'ERROR'}, refusal(source, error))
            return {'CANCELLED'}
        report["creases"] = crease_count(source)
        s.report = json.dumps(report)
        self.report({'INFO'}, f"{source.name}: {len(report['poles'])} poles, area {report['area']:.6g}")
        return {'FINISHED'}


FORMATS = [("step", "STEP", "B-spline surfaces (AP214), exact", ".step"),
           ("iges", "IGES", "IGES 5.3 B-spline surfaces (entity 128)", ".igs"),
           ("glb", "glTF binary", "the tessellation with K and H per vertex", ".glb"),
           ("ply", "PLY", "the tessellation with exact normal, K and H per vertex", ".ply")]
UNITS = [("mm", "mm", ""), ("m", "m", ""), ("inch", "inch", "")]


class POLARVIEW_OT_export(bpy.types.Operator, ExportHelper):
    """Write the limit surface of the active mesh (its scheme, level and samples) with polarview's writers"""
    bl_idname = "polarview.export"
    bl_label = "Export limit surface"
    bl_options = {'REGISTER'}

    filename_ext = ".step"
    check_extension = None  # the extension follows the format
    filter_glob: bpy.props.StringProperty(default="*.step;*.stp;*.igs;*.iges;*.glb;*.ply", options={'HIDDEN'})
    format: bpy.props.EnumProperty(name="Format", items=[f[:3] for f in FORMATS], default="step")
    units: bpy.props.EnumProperty(name="Units", items=UNITS, default="mm",
                                  description="The length unit STEP and IGES files name (coordinates are not scaled)")

    def invoke(self, context, event):
        source, _ = control_object(context)
        extension = dict((f[0], f[3]) for f in FORMATS)[self.format]
        stem = bpy.path.clean_name(source.name if source else "surface")
        folder = os.path.dirname(bpy.data.filepath) if bpy.data.filepath else ""
        self.filepath = os.path.join(folder, stem + "_limit" + extension)
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}

    def execute(self, context):
        source = operand(self, context)
        if source is None:
            return {'CANCELLED'}
        from .surface import control_mesh
        s = source.polarview
        path = bpy.path.abspath(self.filepath)
        try:
            mesh, _ = control_mesh(source, s.ngon_to_fan)
            summary = pv.export_surface(mesh, path, s.scheme, s.level, format=self.format, samples=s.samples,
                                        units=self.units)
        except INPUT_ERRORS as error:
            self.report({'ERROR'}, refusal(source, error))
            return {'CANCELLED'}
        self.report({'INFO'}, f"{path}: {summary}")
        return {'FINISHED'}


CLASSES = (POLARVIEW_OT_subdivide, POLARVIEW_OT_analyse, POLARVIEW_OT_export)
