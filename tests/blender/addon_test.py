"""The Blender add-on, headless (run by run_addon_test.sh inside `blender -b --factory-startup`):
installs build/blender/polarview_blender.zip, subdivides the default model (Blender's OBJ importer)
and a Blender UV sphere (valence-32 triangle-fan poles), and checks the result against the CLI:
`polarview export x.ply --samples N` (vertex count, triangles, positions, K, H, colours), `polarview
pole --json` (K and H at each pole) and `polarview measure --json` (area, volume). Also: the exact
normals as custom split normals, a watertight result, live updates, export files, errors reported
in the UI, and an add-on whose extension cannot load.

Case `broken` installs a copy of the zip without the extension."""
import argparse
import json
import os
import subprocess
import sys
import time
import zipfile

import bpy
import numpy

args = argparse.ArgumentParser()
args.add_argument("--zip", required=True)
args.add_argument("--cli", required=True)
args.add_argument("--source", required=True)
args.add_argument("--work", required=True)
args.add_argument("--case", choices=("surfaces", "broken"), required=True)
args = args.parse_args(sys.argv[sys.argv.index("--") + 1:])

# Tolerances. Blender keeps positions and float attributes as float32: values agree with the CLI's
# doubles to float32's rounding (2^-24 relative), not better.
FLOAT32 = 2.0 ** -24
POSITION_TOLERANCE = 4 * FLOAT32   # of the bounding box's diagonal
CURVATURE_TOLERANCE = 2 * FLOAT32  # of the value (float32 rounding of one double)
NORMAL_ANGLE = 2e-3                # radians: Blender stores custom normals in a compressed form
STARTED = time.monotonic()


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def install(path):
    bpy.ops.preferences.addon_install(filepath=path, overwrite=True)
    bpy.ops.preferences.addon_enable(module="polarview_blender")
    import polarview_blender  # noqa: F401  (what addon_enable loaded)
    check(hasattr(bpy.types, "POLARVIEW_PT_panel"), "the panel is not registered")
    installed = os.path.dirname(sys.modules["polarview_blender"].__file__)
    check(installed.startswith(os.environ["BLENDER_USER_SCRIPTS"]), f"installed outside the test's scripts folder: {installed}")


def cli(*arguments):
    done = subprocess.run([args.cli, *arguments], capture_output=True, text=True)
    check(done.returncode == 0, f"polarview {' '.join(arguments)}: {done.stderr}")
    return done.stdout


def write_obj(obj, path):
    """The object's mesh as an OBJ, written here (not by the add-on), every float32 exactly; its
    edge creases c > 0 as `t crease` tags of sharpness 10 c^2 (Blender's own mapping for its
    Subdivision Surface modifier)."""
    me = obj.data
    with open(path, "w") as f:
        for v in me.vertices:
            f.write("v %r %r %r\n" % tuple(float(c) for c in v.co))
        for p in me.polygons:
            f.write("f " + " ".join(str(i + 1) for i in p.vertices) + "\n")
        for e in me.edges:
            if e.crease > 0.0:
                f.write("t crease 2/1/0 %d %d %r\n" % (e.vertices[0], e.vertices[1], 10.0 * float(e.crease) ** 2))


