"""A strict reader of VTK XML UnstructuredGrid (.vtu) files, written from
the VTK file-format specification with Python's standard library alone, so
that it shares no code with the writer it checks (engine/io/fea_export.cpp).

    grid = read_vtu(path)       # raises VtuError naming what is wrong
    grid.points                 # number of points
    grid.cells                  # number of cells
    grid.point_data["name"]     # Array: .type, .components, .values (flat list)
    grid.cell_data["name"]
    grid.coordinates            # Array, 3 components
    grid.connectivity, grid.offsets, grid.types, grid.faces, grid.faceoffsets
    grid.cell_points(c)         # the point ids of cell c
    grid.attributes             # the VTKFile element's attributes

What it checks, beside decoding: the VTKFile element (type, version,
byte_order, header_type, compressor), one Piece with whole
NumberOfPoints/NumberOfCells, every DataArray's type, format, name and
NumberOfComponents, that each array holds exactly its tuple count x
components values; for appended data (raw encoding) that each offset lies
inside the data after the '_' marker, that every block header and
compressed block fits inside it, that each block inflates to the size the
header gives (full blocks to the block size, the last to the last block's
size, 0 there meaning a full block), that the arrays neither overlap nor
leave bytes between them, and that only whitespace follows the last; for
cells, that offsets rise from the first cell, connectivity holds
offsets[-1] point ids all below NumberOfPoints, each cell of a fixed type
has that type's number of points, and each polyhedron's face stream
(faces, faceoffsets) is well formed and uses only the cell's points.
"""

import struct
import sys
import xml.etree.ElementTree as ElementTree
import zlib


class VtuError(Exception):
    pass


# type name -> (struct code, byte size)
TYPES = {
    "Int8": ("b", 1), "UInt8": ("B", 1), "Int16": ("h", 2), "UInt16": ("H", 2),
    "Int32": ("i", 4), "UInt32": ("I", 4), "Int64": ("q", 8), "UInt64": ("Q", 8),
    "Float32": ("f", 4), "Float64": ("d", 8),
}
INTEGER_TYPES = {name for name in TYPES if not name.startswith("Float")}

# Points per cell for the fixed-size linear cell types (vtkCellType.h).
CELL_POINTS = {1: 1, 3: 2, 5: 3, 8: 4, 9: 4, 10: 4, 11: 8, 12: 8, 13: 6, 14: 5}
VTK_POLYHEDRON = 42


class Array:
    def __init__(self, name, type_name, components, values, attributes):
        self.name = name
        self.type = type_name
        self.components = components
        self.values = values
        self.attributes = attributes

    def tuple(self, i):
        c = self.components
        return self.values[c * i:c * (i + 1)]


class Grid:
    pass


def _whole(element, key, where, least=0):
    text = element.get(key)
    if text is None:
        raise VtuError(f"{where}: attribute {key} is missing")
    try:
        value = int(text)
    except ValueError:
        raise VtuError(f"{where}: {key}=\"{text}\" is not a whole number") from None
    if value < least:
        raise VtuError(f"{where}: {key}={value} is below {least}")
    return value


def _split_appended(data):
    """The file's XML with the raw appended bytes cut out, and those bytes
    (from just after the '_' marker up to the closing tag), or None."""
    start = data.find(b"<AppendedData")
    if start < 0:
        return data, None, None
    tag_end = data.index(b">", start)
    tag = data[start:tag_end + 1].decode("ascii")
    close = data.rfind(b"</AppendedData>")
    if close < 0:
        raise VtuError("AppendedData is not closed")
    marker = tag_end + 1
    while marker < close and data[marker:marker + 1] in b" \t\r\n":
        marker += 1
    if data[marker:marker + 1] != b"_":
        raise VtuError("AppendedData does not start with the '_' marker")
    appended = data[marker + 1:close]
    xml = data[:tag_end + 1] + data[close:]
    if tag.rstrip(">").endswith("/"):
        raise VtuError("AppendedData is an empty element")
    return xml, appended, tag


