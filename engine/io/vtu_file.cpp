// VTK XML UnstructuredGrid files, ASCII or zlib-compressed binary (vtu_file.hpp).
#include "io/vtu_file.hpp"

#include <algorithm>
#include <cstring>
#include <iomanip>
#include <locale>
#include <sstream>

#include <zlib.h>

#include "core/error.hpp"

namespace ashlar {
namespace {

const char* type_name(VtuType type) {
  switch (type) {
    case VtuType::Float64: return "Float64";
    case VtuType::Int32: return "Int32";
    case VtuType::Int64: return "Int64";
    case VtuType::UInt8: return "UInt8";
  }
  return "?";
}

int type_bytes(VtuType type) {
  switch (type) {
    case VtuType::Float64:
    case VtuType::Int64: return 8;
    case VtuType::Int32: return 4;
    case VtuType::UInt8: return 1;
  }
  return 0;
}

class VtuWriter {
public:
  explicit VtuWriter(VtuFormat format) : format_(format) {
    xml_.imbue(std::locale::classic());  // a user's locale must not turn points into commas
    xml_ << std::setprecision(17);
  }

  std::string text(const VtuGrid& grid) {
    const bool binary = format_ == VtuFormat::Binary;
    xml_ << "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"";
    if (binary) xml_ << " header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\"";
    xml_ << ">\n  <UnstructuredGrid>\n"
         << "    <Piece NumberOfPoints=\"" << grid.points << "\" NumberOfCells=\"" << grid.cells
         << "\">\n";
    xml_ << "      <PointData" << grid.point_attributes << ">\n";
    for (const VtuArray& array : grid.point_data) data_array(array);
    xml_ << "      </PointData>\n      <CellData" << grid.cell_attributes << ">\n";
    for (const VtuArray& array : grid.cell_data) data_array(array);
    xml_ << "      </CellData>\n      <Points>\n";
    data_array(grid.coordinates);
    xml_ << "      </Points>\n      <Cells>\n";
    for (const VtuArray& array : grid.cell_arrays) data_array(array);
    xml_ << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
    std::string text = xml_.str();
    if (binary) {
      text += "  <AppendedData encoding=\"raw\">\n   _";
      text += appended_;
      text += "\n  </AppendedData>\n";
    }
    text += "</VTKFile>\n";
    return text;
  }

private:
  static constexpr size_t kBlockSize = 32768;  // VTK's own

  void data_array(const VtuArray& array) {
    xml_ << "        <DataArray type=\"" << type_name(array.type) << "\"";
    if (!array.name.empty()) xml_ << " Name=\"" << array.name << "\"";
    if (array.components > 1) xml_ << " NumberOfComponents=\"" << array.components << "\"";
    xml_ << array.attributes;
    if (format_ == VtuFormat::Binary) {
      xml_ << " format=\"appended\" offset=\"" << appended_.size() << "\"/>\n";
      append_compressed(little_endian(array));
      return;
    }
    xml_ << " format=\"ascii\">\n";
    const bool real = array.type == VtuType::Float64;
    const size_t values = real ? array.reals.size() : array.integers.size();
    for (size_t i = 0; i < values; ++i) {
      const bool first = i % array.components == 0, last = (i + 1) % array.components == 0;
      xml_ << (first ? "          " : " ");
      if (real) xml_ << array.reals[i];
      else xml_ << array.integers[i];
      if (last) xml_ << '\n';
    }
    xml_ << "        </DataArray>\n";
  }

  template <typename Integer>
  static void put(std::string& bytes, Integer value, int width) {  // little-endian
    for (int k = 0; k < width; ++k) bytes.push_back(static_cast<char>((value >> (8 * k)) & 0xff));
  }

  static std::string little_endian(const VtuArray& array) {
    std::string bytes;
    const int width = type_bytes(array.type);
    if (array.type == VtuType::Float64) {
      bytes.reserve(8 * array.reals.size());
      for (double v : array.reals) {
        std::uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        put(bytes, bits, width);
      }
      return bytes;
    }
    bytes.reserve(width * array.integers.size());
    for (std::int64_t v : array.integers) put(bytes, static_cast<std::uint64_t>(v), width);
    return bytes;
  }

  void append_compressed(const std::string& data) {
    const size_t blocks = (data.size() + kBlockSize - 1) / kBlockSize;
    std::vector<std::string> compressed(blocks);
    for (size_t k = 0; k < blocks; ++k) {
      const size_t size = std::min(kBlockSize, data.size() - k * kBlockSize);
      uLongf length = compressBound(size);
      compressed[k].resize(length);
      const int status = compress2(reinterpret_cast<Bytef*>(&compressed[k][0]), &length,
                                   reinterpret_cast<const Bytef*>(data.data() + k * kBlockSize), size,
                                   Z_DEFAULT_COMPRESSION);
      if (status != Z_OK) throw IoError("vtu: zlib failed to compress (code " + std::to_string(status) + ")");
      compressed[k].resize(length);
    }
    put(appended_, static_cast<std::uint64_t>(blocks), 8);
    put(appended_, static_cast<std::uint64_t>(kBlockSize), 8);
    put(appended_, static_cast<std::uint64_t>(data.size() % kBlockSize), 8);
    for (const std::string& block : compressed) put(appended_, static_cast<std::uint64_t>(block.size()), 8);
    for (const std::string& block : compressed) appended_ += block;
  }

  VtuFormat format_;
  std::ostringstream xml_;
  std::string appended_;
};

}  // namespace

VtuArray real_array(std::string name, int components, std::vector<double> values,
                    std::string attributes) {
  return {std::move(name), VtuType::Float64, components, std::move(attributes), std::move(values), {}};
}

VtuArray integer_array(std::string name, VtuType type, std::vector<std::int64_t> values) {
  return {std::move(name), type, 1, "", {}, std::move(values)};
}

std::string vtu_text(const VtuGrid& grid, VtuFormat format) { return VtuWriter(format).text(grid); }

}  // namespace ashlar