def read_ply(path):
    """The CLI's binary PLY (formats.md): vertex x y z nx ny nz quality K H (double) r g b (uchar)."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode()
    nv = int(header.split("element vertex ")[1].split()[0])
    nt = int(header.split("element face ")[1].split()[0])
    vertex = numpy.dtype([("p", "<f8", 3), ("n", "<f8", 3), ("q", "<f8"), ("K", "<f8"), ("H", "<f8"), ("c", "u1", 3)])
    face = numpy.dtype([("k", "u1"), ("i", "<i4", 3)])
    v = numpy.frombuffer(data, vertex, nv, end)
    f = numpy.frombuffer(data, face, nt, end + nv * vertex.itemsize)
    check(numpy.all(f["k"] == 3), "the PLY has a face that is no triangle")
    return {"positions": v["p"], "normals": v["n"], "K": v["K"], "H": v["H"], "colours": v["c"], "triangles": f["i"]}


def result_arrays(obj):
    """What the add-on made: positions, K, H, colours (linear RGBA), triangles, loop normals."""
    me = obj.data
    n = len(me.vertices)
    out = {}
    co = numpy.empty(3 * n, numpy.float32)
    me.vertices.foreach_get("co", co)
    out["positions"] = co.reshape(-1, 3).astype(numpy.float64)
    for name, key in (("gaussian_curvature", "K"), ("mean_curvature", "H")):
        attribute = me.attributes[name]
        check(attribute.domain == 'POINT' and attribute.data_type == 'FLOAT', f"{name} is not a float point attribute")
        values = numpy.empty(n, numpy.float32)
        attribute.data.foreach_get("value", values)
        out[key] = values.astype(numpy.float64)
    colour = me.color_attributes.active_color
    check(colour is not None and colour.name == "K colour", "no active colour attribute 'K colour'")
    rgba = numpy.empty(4 * n, numpy.float32)
    colour.data.foreach_get("color", rgba)
    out["colours"] = rgba.reshape(-1, 4)
    loops = numpy.empty(len(me.loops), numpy.int32)
    me.loops.foreach_get("vertex_index", loops)
    out["triangles"] = loops.reshape(-1, 3)
    me.calc_normals_split()
    normals = numpy.empty(3 * len(me.loops), numpy.float32)
    me.loops.foreach_get("normal", normals)
    out["loop_normals"] = normals.reshape(-1, 3)
    edges = numpy.empty(len(me.loops), numpy.int32)
    me.loops.foreach_get("edge_index", edges)
    out["faces_per_edge"] = numpy.bincount(edges, minlength=len(me.edges))
    out["euler"] = len(me.vertices) - len(me.edges) + len(me.polygons)
    return out


def linear_to_srgb(c):
    c = numpy.asarray(c, numpy.float64)
    return numpy.where(c <= 0.0031308, 12.92 * c, 1.055 * numpy.power(numpy.maximum(c, 0), 1 / 2.4) - 0.055)


def compare_with_cli(control, result, scheme, level, samples, label, closed=True, normal_angle=None):
    """The result against the CLI on the same control mesh; returns the measured differences.
    `closed`: also watertight with a sphere's Euler characteristic; `normal_angle`: the corner
    normals' tolerance (NORMAL_ANGLE by default)."""
    obj_path = os.path.join(args.work, f"{label}.obj")
    ply_path = os.path.join(args.work, f"{label}.ply")
    write_obj(control, obj_path)
    cli("export", obj_path, "-o", ply_path, "--scheme", scheme, "--level", str(level), "--samples", str(samples))
    ply, got = read_ply(ply_path), result_arrays(result)
    check(len(got["positions"]) == len(ply["positions"]),
          f"{label}: {len(got['positions'])} vertices, the CLI's PLY {len(ply['positions'])}")
    check(numpy.array_equal(got["triangles"], ply["triangles"]), f"{label}: the triangles differ from the CLI's")
    diagonal = numpy.linalg.norm(numpy.ptp(ply["positions"], axis=0))
    position = numpy.abs(got["positions"] - ply["positions"]).max() / diagonal
    check(position <= POSITION_TOLERANCE, f"{label}: positions differ by {position:.3g} of the diagonal")
    stats = {"vertices": len(ply["positions"]), "triangles": len(ply["triangles"]), "position": position}
    for key in ("K", "H"):
        error = numpy.abs(got[key] - ply[key]) / numpy.maximum(numpy.abs(ply[key]), 1e-30)
        worst = error.max()
        check(worst <= CURVATURE_TOLERANCE, f"{label}: {key} differs by {worst:.3g} (relative) at vertex {error.argmax()}")
        stats[key] = worst
    # Colours: the PLY's bytes are the same sRGB colours rounded to 1/255.
    srgb = linear_to_srgb(got["colours"][:, :3]) * 255.0
    colour = numpy.abs(srgb - ply["colours"]).max()
    check(colour <= 0.5 + 1e-3, f"{label}: colours differ from the PLY's by {colour:.3g}/255")
    stats["colour"] = colour
    # Custom split normals: every corner's normal is its vertex's exact normal (no shading creases).
    exact = ply["normals"][got["triangles"].ravel()]
    cosine = numpy.clip(numpy.einsum("ij,ij->i", exact, got["loop_normals"]), -1.0, 1.0)
    angle = numpy.arccos(cosine).max()
    check(angle <= (normal_angle or NORMAL_ANGLE), f"{label}: a corner normal is {angle:.3g} rad from the exact normal")
    stats["normal_angle"] = angle
    if not closed:
        return stats, got
    # Watertight: every edge between exactly two triangles; a sphere's Euler characteristic.
    check(numpy.all(got["faces_per_edge"] == 2), f"{label}: an edge is not between two triangles")
    check(got["euler"] == 2, f"{label}: Euler characteristic {got['euler']}, not 2")
    return stats, got


