"""From a Blender control mesh to the limit surface as a Blender mesh, without any UI: the control
mesh as the module's Mesh, the analysis the panel shows (poles, rejected candidates, area and
volume), and the result mesh with the exact normals, K, H and the K colours of
``polarview.tessellate`` (the tessellation ``polarview export OUT.ply`` writes)."""
import json
import math

import bpy
import numpy
from mathutils import Matrix

from .module import require

# Names of what the result mesh carries.
GAUSSIAN = "gaussian_curvature"
MEAN = "mean_curvature"
COLOUR = "K colour"
MATERIAL = "polarview K colour"
# Faces with this many corners or more become triangle fans with "N-gons to fans" (ngon_to_fan.h).
MIN_FAN_SIDES = 5


def control_arrays(obj):
    """The object's own mesh (modifiers not applied; in Edit Mode its current edit) as float64
    vertices (N, 3), flat 0-based face indices and face sizes, in Blender's order."""
    if obj.mode == 'EDIT':
        obj.update_from_editmode()
    me = obj.data
    co = numpy.empty(3 * len(me.vertices), numpy.float32)
    me.vertices.foreach_get("co", co)
    starts = numpy.empty(len(me.polygons), numpy.int32)
    sizes = numpy.empty(len(me.polygons), numpy.int32)
    me.polygons.foreach_get("loop_start", starts)
    me.polygons.foreach_get("loop_total", sizes)
    loops = numpy.empty(len(me.loops), numpy.int32)
    me.loops.foreach_get("vertex_index", loops)
    # Face f's corners are loops[starts[f] : starts[f] + sizes[f]]; gathered in face order.
    order = numpy.repeat(starts - numpy.cumsum(sizes) + sizes, sizes) + numpy.arange(sizes.sum())
    return co.astype(numpy.float64).reshape(-1, 3), loops[order].astype(numpy.int64), sizes.astype(numpy.int64)


def crease_to_sharpness(crease):
    """Blender's crease c in [0, 1] as the OpenSubdiv sharpness Blender's own Subdivision Surface
    modifier gives it: 10 c^2 (c = 1 is infinitely sharp)."""
    return 10.0 * numpy.square(numpy.clip(crease, 0.0, 1.0))


def _layer_values(me, domain, legacy_attribute, attribute_name):
    """A float per edge or vertex: the legacy property (Blender 3.x: MeshEdge.crease) or the
    generic attribute (4.x: "crease_edge", "crease_vert"); None where the mesh has neither."""
    items = me.edges if domain == "EDGE" else me.vertices
    values = numpy.zeros(len(items), numpy.float32)
    if len(items) and legacy_attribute and hasattr(items[0], legacy_attribute):
        items.foreach_get(legacy_attribute, values)
        return values
    attribute = me.attributes.get(attribute_name)
    if attribute is not None and attribute.domain == domain and attribute.data_type == 'FLOAT':
        attribute.data.foreach_get("value", values)
        return values
    if domain == "POINT" and getattr(me, "vertex_creases", None):  # Blender 3.x's vertex crease layer
        me.vertex_creases[0].data.foreach_get("value", values)
        return values
    return None


def sharp_features(obj):
    """The object's edge and vertex creases as the module's tags: crease edges (E, 2) with their
    sharpness (E,) and corners (C,) with theirs, each crease c > 0 as crease_to_sharpness(c)."""
    me = obj.data
    edges = numpy.zeros((0, 2), numpy.int64)
    edge_sharpness = numpy.zeros(0)
    creases = _layer_values(me, "EDGE", "crease", "crease_edge")
    if creases is not None and numpy.any(creases > 0.0):
        ends = numpy.empty(2 * len(me.edges), numpy.int32)
        me.edges.foreach_get("vertices", ends)
        chosen = creases > 0.0
        edges = ends.reshape(-1, 2)[chosen].astype(numpy.int64)
        edge_sharpness = crease_to_sharpness(creases[chosen].astype(numpy.float64))
    corners = numpy.zeros(0, numpy.int64)
    corner_sharpness = numpy.zeros(0)
    vertex_creases = _layer_values(me, "POINT", None, "crease_vert")
    if vertex_creases is not None and numpy.any(vertex_creases > 0.0):
        corners = numpy.flatnonzero(vertex_creases > 0.0).astype(numpy.int64)
        corner_sharpness = crease_to_sharpness(vertex_creases[corners].astype(numpy.float64))
    return edges, edge_sharpness, corners, corner_sharpness


