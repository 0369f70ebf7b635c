// Binary zlib-compressed .vtu: see vtu_compressed.h.
#include "common/vtu_compressed.h"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.h"
#include "common/xml_text.h"

namespace nmm {
namespace {

constexpr std::size_t kBlock = 32768;  // bytes of raw data per compressed block (VTK's default)

bool little_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

void put_u64(std::string& out, std::uint64_t v) {
  char b[8];
  std::memcpy(b, &v, 8);  // little-endian host: checked in vtu_compressed
  out.append(b, 8);
}

/// Appends one array's header and compressed blocks to `data`.
void append_compressed(std::string& data, const void* raw, std::size_t bytes, int level) {
  const std::size_t nblocks = (bytes + kBlock - 1) / kBlock;
  std::vector<std::string> blocks(nblocks);
  const auto* p = static_cast<const Bytef*>(raw);
  for (std::size_t b = 0; b < nblocks; ++b) {
    const std::size_t n = std::min(kBlock, bytes - b * kBlock);
    uLongf out_len = compressBound(static_cast<uLong>(n));
    blocks[b].resize(out_len);
    if (compress2(reinterpret_cast<Bytef*>(blocks[b].data()), &out_len, p + b * kBlock,
                  static_cast<uLong>(n), level) != Z_OK)
      throw std::runtime_error("zlib compress2 failed");
    blocks[b].resize(out_len);
  }
  put_u64(data, nblocks);
  put_u64(data, kBlock);
  put_u64(data, bytes % kBlock);
  for (const std::string& b : blocks) put_u64(data, b.size());
  for (const std::string& b : blocks) data += b;
}

struct Writer {
  int level;  // zlib, 0–9
  std::string xml, data;
  void array(const char* type, const std::string& name, int components, const void* raw,
             std::size_t bytes, const char* indent) {
    xml += indent;
    xml += "<DataArray type=\"";
    xml += type;
    xml += "\" Name=\"" + xml_escape(name) + "\"";
    if (components > 0) xml += " NumberOfComponents=\"" + std::to_string(components) + "\"";
    xml += " format=\"appended\" offset=\"" + std::to_string(data.size()) + "\"/>\n";
    append_compressed(data, raw, bytes, level);
  }
  void arrays(const std::vector<GridArray>& list, const char* tag) {
    if (list.empty()) return;
    xml += std::string("      <") + tag + ">\n";
    for (const GridArray& a : list) {
      if (a.type == GridArray::Type::Float64)
        array("Float64", a.name, a.components, a.f64.data(), a.f64.size() * 8, "        ");
      else
        array("Int32", a.name, a.components, a.i32.data(), a.i32.size() * 4, "        ");
    }
    xml += std::string("      </") + tag + ">\n";
  }
};

}  // namespace

std::string vtu_compressed(const PolygonGrid& g, int level) {
  check_grid(g);
  if (!little_endian()) throw std::logic_error("vtu_compressed: big-endian hosts are not supported");
  if (level < 0 || level > 9) throw std::logic_error("vtu_compressed: zlib level outside 0-9");
  Writer w{level, {}, {}};
  w.xml += "<?xml version=\"1.0\"?>\n";
  w.xml +=
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n";
  w.xml += "  <UnstructuredGrid>\n";
  w.xml += "    <Piece NumberOfPoints=\"" + std::to_string(g.point_count()) + "\" NumberOfCells=\"" +
           std::to_string(g.cell_count()) + "\">\n";
  w.arrays(g.point_data, "PointData");
  w.arrays(g.cell_data, "CellData");
  w.xml += "      <Points>\n";
  w.array("Float64", "Points", 3, g.points.data(), g.points.size() * 8, "        ");
  w.xml += "      </Points>\n      <Cells>\n";
  // VTK's offsets are the end of each cell (no leading 0), unlike our CSR.
  const std::vector<std::int32_t> offsets(g.offsets.begin() + 1, g.offsets.end());
  const std::vector<std::uint8_t> types(g.cell_count(), g.cell_type);  // VTK_POLYGON or VTK_LINE
  w.array("Int32", "connectivity", 0, g.connectivity.data(), g.connectivity.size() * 4, "        ");
  w.array("Int32", "offsets", 0, offsets.data(), offsets.size() * 4, "        ");
  w.array("UInt8", "types", 0, types.data(), types.size(), "        ");
  w.xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
  w.xml += "  <AppendedData encoding=\"raw\">\n   _";
  w.xml += w.data;
  w.xml += "\n  </AppendedData>\n</VTKFile>\n";
  return w.xml;
}

void write_vtu_compressed(const PolygonGrid& grid, const std::string& path,
                          Durability durability) {
  write_file_atomically(path, vtu_compressed(grid), durability);
}

}  // namespace nmm
