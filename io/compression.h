#pragma once
// How .vtp files are compressed (`--compress none|lz4|zlib[:LEVEL]`); PLY, OBJ and STL ignore it.
// Tested in tests/io/test_mesh_file.cpp.
#include <string>

namespace isocurv::io {

/// The compressor of a .vtp file's appended binary arrays (VTK's vtkXMLWriter compressors; every
/// VTK 9 reader, ParaView included, reads all three).
enum class Compressor { none, lz4, zlib };

/// A compressor and its level. The default, LZ4 at level 1, was chosen by measurement
/// (bench_write, lobster at its Otsu value, 147k vertices with every curvature array): 129 ms
/// against 1530 ms for zlib at VTK's default level 5 (what isocurv wrote before) and 999 ms for
/// zlib at level 1, for a file 1.29 times larger (17.7 MB against 13.7; uncompressed 19.0 MB).
/// Float curvature arrays compress poorly, so zlib's extra time buys little.
struct Compression {
  Compressor compressor = Compressor::lz4;
  /// 1 (fastest) .. 9 (smallest), as vtkXMLWriter::SetCompressionLevel; ignored for none. For
  /// LZ4, VTK maps levels 1..9 onto LZ4's acceleration (1 the most accelerated; all levels
  /// measured within noise of each other here).
  int level = 1;
};

/// Parses "none", "lz4", "lz4:LEVEL", "zlib" or "zlib:LEVEL" (LEVEL 1..9; "zlib" alone means
/// level 1). @throw Error naming the text and the accepted forms for anything else.
Compression parse_compression(const std::string& text);

/// The text parse_compression reads back, e.g. "lz4:1", "zlib:6", "none".
std::string to_string(const Compression& c);

}  // namespace isocurv::io
