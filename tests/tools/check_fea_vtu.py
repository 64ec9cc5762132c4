"""FEA results exported as .vtu, read back by an independent reader
(vtu_reader.py, Python's standard library only) and checked against
references that do not come from the writer:

  - every file passes the reader's structural checks (VTK XML file format);
  - the binary file (the default) and the ASCII one of each result hold the
    same arrays with the same values (doubles to 1e-15 relative: both
    formats are exact, the tolerance only forgives a last-digit parse);
  - point and cell counts are those of the mesh definition: (refine + 1)^3
    nodes and refine^3 elements per free block, and per support block its
    vertices and one cell (VTK_HEXAHEDRON for a box, VTK_POLYHEDRON for the
    pentagonal slab);
  - support cells are marked `support` = 1 (and only they), their points do
    not move and carry no contact force;
  - every hexahedron is in VTK's corner order (positive volume);
  - nodal_stress is the mean of the stresses of the cells around each point
    within its block, recomputed here from the cells, and nodal_von_mises
    its von Mises stress;
  - the column under its own weight (Poisson's ratio 0, fixed base: the 1D
    bar, whose element strains are exact at element centres, see
    tests/regression/column_fea.lua): sigma_zz = -rho g (L - z) at every
    element centre and at every node strictly inside the column (the mean
    of the elements just above and below is exact for a linear field), to
    1e-6 of rho g L; the other components are 0 to the same tolerance;
  - the reader refuses broken files: a wrong point count, an offset past the
    data, a header that lies about a block's size, a truncated file.

    python3 check_fea_vtu.py <ashlar> <folder>
"""

import json
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtu_reader import VtuError, read_vtu  # noqa: E402

G = 9.81
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def same_arrays(name, binary, ascii):
    for section in ("point_data", "cell_data"):
        b, a = getattr(binary, section), getattr(ascii, section)
        check(sorted(b) == sorted(a), f"{name}: {section} arrays differ: {sorted(b)} vs {sorted(a)}")
        for key in b:
            if key not in a:
                continue
            check(b[key].type == a[key].type and b[key].components == a[key].components,
                  f"{name}: {section} {key}: type or components differ")
            bad = [i for i, (x, y) in enumerate(zip(b[key].values, a[key].values)) if not close(x, y, 1e-15)]
            check(not bad, f"{name}: {section} {key}: {len(bad)} values differ, first at {bad[:1]}")
    for field in ("connectivity", "offsets", "types", "faces", "faceoffsets"):
        check(getattr(binary, field) == getattr(ascii, field), f"{name}: {field} differ")
    bad = [i for i, (x, y) in enumerate(zip(binary.coordinates.values, ascii.coordinates.values))
           if not close(x, y, 1e-15)]
    check(not bad, f"{name}: point coordinates differ at {bad[:1]}")


def volume_sign(p):
    """(p1 - p0) x (p3 - p0) . (p4 - p0) of a hexahedron's corners."""
    a = [p[1][k] - p[0][k] for k in range(3)]
    b = [p[3][k] - p[0][k] for k in range(3)]
    c = [p[4][k] - p[0][k] for k in range(3)]
    return (a[1] * b[2] - a[2] * b[1]) * c[0] + (a[2] * b[0] - a[0] * b[2]) * c[1] + (a[0] * b[1] - a[1] * b[0]) * c[2]


def von_mises(s):  # VTK order xx yy zz xy yz xz
    xx, yy, zz, xy, yz, xz = s
    return math.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * (xy ** 2 + yz ** 2 + xz ** 2))


def check_grid(name, grid, case):
    refine, blocks = case["refine"], case["blocks"]
    free = [b for b in blocks if not b["support"]]
    supports = [b for b in blocks if b["support"]]
    element_count = len(free) * refine ** 3
    points = len(free) * (refine + 1) ** 3 + sum(b["vertices"] for b in supports)
    check(grid.points == points, f"{name}: {grid.points} points, the mesh definition gives {points}")
    check(grid.cells == element_count + len(supports),
          f"{name}: {grid.cells} cells, the mesh definition gives {element_count + len(supports)}")
    coordinates = [grid.coordinates.tuple(i) for i in range(grid.points)]

    support = grid.cell_data["support"].values
    check(support == [0] * element_count + [1] * len(supports), f"{name}: support marks the wrong cells")
    support_points = set()
    for c in range(grid.cells):
        ids = grid.cell_points(c)
        if support[c]:
            support_points.update(ids)
            expected = 12 if blocks[grid.cell_data["block"].values[c] - 1]["vertices"] == 8 else 42
            check(grid.types[c] == expected, f"{name}: support cell {c} has type {grid.types[c]}, expected {expected}")
        else:
            check(grid.types[c] == 12, f"{name}: element cell {c} has type {grid.types[c]}")
        if grid.types[c] == 12:
            check(volume_sign([coordinates[p] for p in ids]) > 0, f"{name}: hexahedron {c} is inside out")
    check(len(support_points) == sum(b["vertices"] for b in supports),
          f"{name}: support cells use {len(support_points)} points")
    for p in support_points:
        check(grid.point_data["displacement"].tuple(p) == [0.0, 0.0, 0.0], f"{name}: support point {p} moves")
        check(grid.point_data["contact_force"].tuple(p) == [0.0, 0.0, 0.0], f"{name}: support point {p} has a force")
        check(blocks[grid.point_data["block"].values[p] - 1]["support"], f"{name}: point {p} of a support cell is in a free block")

    if not case["stresses"]:
        for key in ("stress", "von_mises"):
            check(key not in grid.cell_data, f"{name}: {key} without stresses")
        for key in ("nodal_stress", "nodal_von_mises"):
            check(key not in grid.point_data, f"{name}: {key} without stresses")
        return
    stress = grid.cell_data["stress"]
    check(stress.components == 6, f"{name}: stress has {stress.components} components")
    check(all(v == 0 for c in range(element_count, grid.cells) for v in stress.tuple(c)),
          f"{name}: support cells carry stress")
    # Nodal means recomputed from the cells, within each block.
    sums = [[0.0] * 6 for _ in range(grid.points)]
    counts = [0] * grid.points
    for c in range(element_count):
        block = grid.cell_data["block"].values[c]
        for p in grid.cell_points(c):
            check(grid.point_data["block"].values[p] == block, f"{name}: cell {c} uses a point of another block")
            counts[p] += 1
            sums[p] = [s + v for s, v in zip(sums[p], stress.tuple(c))]
    nodal = grid.point_data["nodal_stress"]
    mises = grid.point_data["nodal_von_mises"]
    scale = max(abs(v) for v in stress.values)
    for p in range(grid.points):
        mean = [s / counts[p] for s in sums[p]] if counts[p] else [0.0] * 6
        check(all(abs(a - b) <= 1e-12 * scale for a, b in zip(nodal.tuple(p), mean)),
              f"{name}: nodal_stress at point {p} is {nodal.tuple(p)}, the mean of its cells {mean}")
        check(abs(mises.values[p] - von_mises(mean)) <= 1e-12 * scale, f"{name}: nodal_von_mises at point {p}")