class _Reader:
    def __init__(self, path):
        with open(path, "rb") as f:
            data = f.read()
        xml, self.appended, _ = _split_appended(data)
        try:
            self.root = ElementTree.fromstring(xml)
        except ElementTree.ParseError as e:
            raise VtuError(f"not well-formed XML: {e}") from None
        root = self.root
        if root.tag != "VTKFile":
            raise VtuError(f"the root element is {root.tag}, not VTKFile")
        if root.get("type") != "UnstructuredGrid":
            raise VtuError(f"VTKFile type is {root.get('type')!r}, not 'UnstructuredGrid'")
        version = root.get("version")
        if version is None:
            raise VtuError("VTKFile has no version")
        major, minor = (int(part) for part in version.split("."))
        order = root.get("byte_order")
        if order not in ("LittleEndian", "BigEndian"):
            raise VtuError(f"byte_order is {order!r}")
        self.endian = "<" if order == "LittleEndian" else ">"
        header_type = root.get("header_type", "UInt32")
        if header_type not in ("UInt32", "UInt64"):
            raise VtuError(f"header_type is {header_type!r}, not UInt32 or UInt64")
        if header_type == "UInt64" and (major, minor) < (1, 0):
            raise VtuError("header_type UInt64 needs file version 1.0 or later")
        self.header = TYPES[header_type]
        compressor = root.get("compressor")
        if compressor not in (None, "vtkZLibDataCompressor"):
            raise VtuError(f"compressor {compressor!r} is not supported")
        self.compressed = compressor is not None

        if self.appended is not None:
            appended = root.find("AppendedData")
            encoding = appended.get("encoding")
            if encoding != "raw":
                raise VtuError(f"AppendedData encoding is {encoding!r}; this reader reads 'raw'")
        self.extents = []  # (offset, end) of each appended array

    def header_values(self, data, at, count, what):
        code, size = self.header
        end = at + count * size
        if end > len(data):
            raise VtuError(f"{what}: its header runs past the end of the data")
        return struct.unpack(f"{self.endian}{count}{code}", data[at:end]), end

    def binary_bytes(self, data, at, what):
        """The array's bytes from its header at `at`; returns (bytes, end)."""
        if not self.compressed:
            (size,), at = self.header_values(data, at, 1, what)
            if at + size > len(data):
                raise VtuError(f"{what}: {size} bytes run past the end of the data")
            return data[at:at + size], at + size
        (blocks, block_size, last_size), at = self.header_values(data, at, 3, what)
        sizes, at = self.header_values(data, at, blocks, what)
        if blocks and block_size == 0:
            raise VtuError(f"{what}: block size 0")
        if last_size > block_size:
            raise VtuError(f"{what}: last block of {last_size} bytes exceeds the block size {block_size}")
        out = bytearray()
        for k, size in enumerate(sizes):
            if at + size > len(data):
                raise VtuError(f"{what}: compressed block {k + 1} runs past the end of the data")
            try:
                inflater = zlib.decompressobj()
                block = inflater.decompress(data[at:at + size])
                block += inflater.flush()
            except zlib.error as e:
                raise VtuError(f"{what}: block {k + 1} does not inflate: {e}") from None
            if not inflater.eof or inflater.unused_data:
                raise VtuError(f"{what}: block {k + 1} is not exactly one zlib stream")
            expected = last_size if k == blocks - 1 and last_size else block_size
            if len(block) != expected:
                raise VtuError(f"{what}: block {k + 1} inflates to {len(block)} bytes, the header says {expected}")
            out += block
            at += size
        return bytes(out), at

    def array(self, element, count, where, name_required=True, expected_type=None):
        name = element.get("Name")
        what = f"{where} DataArray {name!r}"
        if element.tag != "DataArray":
            raise VtuError(f"{where}: {element.tag} where a DataArray belongs")
        if name_required and not name:
            raise VtuError(f"{where}: a DataArray without a Name")
        type_name = element.get("type")
        if type_name not in TYPES:
            raise VtuError(f"{what}: type {type_name!r} is not a VTK type")
        if expected_type and type_name not in expected_type:
            raise VtuError(f"{what}: type {type_name}, expected one of {sorted(expected_type)}")
        components = _whole(element, "NumberOfComponents", what, 1) if "NumberOfComponents" in element.attrib else 1
        code, size = TYPES[type_name]
        values_expected = count * components
        form = element.get("format")
        if form == "ascii":
            words = (element.text or "").split()
            if len(words) != values_expected:
                raise VtuError(f"{what}: {len(words)} values, expected {count} x {components}")
            convert = int if type_name in INTEGER_TYPES else float
            try:
                values = [convert(w) for w in words]
            except ValueError as e:
                raise VtuError(f"{what}: {e}") from None
        elif form == "appended":
            if self.appended is None:
                raise VtuError(f"{what}: appended, but the file has no AppendedData")
            if (element.text or "").strip():
                raise VtuError(f"{what}: appended, yet it has inline content")
            offset = _whole(element, "offset", what)
            if offset >= len(self.appended):
                raise VtuError(f"{what}: offset {offset} is outside the {len(self.appended)} bytes of appended data")
            raw, end = self.binary_bytes(self.appended, offset, what)
            self.extents.append((offset, end, what))
            if len(raw) != values_expected * size:
                raise VtuError(f"{what}: {len(raw)} bytes, expected {count} x {components} x {size}")
            values = list(struct.unpack(f"{self.endian}{values_expected}{code}", raw))
        elif form == "binary":
            raise VtuError(f"{what}: inline binary data; this reader reads ascii and appended raw")
        else:
            raise VtuError(f"{what}: format {form!r} is not ascii, binary or appended")
        return Array(name, type_name, components, values, dict(element.attrib))

    def check_extents(self):
        """Appended arrays neither overlap nor leave gaps; only whitespace follows."""
        position = 0
        for offset, end, what in sorted(self.extents):
            if offset != position:
                raise VtuError(f"{what}: starts at {offset}, the previous array ends at {position}")
            position = end
        if self.appended is not None and self.appended[position:].strip(b" \t\r\n"):
            raise VtuError(f"{len(self.appended) - position} bytes after the last array are not whitespace")


