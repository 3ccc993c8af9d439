#!/usr/bin/python3
"""Reads fetic's ParaView output back with VTK's own XML reader (Debian's python3-vtk9, the
reader ParaView uses) and compares every value with the result file (JSON) to 1e-12:
a bar scene in all three encodings, a plane scene, a load sweep and an iteration series.

usage: vtu_readback_test.py FETIC SCENES_DIR WORK_DIR
Exit 77 (skipped) when VTK's Python module is missing."""

import base64
import json
import os
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

try:
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError:
    print("skipped: VTK's Python module is missing (apt-get install python3-vtk9)")
    # CI (FETIC_REQUIRE_ALL=1) has it: there a skip is a failure.
    sys.exit(1 if os.environ.get("FETIC_REQUIRE_ALL") == "1" else 77)

FETIC, SCENES, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
TOLERANCE = 1e-12
checked = {"values": 0}


def fail(message):
    print("FAILED:", message)
    sys.exit(1)


def close(a, b, what):
    checked["values"] += 1
    if abs(a - b) > TOLERANCE * max(1.0, abs(b)):
        fail(f"{what}: vtu {a!r} != json {b!r}")


def solve(scene, out, *options):
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    command = [FETIC, "solve", os.path.join(SCENES, scene), "--json", os.path.join(out, "r.json"),
               "--vtu", out, "--quiet", *options]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        fail(f"{' '.join(command)} exited {done.returncode}: {done.stdout}{done.stderr}")
    with open(os.path.join(out, "r.json")) as f:
        return json.load(f)