def check_column(grid, cases):
    L, rho = cases["column_height"], cases["density"]
    tolerance = 1e-6 * rho * G * L
    stress, nodal = grid.cell_data["stress"], grid.point_data["nodal_stress"]
    element_count = sum(1 for s in grid.cell_data["support"].values if not s)
    for c in range(element_count):
        ids = grid.cell_points(c)
        z = sum(grid.coordinates.tuple(p)[2] for p in ids) / 8
        expected = [0, 0, -rho * G * (L - z), 0, 0, 0]
        check(all(abs(a - b) <= tolerance for a, b in zip(stress.tuple(c), expected)),
              f"column: stress of element {c} at z = {z:.3f} is {stress.tuple(c)}, expected {expected}")
    inside = 0
    for p in range(grid.points):
        x, y, z = grid.coordinates.tuple(p)
        if grid.point_data["block"].values[p] != 1 or not 1e-9 < z < L - 1e-9:
            continue
        inside += 1
        expected = [0, 0, -rho * G * (L - z), 0, 0, 0]
        check(all(abs(a - b) <= tolerance for a, b in zip(nodal.tuple(p), expected)),
              f"column: nodal_stress at z = {z:.3f} is {nodal.tuple(p)}, expected {expected}")
    check(inside == 25 * 3, f"column: {inside} nodes strictly inside, expected 5 x 5 x 3")


def refused(path, mutate, folder, label):
    with open(path, "rb") as f:
        data = f.read()
    broken = os.path.join(folder, "broken.vtu")
    with open(broken, "wb") as f:
        f.write(mutate(data))
    try:
        read_vtu(broken)
    except VtuError:
        return
    failures.append(f"the reader accepted a file with {label}")


def main():
    ashlar, folder = sys.argv[1], sys.argv[2]
    os.makedirs(folder, exist_ok=True)
    subprocess.run([ashlar, os.path.join(os.path.dirname(os.path.abspath(__file__)), "fea_vtu_samples.lua"), folder],
                   check=True)
    with open(os.path.join(folder, "cases.json")) as f:
        cases = json.load(f)
    for name in ("column", "arch", "plain"):
        grids = {}
        for form in ("binary", "ascii"):
            path = os.path.join(folder, f"{name}_{form}.vtu")
            try:
                grids[form] = read_vtu(path)
            except VtuError as e:
                failures.append(f"{path}: {e}")
        if len(grids) < 2:
            continue
        attributes = grids["binary"].attributes
        check(attributes.get("header_type") == "UInt64" and attributes.get("compressor") == "vtkZLibDataCompressor",
              f"{name}: the default format is not zlib-compressed binary: {attributes}")
        check("compressor" not in grids["ascii"].attributes, f"{name}: the ASCII file names a compressor")
        same_arrays(name, grids["binary"], grids["ascii"])
        check_grid(name, grids["binary"], cases[name])
        if name == "column":
            check_column(grids["binary"], cases)

    binary = os.path.join(folder, "arch_binary.vtu")
    refused(binary, lambda d: d.replace(b'NumberOfPoints="151"', b'NumberOfPoints="152"', 1), folder,
            "one point more than its arrays hold")
    refused(binary, lambda d: re.sub(rb'offset="(\d+)"/>\s*</PointData>',
                                     lambda m: m.group(0).replace(m.group(1), b"99999999"), d, count=1),
            folder, "an offset past the appended data")
    with open(binary, "rb") as f:
        data = f.read()
    binary_marker = data.index(b"_", data.index(b"<AppendedData")) + 1

    def lie_about_last_block(d):
        header = bytearray(d)
        last = int.from_bytes(header[binary_marker + 16:binary_marker + 24], "little")
        header[binary_marker + 16:binary_marker + 24] = (last + 8).to_bytes(8, "little")
        return bytes(header)

    refused(binary, lie_about_last_block, folder, "a header that gives the wrong size of the last block")
    refused(binary, lambda d: d[:binary_marker + 100] + d[d.rindex(b"</AppendedData>"):], folder,
            "its appended data cut short")

    for failure in failures:
        print("FAIL:", failure)
    print(f"check_fea_vtu: {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