def crease_count(obj):
    """How many edges and vertices of the object's mesh carry a Blender crease (> 0)."""
    edges, _, corners, _ = sharp_features(obj)
    return int(len(edges) + len(corners))


def control_mesh(obj, ngon_to_fan):
    """The module's Mesh of the object's control mesh (n-gons of 5 or more sides fanned when asked)
    and the number of faces of 5 or more sides (fanned or not). ValueError (the module's message)
    for a mesh it refuses."""
    pv = require()
    if len(obj.data.polygons) == 0:
        raise ValueError(f"{obj.name} has no faces: the control mesh needs faces")
    vertices, indices, sizes = control_arrays(obj)
    edges, edge_sharpness, corners, corner_sharpness = sharp_features(obj)
    mesh = pv.Mesh(vertices, indices, sizes, crease_edges=edges, crease_sharpness=edge_sharpness, corners=corners,
                   corner_sharpness=corner_sharpness)
    fanned = int(numpy.count_nonzero(sizes >= MIN_FAN_SIDES))
    if ngon_to_fan and fanned:
        mesh, _ = pv.ngon_to_fan(mesh, MIN_FAN_SIDES)
    return mesh, fanned


def analyse(mesh, scheme, level, fan_faces_left):
    """What the panel shows of a control mesh: its poles (vertex, valence, and for a polar scheme
    K and H at the pole), the candidates that are no poles and why, the faces "N-gons to fans"
    would convert, and area and volume of the limit surface (the module's measure())."""
    pv = require()
    info = mesh.info()
    curvature = {}
    if scheme in pv.POLAR_SCHEMES and info["poles"]:
        for p in pv.pole(mesh, scheme):
            curvature[p["vertex"]] = (p["gaussian_curvature"], p["mean_curvature"], list(p["limit"]))
    poles = []
    for p in info["poles"]:
        K, H, limit = curvature.get(p["vertex"], (None, None, None))
        poles.append({"vertex": p["vertex"], "valence": p["valence"], "K": K, "H": H, "limit": limit,
                      "treatment": p["schemes"].get(pv.scheme_name(scheme).split("-")[0], "")})
    rejected = [{"reason": g["words"], "vertices": g["vertices"][:6], "count": len(g["vertices"]),
                 "max_valence": g["max_valence"]} for g in info["rejected_groups"]]
    measured = pv.measure(mesh, scheme, level)
    return {"poles": poles, "rejected": rejected, "fan_faces": fan_faces_left,
            "area": measured["area"], "volume": measured["volume"], "closed": measured["closed"]}


def srgb_to_linear(c):
    """sRGB in [0, 1] to linear (Blender's float colour attributes hold linear values)."""
    c = numpy.asarray(c, numpy.float64)
    return numpy.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def build_mesh(name, tess):
    """A new Blender mesh of a tessellation: its triangles smooth-shaded with custom split normals
    set to the exact normals (no creases in the shading), float point attributes K and H, and the K
    colours as the active colour attribute (linear floats)."""
    positions, triangles = tess["positions"], tess["triangles"]
    nv, nt = len(positions), len(triangles)
    me = bpy.data.meshes.new(name)
    me.vertices.add(nv)
    me.vertices.foreach_set("co", positions.astype(numpy.float32).ravel())
    me.loops.add(3 * nt)
    me.loops.foreach_set("vertex_index", triangles.astype(numpy.int32).ravel())
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", numpy.arange(0, 3 * nt, 3, dtype=numpy.int32))
    me.polygons.foreach_set("loop_total", numpy.full(nt, 3, numpy.int32))
    me.polygons.foreach_set("use_smooth", numpy.ones(nt, bool))
    me.update(calc_edges=True)
    # Exact normals as custom split normals (Blender 3.x uses them only with Auto Smooth on).
    if hasattr(me, "use_auto_smooth"):  # gone in Blender 4.1, where custom normals need no switch
        me.use_auto_smooth = True
        me.auto_smooth_angle = math.pi
    me.normals_split_custom_set_from_vertices(tess["normals"].astype(numpy.float32))
    for attribute, values in ((GAUSSIAN, tess["gaussian"]), (MEAN, tess["mean"])):
        me.attributes.new(attribute, 'FLOAT', 'POINT').data.foreach_set("value", values.astype(numpy.float32))
    rgba = numpy.ones((nv, 4), numpy.float32)
    rgba[:, :3] = srgb_to_linear(tess["colours"])
    colour = me.color_attributes.new(COLOUR, 'FLOAT_COLOR', 'POINT')
    colour.data.foreach_set("color", rgba.ravel())
    me.color_attributes.active_color = colour
    if hasattr(me.color_attributes, "render_color_index"):
        me.color_attributes.render_color_index = me.color_attributes.active_color_index
    me.materials.append(colour_material())
    return me