def check_poles(control, got, scheme, label, valences):
    """K and H at each pole: the panel's report and the result's attributes against `pole --json`."""
    poles = json.loads(cli("pole", os.path.join(args.work, f"{label}.obj"), "--scheme", scheme, "--json"))["poles"]
    check(sorted(p["valence"] for p in poles) == sorted(valences), f"{label}: the CLI's poles {poles}")
    report = json.loads(control.polarview.report)
    check(sorted(p["valence"] for p in report["poles"]) == sorted(valences), f"{label}: the panel's poles {report['poles']}")
    by_vertex = {p["vertex"]: p for p in report["poles"]}
    worst = 0.0
    for p in poles:
        mine = by_vertex[p["vertex"]]
        for key, name in (("K", "gaussian_curvature"), ("H", "mean_curvature")):
            check(abs(mine[key] - p[name]) <= 1e-12 * abs(p[name]), f"{label}: panel {key} {mine[key]} != CLI {p[name]}")
        # The result's vertex at the pole's limit point carries its K and H.
        distance = numpy.linalg.norm(got["positions"] - numpy.array(p["limit"]), axis=1)
        v = int(distance.argmin())
        check(distance[v] <= 1e-6, f"{label}: no result vertex at the pole {p['limit']} (nearest {distance[v]:.3g})")
        for key, name in (("K", "gaussian_curvature"), ("H", "mean_curvature")):
            error = abs(got[key][v] - p[name]) / abs(p[name])
            check(error <= CURVATURE_TOLERANCE, f"{label}: {key} at the pole {got[key][v]} != CLI {p[name]}")
            worst = max(worst, error)
    return poles, worst


def check_measure(control, scheme, level, label):
    measured = json.loads(cli("measure", os.path.join(args.work, f"{label}.obj"), "--scheme", scheme,
                              "--level", str(level), "--json"))
    report = json.loads(control.polarview.report)
    for key in ("area", "volume"):
        check(abs(report[key] - measured[key]) <= 1e-12 * abs(measured[key]),
              f"{label}: panel {key} {report[key]} != CLI {measured[key]}")
    return measured


class FakeLayout:
    """Stands in for a panel's UILayout (a background Blender draws no panels): records the
    labels, properties and operators a draw() asks for."""

    def __init__(self):
        self.lines, self.alert = [], False

    def label(self, text="", icon='NONE'):
        self.lines.append(text)

    def prop(self, data, name, **options):
        self.lines.append(f"[{name} = {getattr(data, name)}]")

    def operator(self, idname, text="", icon='NONE'):
        self.lines.append(f"<{idname} {text}>")
        return type("OperatorProperties", (), {})()

    def box(self):
        return self

    def row(self, align=False):
        return self

    def column(self, align=False):
        return self


def draw_panel():
    """The sidebar panel's lines for the active object."""
    import polarview_blender.panel as panel
    cls = panel.POLARVIEW_PT_panel
    fake = type("Panel", (), {"layout": FakeLayout(), "draw_report": cls.draw_report})()
    cls.draw(fake, bpy.context)
    return fake.layout.lines


def subdivide(obj, **arguments):
    for other in bpy.context.selected_objects:
        other.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return bpy.ops.polarview.subdivide(**arguments)


def expect_error(words, **arguments):
    """An operator call the add-on must refuse with a message in the UI (RuntimeError from bpy.ops
    in the background) naming `words`, not a traceback."""
    try:
        bpy.ops.polarview.subdivide(**arguments)
    except RuntimeError as error:
        text = str(error)
        check(words in text and "Traceback" not in text, f"refused with {text!r}, expected {words!r}")
        return text
    raise AssertionError(f"accepted {arguments}, expected an error naming {words!r}")