def read_vtu(path):
    reader = _Reader(path)
    root = reader.root
    grids = root.findall("UnstructuredGrid")
    if len(grids) != 1:
        raise VtuError(f"{len(grids)} UnstructuredGrid elements, expected 1")
    pieces = grids[0].findall("Piece")
    if len(pieces) != 1:
        raise VtuError(f"{len(pieces)} Piece elements; this reader reads 1")
    piece = pieces[0]
    grid = Grid()
    grid.attributes = dict(root.attrib)
    grid.points = _whole(piece, "NumberOfPoints", "Piece")
    grid.cells = _whole(piece, "NumberOfCells", "Piece")

    def data_section(tag, count):
        arrays = {}
        section = piece.findall(tag)
        if len(section) > 1:
            raise VtuError(f"{len(section)} {tag} elements")
        if not section:
            return arrays, {}
        for element in section[0]:
            array = reader.array(element, count, tag)
            if array.name in arrays:
                raise VtuError(f"{tag}: two arrays named {array.name!r}")
            arrays[array.name] = array
        for role in ("Scalars", "Vectors", "Tensors", "Normals", "TCoords"):
            named = section[0].get(role)
            if named is not None and named not in arrays:
                raise VtuError(f"{tag} {role}={named!r} names no array")
        return arrays, dict(section[0].attrib)

    grid.point_data, grid.point_roles = data_section("PointData", grid.points)
    grid.cell_data, grid.cell_roles = data_section("CellData", grid.cells)

    points = piece.find("Points")
    if points is None or len(points) != 1:
        raise VtuError("Piece needs a Points element with one DataArray")
    grid.coordinates = reader.array(points[0], grid.points, "Points", False, {"Float32", "Float64"})
    if grid.coordinates.components != 3:
        raise VtuError(f"Points have {grid.coordinates.components} components, not 3")

    cells = piece.find("Cells")
    if cells is None:
        raise VtuError("Piece has no Cells element")
    by_name = {}
    for element in cells:
        name = element.get("Name")
        if name not in ("connectivity", "offsets", "types", "faces", "faceoffsets"):
            raise VtuError(f"Cells: unexpected array {name!r}")
        if name in by_name:
            raise VtuError(f"Cells: two arrays named {name!r}")
        by_name[name] = element
    for name in ("connectivity", "offsets", "types"):
        if name not in by_name:
            raise VtuError(f"Cells: no {name} array")
    grid.offsets = reader.array(by_name["offsets"], grid.cells, "Cells", expected_type=INTEGER_TYPES).values
    previous = 0
    for c, end in enumerate(grid.offsets):
        if end < previous:
            raise VtuError(f"Cells: offset of cell {c} ({end}) is below the previous ({previous})")
        previous = end
    grid.connectivity = reader.array(by_name["connectivity"], previous, "Cells", expected_type=INTEGER_TYPES).values
    grid.types = reader.array(by_name["types"], grid.cells, "Cells", expected_type={"UInt8"}).values
    for i, p in enumerate(grid.connectivity):
        if not 0 <= p < grid.points:
            raise VtuError(f"Cells: connectivity[{i}] = {p} is not a point (0 to {grid.points - 1})")

    grid.faces, grid.faceoffsets = None, None
    if ("faces" in by_name) != ("faceoffsets" in by_name):
        raise VtuError("Cells: faces and faceoffsets come together")
    if "faces" in by_name:
        grid.faceoffsets = reader.array(by_name["faceoffsets"], grid.cells, "Cells", expected_type=INTEGER_TYPES).values
        stream_end = max([o for o in grid.faceoffsets if o >= 0], default=0)
        grid.faces = reader.array(by_name["faces"], stream_end, "Cells", expected_type=INTEGER_TYPES).values

    def cell_points(c):
        start = grid.offsets[c - 1] if c else 0
        return grid.connectivity[start:grid.offsets[c]]

    grid.cell_points = cell_points
    face_position = 0
    for c, cell_type in enumerate(grid.types):
        ids = cell_points(c)
        if cell_type == VTK_POLYHEDRON:
            if grid.faces is None:
                raise VtuError(f"cell {c} is a polyhedron, but the file has no faces")
            end = grid.faceoffsets[c]
            if end < face_position:
                raise VtuError(f"cell {c}: faceoffset {end} is before the end of the previous polyhedron ({face_position})")
            stream = grid.faces[face_position:end]
            if not stream:
                raise VtuError(f"cell {c}: empty face stream")
            at, faces = 1, stream[0]
            if faces < 4:
                raise VtuError(f"cell {c}: a polyhedron with {faces} faces")
            for f in range(faces):
                if at >= len(stream) or stream[at] < 3 or at + 1 + stream[at] > len(stream):
                    raise VtuError(f"cell {c}: face {f} does not fit its face stream")
                for p in stream[at + 1:at + 1 + stream[at]]:
                    if p not in ids:
                        raise VtuError(f"cell {c}: face {f} uses point {p}, not one of the cell's")
                at += 1 + stream[at]
            if at != len(stream):
                raise VtuError(f"cell {c}: {len(stream) - at} values left over in its face stream")
            face_position = end
        else:
            if cell_type not in CELL_POINTS:
                raise VtuError(f"cell {c}: type {cell_type} is not a linear VTK cell type this reader knows")
            if len(ids) != CELL_POINTS[cell_type]:
                raise VtuError(f"cell {c}: type {cell_type} needs {CELL_POINTS[cell_type]} points, has {len(ids)}")
            if grid.faceoffsets is not None and grid.faceoffsets[c] != -1:
                raise VtuError(f"cell {c}: faceoffset {grid.faceoffsets[c]} on a cell that is no polyhedron")
    if grid.faces is not None and face_position != len(grid.faces):
        raise VtuError("faces: values that no polyhedron uses")
    reader.check_extents()
    return grid


if __name__ == "__main__":
    for path in sys.argv[1:]:
        g = read_vtu(path)
        print(f"{path}: {g.points} points, {g.cells} cells; point data {sorted(g.point_data)}, "
              f"cell data {sorted(g.cell_data)}")
