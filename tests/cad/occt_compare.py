#!/usr/bin/python3
"""OpenCASCADE's reading of polarview's STEP and IGES files against polarview's own values.

Usage: occt_compare.py PREFIX LABEL [--continuity OUT.json] [--g2 KIND,...] [--not-g1 KIND,...]
                       [--t-junctions KIND,...] [--polarview CONTINUITY.json]
Reads PREFIX.step, PREFIX.igs and PREFIX.table (tests/cad/cad_reference.cpp says what the table
holds), runs occt-draw on both files and checks, for each:
  - the file reads, its face count is the table's surface count and checkshape finds nothing;
  - at every point sample OpenCASCADE's position and first and second derivatives (svalue on the
    face's surface) equal polarview's evaluation of the written B-spline to 1e-9 (position: of
    the bounding-box diagonal; derivatives: of the sample's largest derivative), and evaluatePatch's
    (bicubic patches: the same 1e-9; caps: position within the cap fit's deviation); K and H from
    OpenCASCADE's derivatives equal evaluatePatch's to 1e-6 relative (bicubic patches);
  - the area OpenCASCADE computes (sprops) equals polarview's Gauss-Legendre area to 1e-6 relative;
  - continuity across seams from OpenCASCADE's derivatives at the table's seam samples (where
    `polarview continuity --samples K` samples): per seam kind the largest position gap (of the
    diagonal), normal angle (radians) and jumps of K and H (of the model's largest |K|, |H|), the
    JSON of `polarview continuity --json` ({"seams": [{"kind", "count", ...}]}, measure_seams says
    what each means; cap-piece: between pieces of one cap sector, no seam of the limit surface).
    Given --polarview, the box diagonal and largest |K|, |H| are polarview's, and its seams must
    agree with OpenCASCADE's (compare_with_polarview: kinds, counts, smooth or not, maxima). Every seam
    is watertight (gap <= 1e-12); the --g2 kinds are present and G2 to round-off (angle <= 1e-9,
    jump <= 1e-9); the --not-g1 kinds are present and have a normal angle over 1e-3 somewhere;
    the --t-junctions kinds have T-junctions.
Prints one line per file and the continuity table; exits 1 on any failure.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

FAILURES = []


def fail(what):
    FAILURES.append(what)
    print("FAIL: " + what, file=sys.stderr)


def read_table(path):
    table = {"surfaces": [], "points": [], "seams": []}
    with open(path) as f:
        head = f.readline().split()
        table.update({head[k]: float(head[k + 1]) for k in range(0, len(head), 2) if head[k] != "surfaces"})
        for line in f:
            w = line.split()
            if w[0] == "S":
                table["surfaces"].append({"kind": w[2], "level": int(w[3]), "ring": int(w[4]),
                                          "piece": int(w[5]), "pieces": int(w[6]),
                                          "centre": [float(x) for x in w[7:10]], "patch": int(w[10])})
            elif w[0] == "P":
                v = [float(x) for x in w[2:]]
                table["points"].append({"surface": int(w[1]), "u": v[0], "v": v[1], "written": v[2:20],
                                        "limit": v[20:38], "K": v[38], "H": v[39]})
            elif w[0] == "M":
                table["seams"].append({"kind": w[1], "a": (int(w[2]), int(w[3]), float(w[4]), float(w[5])),
                                       "b": (int(w[6]), int(w[7]), float(w[8]), float(w[9]))})
    return table


def queries_of(table):
    """The (surface, u, v) OpenCASCADE is asked about, each once."""
    queries = {}
    for p in table["points"]:
        queries.setdefault((p["surface"], p["u"], p["v"]), len(queries))
    for s in table["seams"]:
        for side in (s["a"], s["b"]):
            queries.setdefault((side[0], side[2], side[3]), len(queries))
    return queries


def draw_script(path, reader, queries, faces, out):
    """A Draw script that reads `path` and prints checkshape, the face count, the area and each
    face's point at (1/2, 1/2) ("C face x y z"), or, given `faces` (the face OpenCASCADE numbers
    each written surface), svalue at every query ("Q index 18 numbers")."""
    shape = "s_1" if reader == "stepread" else "s"
    lines = ["pload MODELING DATAEXCHANGE", "set out [open {%s} w]" % out,
             "if {[catch {%s {%s} s *} err]} { puts $out \"READ-ERROR $err\"; close $out; exit }" % (reader, path),
             "puts $out \"CHECK [string map {\\n { }} [checkshape %s]]\"" % shape,
             "set faces [explode %s f]" % shape,
             "puts $out \"FACES [llength $faces]\"",
             "regexp {Mass : *([-0-9.e+]+)} [sprops %s 1e-9 -full] all area" % shape,
             "puts $out \"AREA $area\""]
    if faces is None:
        lines += ["set k 0", "foreach f $faces { mksurface S $f; svalue S 0.5 0.5 x y z; "
                  "puts $out \"C $k [dval x] [dval y] [dval z]\"; incr k }", "close $out", "exit"]
        return "\n".join(lines) + "\n"
    names = "x y z dux duy duz dvx dvy dvz d2ux d2uy d2uz d2vx d2vy d2vz d2uvx d2uvy d2uvz"
    used = sorted({q[0] for q in queries})
    for s in used:
        lines.append("mksurface S%d %s_%d" % (s, shape, faces[s] + 1))
    for (s, u, v), k in sorted(queries.items(), key=lambda item: item[1]):
        lines.append("svalue S%d %.17g %.17g %s" % (s, u, v, names))
        lines.append("puts $out \"Q %d %s\"" % (k, " ".join("[dval %s]" % n for n in names.split())))
    lines += ["close $out", "exit"]
    return "\n".join(lines) + "\n"


def run_draw(path, reader, queries, faces):
    with tempfile.TemporaryDirectory() as tmp:
        script, out = os.path.join(tmp, "read.tcl"), os.path.join(tmp, "out.txt")
        with open(script, "w") as f:
            f.write(draw_script(path, reader, queries, faces, out))
        subprocess.run(["occt-draw", "-b", "-f", script], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       timeout=300, check=False)
        result = {"values": {}, "centres": {}}
        if not os.path.exists(out):
            return {"error": "occt-draw wrote nothing"}
        with open(out) as f:
            for line in f:
                tag, _, rest = line.partition(" ")
                if tag == "Q":
                    w = rest.split()
                    result["values"][int(w[0])] = [float(x) for x in w[1:]]
                elif tag == "C":
                    w = rest.split()
                    result["centres"][int(w[0])] = [float(x) for x in w[1:]]
                elif tag == "READ-ERROR":
                    result["error"] = rest.strip()
                else:
                    result[tag] = rest.strip()
        return result


def vec(values, k):
    return values[3 * k:3 * k + 3]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(a):
    return math.sqrt(dot(a, a))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def geometry(values):
    """Normal, K and H from position, du, dv, duu, dvv, duv in svalue's order (x, du, dv, d2u, d2v, d2uv)."""
    du, dv, duu, dvv, duv = (vec(values, k) for k in (1, 2, 3, 4, 5))
    n = cross(du, dv)
    n = [x / norm(n) for x in n]
    E, F, G = dot(du, du), dot(du, dv), dot(dv, dv)
    L, M, N = dot(duu, n), dot(duv, n), dot(dvv, n)
    det = E * G - F * F
    return n, (L * N - M * M) / det, (E * N - 2 * F * M + G * L) / (2 * det)


