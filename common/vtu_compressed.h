// Binary, zlib-compressed VTK XML UnstructuredGrid (.vtu) — the solver's default frame format.
//
// Layout (VTK XML file format, "appended" data, readable by ParaView/VTK ≥ 5 and meshio):
//   <VTKFile ... version="1.0" byte_order="LittleEndian" header_type="UInt64"
//            compressor="vtkZLibDataCompressor">
//   every <DataArray format="appended" offset="N"> points N bytes past the '_' that opens
//   <AppendedData encoding="raw">; there each array is
//     UInt64 nblocks, UInt64 block_size, UInt64 last_block_size (0: the last block is full),
//     UInt64 compressed_size[nblocks], then the nblocks zlib streams,
//   the raw values being little-endian Float64 / Int32 / UInt8 (cell types), split into blocks
//   of block_size bytes (32 KiB, VTK's default).
// The same PolygonGrid as vtu_text (vtk_writer.h), so text stays available as an option.
#pragma once

#include <string>

#include "common/atomic_file.h"
#include "common/vtk_writer.h"

namespace nmm {

/// zlib level of the frames: 1 (fastest). Measured at 2.9k unknowns (bench/output_bench,
/// docs/performance.md "Output"): level 1 takes half the time of level 6 for 2 % more bytes;
/// level 0 (stored) would be 4× faster again but 3.2× larger.
constexpr int kFrameCompressionLevel = 1;

/// The .vtu file contents, binary appended and zlib-compressed at `level` (0–9).
std::string vtu_compressed(const PolygonGrid& grid, int level = kFrameCompressionLevel);

/// vtu_compressed written atomically (write_file_atomically with `durability`). InputError
/// naming `path` on failure.
void write_vtu_compressed(const PolygonGrid& grid, const std::string& path,
                          Durability durability = Durability::synced);

}  // namespace nmm
