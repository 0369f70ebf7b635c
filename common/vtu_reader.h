// Reads back the .vtu files this project writes — the solver's frames — into a PolygonGrid, so
// that a finished run can be redrawn (nmm-report) without ParaView.
//
// Formats read (exactly those of common/vtk_writer.h and common/vtu_compressed.h):
//   - ASCII:  <DataArray type=".." Name=".." NumberOfComponents=".." format="ascii"> numbers
//   - binary: <VTKFile ... header_type="UInt64" compressor="vtkZLibDataCompressor">, every
//             <DataArray format="appended" offset="N"> N bytes past the '_' that opens
//             <AppendedData encoding="raw">; there
//               UInt64 nblocks, UInt64 block_size, UInt64 last_block_size (0: last block full),
//               UInt64 compressed_size[nblocks], then the nblocks zlib streams,
//             the raw values little-endian Float64 / Int32 / UInt8.
// Anything else (base64 inline data, UInt32 headers, Float32, other compressors, big-endian) is
// refused with an InputError naming the file and the byte offset, never misread.
#pragma once

#include <string>

#include "common/vtk_writer.h"

namespace nmm {

/// Parses `contents` (the whole file) of an UnstructuredGrid of polygons, or of lines (a frame's
/// flow network). `name` names the file in errors. The result has offsets in our CSR form
/// (leading 0) and point and cell arrays of type Float64 or Int32; the "types" array is checked
/// (all VTK_POLYGON, or all VTK_LINE) and kept as `cell_type`.
PolygonGrid parse_vtu(const std::string& contents, const std::string& name);

/// Reads and parses the file at `path`. InputError naming `path` when it cannot.
PolygonGrid read_vtu(const std::string& path);

}  // namespace nmm