def to_svalue_order(d):
    """The table's position, du, dv, duu, duv, dvv in svalue's order: position, du, dv, duu, dvv, duv."""
    return d[0:9] + d[9:12] + d[15:18] + d[12:15]


def check_points(table, result, label, caps_exact):
    diag = table["box"]
    worst = {"position": 0.0, "derivative": 0.0, "K": 0.0, "H": 0.0, "cap_position": 0.0}
    queries = result["queries"]
    for p in table["points"]:
        occt = result["values"].get(queries[(p["surface"], p["u"], p["v"])])
        if occt is None:
            fail("%s: no OpenCASCADE value for surface %d" % (label, p["surface"]))
            return worst
        written, limit = to_svalue_order(p["written"]), to_svalue_order(p["limit"])
        is_cap = table["surfaces"][p["surface"]]["kind"] == "pole-cap"
        first = max(norm(vec(written, 1)), norm(vec(written, 2)))
        second = max([first] + [norm(vec(written, k)) for k in (3, 4, 5)])
        references = [written] if is_cap else [written, limit]
        for ref in references:
            worst["position"] = max(worst["position"], norm(sub(vec(occt, 0), vec(ref, 0))) / diag)
            for k in (1, 2, 3, 4, 5):
                scale = first if k < 3 else second
                worst["derivative"] = max(worst["derivative"], norm(sub(vec(occt, k), vec(ref, k))) / scale)
        if is_cap:
            worst["cap_position"] = max(worst["cap_position"], norm(sub(vec(occt, 0), vec(limit, 0))) / diag)
            continue
        _, K, H = geometry(occt)
        kappa = abs(p["H"]) + math.sqrt(max(p["H"] ** 2 - p["K"], 0.0))  # largest principal curvature
        worst["K"] = max(worst["K"], abs(K - p["K"]) / max(abs(p["K"]), kappa * kappa, 1e-300))
        worst["H"] = max(worst["H"], abs(H - p["H"]) / max(abs(p["H"]), kappa, 1e-300))
    limits = {"position": 1e-9, "derivative": 1e-9, "K": 1e-6, "H": 1e-6,
              "cap_position": max(table["cap_deviation"] / diag, 1e-12) * 1.01 + 1e-12}
    for key, value in worst.items():
        if value > limits[key]:
            fail("%s: %s differs by %.3g (limit %.3g)" % (label, key, value, limits[key]))
    return worst