def colour_material():
    """The material that shows the K colour attribute (Material Preview, Rendered; Solid mode shows
    it with Viewport Shading > Color > Attribute)."""
    material = bpy.data.materials.get(MATERIAL)
    if material is not None:
        return material
    material = bpy.data.materials.new(MATERIAL)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    shader = nodes.get("Principled BSDF")
    attribute = nodes.new("ShaderNodeVertexColor")
    attribute.layer_name = COLOUR
    attribute.location = (shader.location.x - 300, shader.location.y)
    material.node_tree.links.new(attribute.outputs["Color"], shader.inputs["Base Color"])
    shader.inputs["Roughness"].default_value = 0.45
    return material


def place_beside(result, source, vertices):
    """Puts a new result beside its control mesh: the source's transform, moved along its local x
    by 1.25 times the control mesh's width."""
    width = float(numpy.ptp(vertices[:, 0])) if len(vertices) else 1.0
    result.matrix_world = source.matrix_world @ Matrix.Translation((1.25 * max(width, 1e-6), 0.0, 0.0))


def subdivide(context, source, scheme, level, samples, ngon_to_fan):
    """Makes (or remakes) the limit surface of `source`: a new object beside it the first time,
    else the same result object with a new mesh. Stores the settings and the analysis on the
    source. Returns (result object, summary line). Raises ValueError, MemoryError, TypeError or
    RuntimeError with the module's message for input it refuses."""
    pv = require()
    settings = source.polarview
    mesh, fanned = control_mesh(source, ngon_to_fan)
    vertices = numpy.asarray(mesh.vertices)
    fan_faces_left = 0 if ngon_to_fan else fanned
    tess = pv.tessellate(mesh, scheme, level, samples)
    report = analyse(mesh, scheme, level, fan_faces_left)
    report.update({"vertices": len(tess["positions"]), "triangles": len(tess["triangles"]),
                   "watertight": bool(tess["watertight"]), "boundary_edges": int(tess["boundary_edges"]),
                   "colour_range": list(tess["colour_range"]), "creases": crease_count(source),
                   "K_range": [float(tess["gaussian"].min()), float(tess["gaussian"].max())],
                   "fanned": fanned if ngon_to_fan else 0})

    # The result: the same object when it is still there, with a new mesh.
    name = f"{source.name} limit"
    me = build_mesh(name, tess)
    result = settings.result
    if result is not None and result.name in context.scene.objects:
        old = result.data
        result.data = me
        if old.users == 0:
            bpy.data.meshes.remove(old)
    else:
        result = bpy.data.objects.new(name, me)
        collections = source.users_collection or (context.scene.collection,)
        collections[0].objects.link(result)
        place_beside(result, source, vertices)
        settings.result = result
    result.polarview.source = source

    settings.scheme, settings.level, settings.samples, settings.ngon_to_fan = scheme, level, samples, ngon_to_fan
    settings.report = json.dumps(report)
    settings.error = ""
    summary = (f"{result.name}: {report['vertices']} vertices, {report['triangles']} triangles, "
               f"{'watertight' if report['watertight'] else str(report['boundary_edges']) + ' boundary edges'}, "
               f"{len(report['poles'])} pole{'s' if len(report['poles']) != 1 else ''}")
    return result, summary
