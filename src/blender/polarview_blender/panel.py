"""The sidebar panel View3D > Sidebar > polarview: the active control mesh's settings, Subdivide,
Live, its poles (valence, K, H) and the candidates that are no poles, n-gons to fans, area and
volume, and export. It draws the settings and the last analysis; the operators do the work."""
import json

import bpy

from .module import LOAD_ERROR, pv
from .operators import control_object

# Poles and rejected groups listed before "... and n more".
LISTED = 8


def _number(x):
    return "-" if x is None else f"{x:.6g}"


class POLARVIEW_PT_panel(bpy.types.Panel):
    bl_label = "polarview"
    bl_idname = "POLARVIEW_PT_panel"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "polarview"

    def draw(self, context):
        layout = self.layout
        if pv is None:
            box = layout.box()
            box.alert = True
            box.label(text="polarview could not load", icon='ERROR')
            for line in _wrap(LOAD_ERROR, 40):
                box.label(text=line)
            return
        source, why = control_object(context)
        if source is None:
            layout.label(text=why, icon='INFO')
            return
        s = source.polarview
        if context.active_object is not source:
            layout.label(text=f"limit surface of {source.name}", icon='MESH_DATA')

        col = layout.column(align=True)
        col.prop(s, "scheme")
        col.prop(s, "level")
        col.prop(s, "samples")
        layout.prop(s, "ngon_to_fan")
        row = layout.row(align=True)
        row.operator("polarview.subdivide", icon='MOD_SUBSURF')
        row.prop(s, "live", toggle=True, icon='FILE_REFRESH')
        if s.error:
            box = layout.box()
            box.alert = True
            for line in _wrap(s.error, 40):
                box.label(text=line)

        report = json.loads(s.report) if s.report else None
        if report is None:
            layout.operator("polarview.analyse", icon='VIEWZOOM')
        else:
            self.draw_report(layout, report)

        box = layout.box()
        box.label(text="Export limit surface")
        row = box.row(align=True)
        for name, label in (("step", "STEP"), ("iges", "IGES"), ("glb", "glb")):
            row.operator("polarview.export", text=label).format = name

    def draw_report(self, layout, report):
        box = layout.box()
        poles = report["poles"]
        box.label(text=f"Poles: {len(poles)}", icon='SPHERECURVE')
        for p in poles[:LISTED]:
            box.label(text=f"v{p['vertex']}  valence {p['valence']}  K {_number(p['K'])}  H {_number(p['H'])}")
        if len(poles) > LISTED:
            box.label(text=f"... and {len(poles) - LISTED} more")
        if report["rejected"]:
            box.label(text="Not poles:")
            for group in report["rejected"][:LISTED]:
                vertices = ", ".join(f"v{v}" for v in group["vertices"][:3])
                more = f" +{group['count'] - 3}" if group["count"] > 3 else ""
                box.label(text=f"{vertices}{more}: {group['reason']}")
        if report["fan_faces"]:
            box.label(text=f"{report['fan_faces']} faces of 5+ sides: try N-gons to fans", icon='INFO')
        if report.get("creases"):
            box.label(text=f"{report['creases']} creased edges and vertices (sharpness 10 c\u00b2)", icon='INFO')
        box.label(text=f"Area {_number(report['area'])}")
        box.label(text=f"Volume {_number(report['volume'])}" if report["closed"] else "Volume: open surface")
        if "vertices" in report:
            box.label(text=f"{report['vertices']} vertices, {report['triangles']} triangles")
            low, high = report["colour_range"]
            box.label(text=f"K colours over [{low:.3g}, {high:.3g}]")
        box.operator("polarview.analyse", icon='VIEWZOOM', text="Analyse again")


def _wrap(text, width):
    """Text in lines of about `width` characters (panel labels do not wrap)."""
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return lines + ([line] if line else [])


CLASSES = (POLARVIEW_PT_panel,)