def patch_side(table, surface, side):
    """The patch side a written surface's side lies on, as `polarview continuity` names it: a cap
    sector's pieces share their patch's u = 1 side, the first piece its v = 0, the last its v = 1
    (sides between pieces stay their own: they are no seam of the limit surface)."""
    s = table["surfaces"][surface]
    outer = side == 1 or (side == 0 and s["piece"] == 0) or (side == 2 and s["piece"] == s["pieces"] - 1)
    return (s["patch"], side) if outer else ("piece", surface, side)


def seam_pairs(table, result):
    """The samples of each seam: per (kind, pair of patch sides), OpenCASCADE's values on both."""
    queries, values = result["queries"], result["values"]
    pairs = {}
    for s in table["seams"]:
        a, b = s["a"], s["b"]
        key = tuple(sorted([patch_side(table, a[0], a[1]), patch_side(table, b[0], b[1])], key=repr))
        va, vb = values[queries[(a[0], a[2], a[3])]], values[queries[(b[0], b[2], b[3])]]
        pairs.setdefault((s["kind"], key), []).append((va, vb))
    return pairs


def measure_seams(table, result, scales):
    """Per seam kind, as `polarview continuity --json` reports it: seams (pairs of patch sides that
    meet), T-junctions (of them, those one of whose sides meets more than one side), the largest gap
    (of scales' box diagonal), normal angle (radians) and jumps of K and H (of scales' largest |K|,
    |H|), from OpenCASCADE's values."""
    pairs = seam_pairs(table, result)
    partners = {}
    for _, (a, b) in pairs:
        partners.setdefault(a, set()).add(b)
        partners.setdefault(b, set()).add(a)
    stats = {}
    for (kind, (a, b)), samples in pairs.items():
        st = stats.setdefault(kind, {"kind": kind, "count": 0, "t_junctions": 0, "samples": 0, "max_position_gap": 0.0,
                                     "max_normal_angle": 0.0, "max_curvature_jump": 0.0, "max_gaussian_jump": 0.0,
                                     "max_mean_jump": 0.0})
        st["count"] += 1
        st["t_junctions"] += len(partners[a]) > 1 or len(partners[b]) > 1
        geo = [(geometry(va), geometry(vb)) for va, vb in samples]
        sign = 1.0 if sum(dot(ga[0], gb[0]) for ga, gb in geo) >= 0 else -1.0  # orient the pair's normals
        for (va, vb), (ga, gb) in zip(samples, geo):
            st["samples"] += 1
            st["max_position_gap"] = max(st["max_position_gap"], norm(sub(vec(va, 0), vec(vb, 0))) / scales["box"])
            nb = [sign * x for x in gb[0]]
            st["max_normal_angle"] = max(st["max_normal_angle"], math.atan2(norm(cross(ga[0], nb)), dot(ga[0], nb)))
            st["max_gaussian_jump"] = max(st["max_gaussian_jump"], abs(ga[1] - gb[1]) / scales["K"])
            st["max_mean_jump"] = max(st["max_mean_jump"], abs(ga[2] - sign * gb[2]) / scales["H"])
        st["max_curvature_jump"] = max(st["max_gaussian_jump"], st["max_mean_jump"])
    order = ["regular", "ring-ring", "ring-cap", "cap-cap", "end-cap", "regular-ring", "regular-cap", "cap-piece"]
    return sorted(stats.values(), key=lambda st: order.index(st["kind"]) if st["kind"] in order else 99)