def read(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        fail(f"{path}: VTK could not read it")
    return reader.GetOutput()


def array(data, name):
    a = data.GetArray(name)
    if a is None:
        fail(f"no array {name}")
    return a


def pvd_entries(path):
    root = ET.parse(path).getroot()
    if root.get("type") != "Collection":
        fail(f"{path} is not a collection")
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def compare_struts(grid, state, model):
    struts = state["struts"]
    points = sum(len(s["nodes"]) for s in struts)
    cells = sum(len(s["elements"]) for s in struts)
    if grid.GetNumberOfPoints() != points or grid.GetNumberOfCells() != cells:
        fail(f"{grid.GetNumberOfPoints()} points, {grid.GetNumberOfCells()} cells; "
             f"json {points}, {cells}")
    u = array(grid.GetPointData(), "displacement")
    if u.GetNumberOfComponents() != 3:
        fail("displacement must have 3 components")
    cd = grid.GetCellData()
    stress_names = ["axial"] + (["sxx", "syy", "sxy", "von_mises"] if model == "plane" else [])
    p = c = 0
    for s, strut in enumerate(struts):
        first = p
        for node, moved in zip(strut["nodes"], strut["displacements"]):
            x = grid.GetPoint(p)
            close(x[0], node[0], "x")
            close(x[1], node[1], "y")
            close(x[2], 0.0, "z")
            d = u.GetTuple3(p)
            close(d[0], moved[0], f"strut {s} ux")
            close(d[1], moved[1], f"strut {s} uy")
            close(d[2], 0.0, "uz")
            p += 1
        for k, element in enumerate(strut["elements"]):
            ids = grid.GetCell(c).GetPointIds()
            if [ids.GetId(i) - first for i in range(ids.GetNumberOfIds())] != element:
                fail(f"strut {s} element {k}: connectivity differs")
            expected_type = 9 if model == "plane" else 3
            if grid.GetCellType(c) != expected_type:
                fail(f"cell {c} has type {grid.GetCellType(c)}")
            close(array(cd, "strut").GetValue(c), s, "strut")
            close(array(cd, "element").GetValue(c), k, "element")
            close(array(cd, "subdomain").GetValue(c), strut["element_subdomains"][k], "subdomain")
            for name in stress_names:
                close(array(cd, "stress_" + name).GetValue(c), strut["stress"][name][k],
                      f"strut {s} element {k} stress {name}")
            close(array(cd, "axial_force").GetValue(c), strut["axial_force"][k], "axial force")
            c += 1
    fd = grid.GetFieldData()
    close(fd.GetArray("load_factor").GetValue(0), state["load_factor"], "load factor")
    close(fd.GetArray("iteration").GetValue(0), state["iterations"], "iteration")


def compare_contacts(grid, state):
    pairs = [pair for contact in state["contacts"] for pair in contact["pairs"]]
    if grid.GetNumberOfCells() != len(pairs) or grid.GetNumberOfPoints() != 2 * len(pairs):
        fail(f"contacts: {grid.GetNumberOfCells()} lines for {len(pairs)} pairs")
    cd = grid.GetCellData()
    u = array(grid.GetPointData(), "displacement")
    by_name = {strut["name"]: strut for strut in state["struts"]}
    k = 0
    for c, contact in enumerate(state["contacts"]):
        strut_a = by_name[contact["a"].rsplit(".", 1)[0]]
        strut_b = by_name[contact["b"].rsplit(".", 1)[0]]
        for j, pair in enumerate(contact["pairs"]):
            close(array(cd, "contact").GetValue(k), c, "contact")
            close(array(cd, "pair").GetValue(k), j, "pair")
            close(array(cd, "gap").GetValue(k), pair["gap"], "gap")
            close(array(cd, "force").GetValue(k), pair["force"], f"contact {c} pair {j} force")
            close(array(cd, "active").GetValue(k), 1 if pair["active"] else 0, "active")
            n = array(cd, "normal").GetTuple3(k)
            close(n[0], pair["normal"][0], "normal x")
            close(n[1], pair["normal"][1], "normal y")
            ends = ((pair["point_a"], strut_a["displacements"][pair["node_a"]]),
                    (pair["point_b"], strut_b["displacements"][pair["node_b"]]))
            for end, (point, moved) in enumerate(ends):
                x = grid.GetPoint(2 * k + end)
                close(x[0], point[0], "pair point x")
                close(x[1], point[1], "pair point y")
                d = u.GetTuple3(2 * k + end)
                close(d[0], moved[0], "pair node ux")
                close(d[1], moved[1], "pair node uy")
            ids = grid.GetCell(k).GetPointIds()
            if (ids.GetId(0), ids.GetId(1)) != (2 * k, 2 * k + 1):
                fail("contact line connectivity")
            k += 1


def compare_frame_struts(grid, state, scene_file):
    """Frame model: the struts share one point per joint; rotations as point data (the
    first end's at a joint) and per element at both ends; bending moments at both ends of
    every element, whose mean is the result file's moment at the middle."""
    import tomllib
    with open(os.path.join(SCENES, scene_file), "rb") as f:
        scene = tomllib.load(f)
    struts = state["struts"]
    index = {s["name"]: i for i, s in enumerate(struts)}
    nodes_of = [len(s["nodes"]) for s in struts]
    # Joints from the scene file: every end after the first shares the first one's point.
    parent = list(range(len(struts)))

    def root(i):
        while parent[i] != i:
            i = parent[i]
        return i
    shared = 0
    for joint in scene.get("joint", []):
        ends = joint["ends"]
        shared += len(ends) - 1
        first = index[ends[0].rsplit(".", 1)[0]]
        for end in ends[1:]:
            parent[root(index[end.rsplit(".", 1)[0]])] = root(first)
    if grid.GetNumberOfPoints() != sum(nodes_of) - shared:
        fail(f"frame: {grid.GetNumberOfPoints()} points, expected {sum(nodes_of) - shared}")
    u = array(grid.GetPointData(), "displacement")
    rotation = array(grid.GetPointData(), "rotation")
    cd = grid.GetCellData()
    end_rotations = array(cd, "end_rotations")
    moment_ends = array(cd, "bending_moment_ends")
    largest_moment = max(max(abs(m) for m in s["bending_moment"]) for s in struts) or 1.0
    first_seen = set()
    point_parent = list(range(grid.GetNumberOfPoints()))

    def point_root(i):
        while point_parent[i] != i:
            i = point_parent[i]
        return i
    c = 0
    for s, strut in enumerate(struts):
        for k, element in enumerate(strut["elements"]):
            ids = grid.GetCell(c).GetPointIds()
            points = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
            for point, node in zip(points, element):
                x = grid.GetPoint(point)
                close(x[0], strut["nodes"][node][0], "frame x")
                close(x[1], strut["nodes"][node][1], "frame y")
                d = u.GetTuple3(point)
                close(d[0], strut["displacements"][node][0], f"frame strut {s} node {node} ux")
                close(d[1], strut["displacements"][node][1], f"frame strut {s} node {node} uy")
                if point not in first_seen:  # the end that made the point: its rotation
                    first_seen.add(point)
                    close(rotation.GetValue(point), strut["rotations"][node], "frame rotation")
            point_parent[point_root(points[1])] = point_root(points[0])
            r = end_rotations.GetTuple2(c)
            close(r[0], strut["rotations"][element[0]], f"strut {s} element {k} rotation at start")
            close(r[1], strut["rotations"][element[1]], f"strut {s} element {k} rotation at end")
            m = moment_ends.GetTuple2(c)
            checked["values"] += 1
            if abs((m[0] + m[1]) / 2 - strut["bending_moment"][k]) > 1e-9 * largest_moment:
                fail(f"strut {s} element {k}: mean of the end moments {m} is not the "
                     f"middle's {strut['bending_moment'][k]}")
            close(array(cd, "bending_moment").GetValue(c), strut["bending_moment"][k], "moment")
            c += 1
    # ParaView sees one piece per group of struts that joints join.
    pieces = len({point_root(p) for p in range(grid.GetNumberOfPoints())})
    groups = len({root(i) for i in range(len(struts))})
    if pieces != groups:
        fail(f"frame: {pieces} connected pieces, {groups} groups of joined struts")
    units = grid.GetFieldData().GetAbstractArray("length_unit")
    if units is None or units.GetValue(0) != state["units"]["length"]:
        fail("frame: field data length_unit")


def check_frame(out, index, state, model):
    compare_struts(read(os.path.join(out, f"struts_{index:04d}.vtu")), state, model)
    compare_contacts(read(os.path.join(out, f"contacts_{index:04d}.vtu")), state)


def block_kinds(path):
    """Per array of a zlib-encoded .vtu, the kinds of its zlib blocks: "stored" (deflate's
    block type 00, what level 0 writes) or "deflated"."""
    kinds = {}
    for item in ET.parse(path).getroot().find("UnstructuredGrid/Piece").iter("DataArray"):
        if item.get("format") != "binary":
            continue
        text = item.text.strip()
        blocks = struct.unpack("<Q", base64.b64decode(text[:12])[:8])[0]
        header_bytes = 8 * (3 + blocks)
        header_text = (header_bytes + 2) // 3 * 4
        sizes = struct.unpack(f"<{3 + blocks}Q", base64.b64decode(text[:header_text])[:header_bytes])
        data = base64.b64decode(text[header_text:])
        starts = [sum(sizes[3:3 + k]) for k in range(blocks)]
        # Each block is a zlib stream: 2 header bytes, then the first deflate block's header.
        kinds[item.get("Name")] = {"stored" if data[s + 2] & 0x06 == 0 else "deflated" for s in starts}
    return kinds


def main():
    # A bar scene with 100 struts and 50 contacts, in every encoding.
    for encoding in ("ascii", "binary", "zlib"):
        out = os.path.join(WORK, "thesis_" + encoding)
        result = solve("thesis.toml", out, "--vtu-format", encoding)
        root = ET.parse(os.path.join(out, "struts_0000.vtu")).getroot()
        formats = {a.get("format") for a in root.find("UnstructuredGrid/Piece").iter("DataArray")}
        if formats != {"ascii" if encoding == "ascii" else "binary"} or \
                (root.get("compressor") == "vtkZLibDataCompressor") != (encoding == "zlib"):
            fail(f"{encoding}: the file does not use that encoding ({formats})")
        check_frame(out, 0, result, "bar")
        if pvd_entries(os.path.join(out, "struts.pvd")) != [(1.0, "struts_0000.vtu")]:
            fail("thesis: struts.pvd")
    # A plane scene: quadrilaterals, plane stresses, several pairs per contact. Its
    # stresses hardly compress and are stored (zlib level 0), the rest deflated: VTK reads
    # both kinds of block.
    out = os.path.join(WORK, "plane")
    result = solve("plane_pair.toml", out)
    check_frame(out, 0, result, "plane")
    kinds = block_kinds(os.path.join(out, "struts_0000.vtu"))
    if kinds.get("stress_sxx") != {"stored"} or kinds.get("connectivity") != {"deflated"}:
        fail(f"plane: the stresses are not stored or the cells not deflated ({kinds})")
    # A load sweep: a frame per step, ParaView's time is the load factor.
    out = os.path.join(WORK, "sweep")
    result = solve("two_bars.toml", out, "--load-steps", "0:2:5", "--vtu-format", "binary")
    entries = pvd_entries(os.path.join(out, "struts.pvd"))
    if [t for t, _ in entries] != [s["load_factor"] for s in result["steps"]]:
        fail(f"sweep: pvd times {entries}")
    if pvd_entries(os.path.join(out, "contacts.pvd"))[-1][1] != "contacts_0004.vtu":
        fail("sweep: contacts.pvd")
    for k, step in enumerate(result["steps"]):
        check_frame(out, k, step, "bar")
    # An iteration series: a frame per iteration, the last one is the result.
    out = os.path.join(WORK, "iterations")
    result = solve("plane_pair.toml", out, "--vtu-every-iteration", "--method", "feti-c")
    entries = pvd_entries(os.path.join(out, "struts.pvd"))
    if len(entries) != result["iterations"] + 1 or [t for t, _ in entries] != list(
            map(float, range(len(entries)))):
        fail(f"iterations: {len(entries)} frames for {result['iterations']} iterations")
    check_frame(out, len(entries) - 1, result, "plane")
    first = read(os.path.join(out, "struts_0000.vtu"))
    if first.GetFieldData().GetArray("iteration").GetValue(0) != 0:
        fail("iterations: frame 0 is not iteration 0")
    # Frames: a truss of pinned joints (ends with their own rotations) and a scaffold of
    # rigid ones; the primal method (joints exact) so that shared points compare exactly.
    for scene in ("frame_truss_bridge.toml", "frame_scaffold.toml"):
        out = os.path.join(WORK, scene)
        result = solve(scene, out, "--method", "active-set")
        compare_frame_struts(read(os.path.join(out, "struts_0000.vtu")), result, scene)
        compare_contacts(read(os.path.join(out, "contacts_0000.vtu")), result)
        version = read(os.path.join(out, "struts_0000.vtu")).GetFieldData().GetAbstractArray(
            "fetic_version")
        if version is None or version.GetValue(0) != result["fetic_version"]:
            fail("frame: field data fetic_version")
    from vtkmodules.vtkCommonCore import vtkVersion
    print(f"VTK {vtkVersion.GetVTKVersion()} read back fetic's .vtu files: {checked['values']}"
          f" values equal to the result file within {TOLERANCE} (relative)")

main()
