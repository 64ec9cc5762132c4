// VTK XML UnstructuredGrid files (.vtu), written by hand: the format is
// simple and VTK is not a dependency. What goes into the grid is the
// caller's (fea_export.hpp); this file knows the format.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/enum_names.hpp"

namespace ashlar {

// How a .vtu file holds its numbers.
enum class VtuFormat {
  Binary,  // raw appended data, zlib-compressed (VTK's vtkZLibDataCompressor)
  Ascii,   // text, 17 significant digits
};
inline constexpr EnumNames<VtuFormat, 2> kVtuFormatNames{
    {{{VtuFormat::Binary, "binary"}, {VtuFormat::Ascii, "ascii"}}}};

// The value types written, by their VTK names.
enum class VtuType { Float64, Int32, Int64, UInt8 };

// One DataArray: its tuples flattened, as doubles (Float64, in `reals`) or
// as integers (the other types, in `integers`; each value must fit its type).
struct VtuArray {
  std::string name;        // none for the points' coordinates
  VtuType type;
  int components = 1;
  std::string attributes;  // further XML attributes, e.g. ` ComponentName0="XX"`
  std::vector<double> reals;
  std::vector<std::int64_t> integers;
};

VtuArray real_array(std::string name, int components, std::vector<double> values,
                    std::string attributes = "");
VtuArray integer_array(std::string name, VtuType type, std::vector<std::int64_t> values);

// One piece of an unstructured grid. Each point-data array holds `points`
// tuples, each cell-data array `cells`; coordinates 3 x Float64 per point;
// cell_arrays are the <Cells> arrays (connectivity, offsets, types, and
// faces, faceoffsets where there are polyhedra).
struct VtuGrid {
  std::size_t points = 0, cells = 0;
  std::string point_attributes, cell_attributes;  // e.g. ` Scalars="a" Vectors="b"`
  std::vector<VtuArray> point_data, cell_data, cell_arrays;
  VtuArray coordinates;
};

// The file's text, format version 1.0, little-endian.
// Ascii: every array inline, one tuple a line, doubles with 17 significant
// digits (they read back exactly), in the C locale.
// Binary: every DataArray format="appended" into one
// <AppendedData encoding="raw">, header_type UInt64, compressed as VTK's
// vtkZLibDataCompressor does: per array the values little-endian, cut into
// blocks of 32768 bytes (VTK's own size), each compressed by zlib, behind a
// header of UInt64s [number of blocks, block size, uncompressed size of the
// last block (0: a full one), compressed size of each block]; each array's
// offset counts from just after the '_' that opens the data.
// Throws IoError if zlib fails.
std::string vtu_text(const VtuGrid& grid, VtuFormat format);

}  // namespace ashlar