# Agreement with `polarview continuity --json`: a value is smooth at or below SMOOTH; above it both
# maxima agree to AGREE relative. Seams touching a cap (ring-cap, cap-cap) compare OpenCASCADE's fitted
# pieces with polarview's exact cap, and get cap_slack more on both: the fit moves positions by the
# table's cap deviation d (of the diagonal) and a degree-n polynomial's derivative moves by up to
# 2 n^2 times its value's change (Markov), so normals and curvatures move by up to about 1e4 d
# (measured: 1e2..1e3 d, e.g. cap-cap angles 6e-9 at d = 1.3e-11, ring-cap jumps 6e-6 relative at
# d = 7e-8); and near the pole (u = 1/2K) K and H divide second derivatives of the degree-(4, d)
# pieces by |du x dv|^2 ~ u^2, which leaves ~1e-9 of round-off (cap-cap jumps of a valence-64 cap
# whose fit is exact to 1e-16), hence the 1e-8 floor.
SMOOTH = 1e-9
AGREE = 1e-6
METRICS = ["max_position_gap", "max_normal_angle", "max_gaussian_jump", "max_mean_jump"]


def cap_slack(table):
    """The allowance of seams touching a cap, in the units of the normalised values (above)."""
    return 1e4 * table["cap_deviation"] / table["box"] + 1e-8


def compare_with_polarview(seams, polarview, table, label):
    """Fails where OpenCASCADE's seam measurement and polarview's disagree; prints both side by side."""
    occt = {st["kind"]: st for st in seams if st["kind"] != "cap-piece"}
    ours = {st["kind"]: st for st in polarview["seams"]}
    if set(occt) != set(ours):
        fail("%s: seam kinds: OpenCASCADE %s, polarview %s" % (label, sorted(occt), sorted(ours)))
    slack_of_caps = cap_slack(table)
    print("  %-16s %-12s %-11s %9s %9s  %-19s %-19s %-19s %-19s" % (
        label, "kind", "side", "seams", "T-jn", "gap", "angle (rad)", "dK", "dH"))
    for kind in [st["kind"] for st in polarview["seams"] if st["kind"] in occt]:
        o, p = occt[kind], ours[kind]
        for name, st in (("OCCT", o), ("polarview", p)):
            print("  %-16s %-12s %-11s %9d %9d  %s" % (label, kind, name, st["count"], st["t_junctions"],
                                                       " ".join("%-19.12g" % st[m] for m in METRICS)))
        for key in ("count", "t_junctions"):
            if o[key] != p[key]:
                fail("%s: %s %s: OpenCASCADE %d, polarview %d" % (label, kind, key, o[key], p[key]))
        slack = slack_of_caps if kind in ("ring-cap", "cap-cap", "regular-cap") else 0.0
        for m in METRICS:
            smooth_o, smooth_p = o[m] <= SMOOTH + slack, p[m] <= SMOOTH + slack
            if smooth_o != smooth_p:
                fail("%s: %s %s: OpenCASCADE %.3g, polarview %.3g (smooth at %.3g)" % (label, kind, m, o[m], p[m],
                                                                                        SMOOTH + slack))
            elif not smooth_o and abs(o[m] - p[m]) > AGREE * max(o[m], p[m]) + slack:
                fail("%s: %s %s: OpenCASCADE %.12g, polarview %.12g (%.3g relative, allowed %.3g + %.3g)" % (
                    label, kind, m, o[m], p[m], abs(o[m] - p[m]) / max(o[m], p[m]), AGREE, slack))


def match_faces(table, centres, label):
    """The face OpenCASCADE numbers each written surface: the one with the same point at (1/2, 1/2)
    (within 1e-9 of the diagonal, one to one); None where they do not match."""
    from scipy.spatial import cKDTree
    if len(centres) != len(table["surfaces"]):
        return None
    order = sorted(centres)
    tree = cKDTree([centres[k] for k in order])
    distance, nearest = tree.query([s["centre"] for s in table["surfaces"]])
    faces = [order[k] for k in nearest]
    worst = max(distance) / table["box"] if len(distance) else 0.0
    if worst > 1e-9 or len(set(faces)) != len(faces):
        fail("%s: the faces read do not match the surfaces written (%.3g of the diagonal apart)" % (label, worst))
        return None
    return faces