def case_surfaces():
    install(args.zip)
    for obj in list(bpy.data.objects):  # the startup scene's cube, camera and light
        bpy.data.objects.remove(obj)
    timings = {}

    # The default model through Blender's OBJ importer, its axes as they are.
    bpy.ops.wm.obj_import(filepath=os.path.join(args.source, "assets", "default.obj"), forward_axis='Y', up_axis='Z')
    model = bpy.context.selected_objects[0]
    check((len(model.data.vertices), len(model.data.polygons)) == (113, 117), "the OBJ importer changed the model")
    start = time.monotonic()
    check(subdivide(model, scheme="c2ps", level=3, samples=4) == {'FINISHED'}, "subdivide did not finish")
    timings["default"] = time.monotonic() - start
    result = model.polarview.result
    check(result is not None and result.polarview.source == model, "the result is not linked to its control mesh")
    check(result.location.x > model.location.x + 1.0, "the result does not sit beside the control mesh")
    check(result.active_material is not None and result.active_material.name == "polarview K colour", "no colour material")
    check(model.name in bpy.data.objects, "the control mesh was not kept")
    stats, got = compare_with_cli(model, result, "c2ps", 3, 4, "default")
    poles, pole_error = check_poles(model, got, "c2ps", "default", [12])
    measured = check_measure(model, "c2ps", 3, "default")
    lines = draw_panel()
    for expected in ("[scheme = c2ps]", "[level = 3]", "[samples = 4]", "Poles: 1",
                     f"v0  valence 12  K {poles[0]['gaussian_curvature']:.6g}  H {poles[0]['mean_curvature']:.6g}",
                     f"Area {measured['area']:.6g}", f"Volume {measured['volume']:.6g}", "<polarview.export STEP>"):
        check(expected in lines, f"the panel does not show {expected!r}: {lines}")
    print(f"default c2ps 3 samples 4: {stats}; pole K {poles[0]['gaussian_curvature']:.9g}, "
          f"H {poles[0]['mean_curvature']:.9g} (worst relative error at the pole {pole_error:.3g}); "
          f"area {measured['area']:.9g}, volume {measured['volume']:.9g}")

    # A Blender UV sphere: its poles are 32-valent triangle fans ringed by quads.
    bpy.ops.mesh.primitive_uv_sphere_add(location=(0.0, 4.0, 0.0))
    sphere = bpy.context.active_object
    start = time.monotonic()
    check(subdivide(sphere, scheme="c2ps", level=2, samples=3) == {'FINISHED'}, "subdivide did not finish")
    timings["sphere"] = time.monotonic() - start
    stats, got = compare_with_cli(sphere, sphere.polarview.result, "c2ps", 2, 3, "sphere")
    poles, pole_error = check_poles(sphere, got, "c2ps", "sphere", [32, 32])
    check_measure(sphere, "c2ps", 2, "sphere")
    print(f"uv sphere c2ps 2 samples 3: {stats}; poles {[(p['vertex'], p['valence'], round(p['gaussian_curvature'], 9)) for p in poles]}")
    # RTS at the same poles: the same pole report, the scheme's own K and H.
    check(subdivide(sphere, scheme="rts", level=2, samples=2) == {'FINISHED'}, "rts did not finish")
    compare_with_cli(sphere, sphere.polarview.result, "rts", 2, 2, "sphere_rts")
    check_poles(sphere, result_arrays(sphere.polarview.result), "rts", "sphere_rts", [32, 32])

    # A Blender cylinder: n-gon caps, no poles until "N-gons to fans" makes each cap a fan.
    bpy.ops.mesh.primitive_cylinder_add(location=(0.0, -4.0, 0.0))
    cylinder = bpy.context.active_object
    check(subdivide(cylinder, scheme="c2ps", level=2, samples=2) == {'FINISHED'}, "cylinder did not finish")
    report = json.loads(cylinder.polarview.report)
    check(report["poles"] == [] and report["fan_faces"] == 2, f"cylinder as it is: {report['poles']}, {report['fan_faces']}")
    check("2 faces of 5+ sides: try N-gons to fans" in draw_panel(), "the panel does not suggest N-gons to fans")
    check(subdivide(cylinder, ngon_to_fan=True) == {'FINISHED'}, "cylinder with fans did not finish")
    report = json.loads(cylinder.polarview.report)
    check([p["valence"] for p in report["poles"]] == [32, 32], f"the fanned caps are no poles: {report['poles']}")
    path = os.path.join(args.work, "cylinder.obj")
    write_obj(cylinder, path)
    cli("convert", path, "--ngon-to-fan", "-o", os.path.join(args.work, "cylinder_fans.obj"))
    fans = bpy.data.objects.new("cylinder_fans", bpy.data.meshes.new("cylinder_fans"))
    lines = open(os.path.join(args.work, "cylinder_fans.obj")).read().split("\n")
    fans.data.from_pydata([tuple(map(float, l.split()[1:4])) for l in lines if l.startswith("v ")], [],
                          [[int(i.split("/")[0]) - 1 for i in l.split()[1:]] for l in lines if l.startswith("f ")])
    compare_with_cli(fans, cylinder.polarview.result, "c2ps", 2, 2, "cylinder_fans")
    bpy.data.objects.remove(fans)

    # Edge creases: a Blender cube with its top face's edges fully creased (c = 1: sharpness 10) and one
    # side edge half creased (c = 0.5: sharpness 2.5) is the CLI's surface of the same `t crease` tags,
    # and not the uncreased one's.
    bpy.ops.mesh.primitive_cube_add(location=(0.0, 4.0, 0.0))
    cube = bpy.context.active_object
    top = [e for e in cube.data.edges if all(cube.data.vertices[v].co.z > 0.0 for v in e.vertices)]
    side = next(e for e in cube.data.edges if cube.data.vertices[e.vertices[0]].co.z != cube.data.vertices[e.vertices[1]].co.z)
    for e in top:
        e.crease = 1.0
    side.crease = 0.5
    check(len(top) == 4, f"the cube's top has {len(top)} edges")
    check(subdivide(cube, scheme="cc", level=3, samples=3, ngon_to_fan=False) == {'FINISHED'}, "creased cube did not finish")
    panel = draw_panel()
    check(any("5 creased edges and vertices" in line for line in panel), f"the panel does not count the creases: {panel}")
    # The tessellation keeps the two sides of an infinitely sharp crease apart (each side's exact
    # normal; the CLI's PLY has the same 96 open edges), so the result is not one closed sheet, and
    # Blender's custom normals at those open-edge corners are stored to about 6e-3 rad.
    stats, _ = compare_with_cli(cube, cube.polarview.result, "cc", 3, 3, "creased_cube", closed=False, normal_angle=1e-2)
    print(f"creased cube cc 3 samples 3: {stats}")
    plain = os.path.join(args.work, "plain_cube.obj")
    with open(plain, "w") as f:
        f.writelines(l for l in open(os.path.join(args.work, "creased_cube.obj")) if not l.startswith("t "))
    cli("export", plain, "-o", os.path.join(args.work, "plain_cube.ply"), "--scheme", "cc", "--level", "3", "--samples", "3")
    smooth, creased = read_ply(os.path.join(args.work, "plain_cube.ply")), result_arrays(cube.polarview.result)
    check(len(smooth["positions"]) != len(creased["positions"]) or
          numpy.abs(smooth["positions"] - creased["positions"]).max() > 1e-2, "the creases changed nothing")

    # Settings: arguments left out come from the panel's settings; a re-run reuses the result object.
    objects = len(bpy.data.objects)
    sphere.polarview.samples = 2
    subdivide(sphere)
    check(len(bpy.data.objects) == objects, "a re-run made a new object")
    check(sphere.polarview.scheme == "rts" and len(sphere.polarview.result.data.vertices) == stats_vertices(sphere, "rts", 2, 2),
          "the panel's settings were not used")

    # Live: an edit of the control mesh is noted by the depsgraph handler and remade on flush.
    from polarview_blender import live
    sphere.polarview.live = True
    live.flush()
    before = sphere.polarview.result.data
    top = max(range(len(sphere.data.vertices)), key=lambda i: sphere.data.vertices[i].co.z)
    sphere.data.vertices[top].co.z += 0.5
    sphere.data.update()
    bpy.context.view_layer.update()
    check(sphere.name in live.pending(), "the depsgraph handler did not note the edit")
    live.flush()
    after = sphere.polarview.result.data
    check(after != before and sphere.polarview.error == "", f"live update failed: {sphere.polarview.error}")
    compare_with_cli(sphere, sphere.polarview.result, "rts", 2, 2, "sphere_live")
    bpy.context.view_layer.update()
    live.flush()
    check(sphere.polarview.result.data == after, "an unchanged control mesh was remade")
    sphere.polarview.live = False

    # Export through the module's writers.
    bpy.context.view_layer.objects.active = model
    for fmt, magic in (("glb", b"glTF"), ("step", b"ISO-10303-21"), ("iges", None)):
        path = os.path.join(args.work, f"default.{fmt}")
        check(bpy.ops.polarview.export(filepath=path, format=fmt) == {'FINISHED'}, f"export {fmt} failed")
        head = open(path, "rb").read(64)
        check(os.path.getsize(path) > 1000 and (magic is None or head.startswith(magic)), f"{path} is not a {fmt} file")

    # Bad input: refused in the UI with a clear line, nothing made.
    objects = len(bpy.data.objects)
    flat = bpy.data.meshes.new("point")
    flat.from_pydata([(0, 0, 0)] * 4, [], [(0, 1, 2, 3)])
    point = bpy.data.objects.new("point", flat)
    bpy.context.scene.collection.objects.link(point)
    bpy.context.view_layer.objects.active = point
    errors = [expect_error("point: the model spans 0")]
    far = bpy.data.objects.new("far", sphere.data.copy())
    co = numpy.empty(3 * len(far.data.vertices), numpy.float32)
    far.data.vertices.foreach_get("co", co)
    co[0] = numpy.inf  # foreach_set stores it as it is (assigning co.x would clamp to FLT_MAX)
    far.data.vertices.foreach_set("co", co)
    bpy.context.scene.collection.objects.link(far)
    bpy.context.view_layer.objects.active = far
    errors.append(expect_error("far: vertex 0 has a coordinate that is infinite"))
    empty = bpy.data.objects.new("empty", None)
    bpy.context.scene.collection.objects.link(empty)
    bpy.context.view_layer.objects.active = empty
    errors.append(expect_error("empty is not a mesh"))
    check(len(bpy.data.objects) == objects + 3, "a refused call made an object")
    for text in errors:
        print("refused:", text.strip())
    print(f"timings (s): {timings}; whole case {time.monotonic() - STARTED:.2f}")


