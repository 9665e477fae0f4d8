"""Reads an exported .ply (meshio) and .glb (the GLB chunks parsed here with struct, json, numpy:
independent of polarview's writers) back and checks them against the export's summary, against
each other and against `polarview pole --json` (tests/cli/export_tessellation.sh runs it).

usage: tessellation_readback.py PLY GLB SUMMARY EULER BOUNDARY_LOOPS [POLE_JSON]
"""
import json
import re
import struct
import sys

import meshio
import numpy as np

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def summary_counts(text):
    m = re.search(r"(\d+) vertices, (\d+) triangles, (watertight|(\d+) boundary edges), K in \[([^,]+), ([^\]]+)\]", text)
    if not m:
        sys.exit("no counts in the summary: " + text)
    return int(m.group(1)), int(m.group(2)), 0 if m.group(3) == "watertight" else int(m.group(4))


def edge_topology(faces, vertices):
    """(bad edges, boundary edges, boundary loops, Euler characteristic) of a triangle list."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    undirected = np.sort(directed, axis=1)
    edges, counts = np.unique(undirected, axis=0, return_counts=True)
    # Each edge once each way: a directed edge repeated means two triangles disagree.
    repeated = len(directed) - len(np.unique(directed, axis=0))
    bad = int(np.sum(counts > 2)) + repeated
    boundary = edges[counts == 1]
    parent = {}

    def find(a):
        while parent.setdefault(a, a) != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in boundary:
        parent[find(int(a))] = find(int(b))
    loops = len({find(v) for v in parent})
    return bad, len(boundary), loops, vertices - len(edges) + len(faces)


def read_ply(path):
    with open(path, "rb") as f:
        header = f.read(4096).split(b"end_header\n")[0].decode()
    check("format binary_little_endian 1.0" in header, "PLY is binary little-endian")
    for name in ["x", "y", "z", "nx", "ny", "nz", "quality", "gaussian_curvature", "mean_curvature"]:
        check(f"property double {name}\n" in header, f"PLY has double {name}")
    check("property list uchar int vertex_indices" in header, "PLY faces are list uchar int vertex_indices")
    mesh = meshio.read(path)
    faces = mesh.cells_dict["triangle"].astype(np.int64)
    return mesh.points, faces, mesh.point_data


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    check(magic == 0x46546C67 and version == 2 and length == len(data), "glb header: glTF, 2, its length")
    json_length, json_type = struct.unpack_from("<II", data, 12)
    check(json_type == 0x4E4F534A and json_length % 4 == 0, "JSON chunk first, 4-byte aligned")
    gltf = json.loads(data[20:20 + json_length])
    offset = 20 + json_length
    bin_length, bin_type = struct.unpack_from("<II", data, offset)
    check(bin_type == 0x004E4942 and bin_length % 4 == 0 and offset % 4 == 0, "BIN chunk, 4-byte aligned")
    binary = data[offset + 8:offset + 8 + bin_length]
    check(gltf["buffers"][0]["byteLength"] <= bin_length, "buffer fits the BIN chunk")

    def accessor(index):
        a = gltf["accessors"][index]
        view = gltf["bufferViews"][a["bufferView"]]
        dtype = {5126: "<f4", 5125: "<u4"}[a["componentType"]]
        width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        return a, np.frombuffer(binary, dtype, a["count"] * width, start).reshape(a["count"], width)

    check(gltf["asset"]["generator"] == "polarview", "asset.generator is polarview")
    check(len(gltf["meshes"]) == 1 and len(gltf["meshes"][0]["primitives"]) == 1, "one mesh, one primitive")
    primitive = gltf["meshes"][0]["primitives"][0]
    check(primitive.get("mode", 4) == 4, "TRIANGLES")
    attributes = {name: accessor(index) for name, index in primitive["attributes"].items()}
    for name in ["POSITION", "NORMAL", "COLOR_0", "_GAUSSIAN_CURVATURE", "_MEAN_CURVATURE"]:
        check(name in attributes, f"glb has {name}")
    _, indices = accessor(primitive["indices"])
    check(gltf["accessors"][primitive["indices"]]["componentType"] == 5125, "uint32 indices")
    return gltf, attributes, indices.reshape(-1, 3).astype(np.int64)


def main():
    ply_path, glb_path, summary, euler, loops = sys.argv[1:6]
    pole = json.load(open(sys.argv[6]))["poles"][0] if len(sys.argv) > 6 else None
    vertices, triangles, boundary = summary_counts(summary)

    # PLY: the summary's counts, the control mesh's topology, exact values.
    points, faces, data = read_ply(ply_path)
    check(len(points) == vertices and len(faces) == triangles, f"PLY counts {len(points)}, {len(faces)} = summary")
    for name in ["quality", "gaussian_curvature", "mean_curvature", "red", "green", "blue", "nx"]:
        check(name in data, f"PLY has {name}")
    K, H = data["gaussian_curvature"], data["mean_curvature"]
    check(np.array_equal(data["quality"], K), "quality = gaussian_curvature")
    bad, open_edges, boundary_loops, chi = edge_topology(faces, len(points))
    check(bad == 0, f"every edge of the PLY twice, once each way ({bad} not)")
    check(open_edges == boundary, f"PLY boundary edges {open_edges} = summary {boundary}")
    check(boundary_loops == int(loops), f"PLY boundary loops {boundary_loops} = {loops}")
    check(chi == int(euler), f"PLY Euler characteristic {chi} = {euler}")
    normals = np.stack([data["nx"], data["ny"], data["nz"]], axis=1)
    check(np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-12), "PLY normals unit")
    # meshio 1.x reads PLY "uchar" as int8 (its binary type table maps uchar to i1): back to bytes.
    colours = np.stack([data["red"], data["green"], data["blue"]], axis=1).astype(np.uint8)
    check(len(np.unique(colours, axis=0)) > 10, "the colours vary with K")
    low, high = (float(x) for x in re.search(r"K in \[([^,]+), ([^\]]+)\]", summary).groups())
    check(abs(K.min() - low) <= 1e-5 * abs(low) and abs(K.max() - high) <= 1e-5 * abs(high), "K range = summary")

    # glb: the same mesh in float.
    gltf, attributes, indices = read_glb(glb_path)
    position_accessor, positions = attributes["POSITION"]
    check(len(positions) == vertices and len(indices) == triangles, "glb counts = summary")
    check(np.array_equal(indices, faces), "glb triangles = PLY triangles")
    check(np.array_equal(positions, points.astype(np.float32)), "glb positions = PLY positions as floats")
    check(np.array_equal(np.float32(position_accessor["min"]), positions.min(axis=0)) and
          np.array_equal(np.float32(position_accessor["max"]), positions.max(axis=0)), "POSITION min/max = the data's")
    check(np.allclose(np.linalg.norm(attributes["NORMAL"][1], axis=1), 1.0, atol=1e-6), "glb normals unit")
    check(np.array_equal(attributes["_GAUSSIAN_CURVATURE"][1][:, 0], K.astype(np.float32)), "glb K = PLY K as floats")
    check(np.array_equal(attributes["_MEAN_CURVATURE"][1][:, 0], H.astype(np.float32)), "glb H = PLY H as floats")
    colour = attributes["COLOR_0"][1]
    check(colour.min() >= 0.0 and colour.max() <= 1.0, "COLOR_0 in [0, 1]")
    # The same colours: COLOR_0 is linear, the PLY's bytes sRGB (IEC 61966-2-1 decoding).
    srgb = colours / 255.0
    linear = np.where(srgb <= 0.04045, srgb / 12.92, ((srgb + 0.055) / 1.055) ** 2.4)
    check(np.abs(colour[:, :3] - linear).max() <= 0.5 / 255.0 * 2.4, "glb COLOR_0 = the PLY's sRGB colours, linear")
    extras = gltf["asset"]["extras"]
    check("scheme" in extras and "level" in extras, "asset.extras name scheme and level")
    bad, _, _, chi = edge_topology(indices, len(positions))
    check(bad == 0 and chi == int(euler), "glb: every edge twice, Euler characteristic")

    # The pole: one vertex at polarview's limit point, with its K and H.
    if pole:
        limit = np.array(pole["limit"])
        distance = np.linalg.norm(points - limit, axis=1)
        at = int(np.argmin(distance))
        size = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
        check(distance[at] <= 1e-12 * size, f"a vertex at the pole ({distance[at]:.3g} away)")
        check(np.sum(distance <= 1e-9 * size) == 1, "one vertex at the pole")
        check(abs(K[at] - pole["gaussian_curvature"]) <= 1e-9 * abs(pole["gaussian_curvature"]),
              f"K at the pole {K[at]!r} = pole --json {pole['gaussian_curvature']!r}")
        check(abs(H[at] - pole["mean_curvature"]) <= 1e-9 * abs(pole["mean_curvature"]),
              f"H at the pole {H[at]!r} = pole --json {pole['mean_curvature']!r}")
        check(abs(abs(np.dot(normals[at], pole["normal"])) - 1.0) <= 1e-12, "the pole's normal")
        check(attributes["_GAUSSIAN_CURVATURE"][1][at, 0] == np.float32(K[at]), "glb K at the pole")
        print(f"pole: K {K[at]!r} (pole --json {pole['gaussian_curvature']!r}), H {H[at]!r}")

    print(f"{ply_path}: {len(points)} vertices, {len(faces)} triangles, Euler {chi}, {boundary_loops} boundary loops: "
          + ("ok" if not failures else f"{len(failures)} failures"))
    sys.exit(1 if failures else 0)


main()