def check_file(table, path, reader, label, queries):
    result = run_draw(path, reader, queries, None)
    if "error" in result:
        fail("%s: OpenCASCADE could not read it: %s" % (label, result["error"]))
        return None
    if "This shape seems to be valid" not in result.get("CHECK", ""):
        fail("%s: checkshape: %s" % (label, result.get("CHECK", "")[:300]))
    faces = int(result.get("FACES", -1))
    if faces != len(table["surfaces"]):
        fail("%s: %d faces read, %d surfaces written" % (label, faces, len(table["surfaces"])))
        return None
    faces_of = match_faces(table, result["centres"], label)
    if faces_of is None:
        return None
    in_order = faces_of == list(range(len(faces_of)))
    values = run_draw(path, reader, queries, faces_of)
    result["values"], result["queries"] = values["values"], queries
    area = float(result["AREA"])
    area_error = abs(area - table["area"]) / table["area"]
    if area_error > 1e-6:
        fail("%s: OpenCASCADE's area %.12g, polarview's %.12g (%.3g relative)" % (label, area, table["area"], area_error))
    worst = check_points(table, result, label, True)
    print("%s: %d faces (%s), checkshape clean, area %.10g (%.1e relative), point %.1e, derivative %.1e, K %.1e, H %.1e, "
          "cap fit %.1e of the diagonal" % (label, faces, "in order" if in_order else "matched by position", area, area_error, worst["position"], worst["derivative"],
                                            worst["K"], worst["H"], worst["cap_position"]))
    return result


def check_seams(seams, args, label):
    by_kind = {st["kind"]: st for st in seams}
    for st in seams:
        if st["max_position_gap"] > 1e-12:
            fail("%s: %s seams are %.3g of the diagonal apart" % (label, st["kind"], st["max_position_gap"]))
    for kind in filter(None, args.g2.split(",")):
        st = by_kind.get(kind)
        if st is None:
            fail("%s: no %s seam found" % (label, kind))
        elif st["max_normal_angle"] > 1e-9 or st["max_curvature_jump"] > 1e-9:
            fail("%s: %s seams are not G2: angle %.3g, curvature jump %.3g" % (
                label, kind, st["max_normal_angle"], st["max_curvature_jump"]))
    for kind in filter(None, args.not_g1.split(",")):
        st = by_kind.get(kind)
        if st is None or st["max_normal_angle"] < 1e-3:
            fail("%s: %s seams should have a visible normal jump, measured %s" % (
                label, kind, "none" if st is None else "%.3g" % st["max_normal_angle"]))
    for kind in filter(None, args.t_junctions.split(",")):
        if by_kind.get(kind, {}).get("t_junctions", 0) == 0:
            fail("%s: no %s seam between surfaces of different levels" % (label, kind))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("prefix")
    parser.add_argument("label")
    parser.add_argument("--continuity")
    parser.add_argument("--g2", default="")
    parser.add_argument("--not-g1", default="")
    parser.add_argument("--t-junctions", default="")
    parser.add_argument("--polarview", help="`polarview continuity --samples K --json` of the same model to agree with")
    args = parser.parse_args()
    table = read_table(args.prefix + ".table")
    queries = queries_of(table)
    step = check_file(table, args.prefix + ".step", "stepread", args.label + " STEP", queries)
    check_file(table, args.prefix + ".igs", "igesread", args.label + " IGES", queries)
    polarview = None
    scales = {"box": table["box"], "K": table["max_abs_K"], "H": table["max_abs_H"]}
    if args.polarview:
        with open(args.polarview) as f:
            polarview = json.load(f)
        if polarview["samples"] != table["samples"]:
            fail("%s: polarview sampled %d points a side, the table %d" % (args.label, polarview["samples"],
                                                                          table["samples"]))
        scales = {"box": polarview["box_diagonal"], "K": polarview["max_abs_gaussian"], "H": polarview["max_abs_mean"]}
    if step is not None:
        seams = measure_seams(table, step, scales)
        for st in seams if polarview is None else []:
            print("  %-18s %-12s %4d pairs (%4d T)  gap %.1e  angle %.1e  K/H jump %.1e" % (
                args.label, st["kind"], st["count"], st["t_junctions"], st["max_position_gap"],
                st["max_normal_angle"], st["max_curvature_jump"]))
        check_seams(seams, args, args.label)
        if polarview is not None:
            compare_with_polarview(seams, polarview, table, args.label)
        if args.continuity:
            with open(args.continuity, "w") as f:
                json.dump({"seams": seams}, f, indent=1)
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