def stats_vertices(obj, scheme, level, samples):
    path = os.path.join(args.work, "count.obj")
    write_obj(obj, path)
    cli("export", path, "-o", os.path.join(args.work, "count.ply"), "--scheme", scheme, "--level", str(level),
        "--samples", str(samples))
    return len(read_ply(os.path.join(args.work, "count.ply"))["positions"])


def case_broken():
    broken = os.path.join(args.work, "broken.zip")
    with zipfile.ZipFile(args.zip) as source, zipfile.ZipFile(broken, "w") as target:
        for item in source.infolist():
            if "/_core" not in item.filename:
                target.writestr(item, source.read(item))
    install(broken)
    module = sys.modules["polarview_blender.module"]
    check(module.pv is None and "could not be loaded" in module.LOAD_ERROR, f"LOAD_ERROR: {module.LOAD_ERROR!r}")
    check("no extension _core" in module.LOAD_ERROR, f"LOAD_ERROR does not say what is missing: {module.LOAD_ERROR}")
    bpy.ops.mesh.primitive_uv_sphere_add()
    print("refused:", expect_error("could not be loaded").strip())
    lines = draw_panel()
    check(lines[0] == "polarview could not load" and "could not be loaded" in " ".join(lines), f"the panel shows {lines}")


{"surfaces": case_surfaces, "broken": case_broken}[args.case]()
print(f"blender add-on test ({args.case}): passed in {time.monotonic() - STARTED:.2f} s")
