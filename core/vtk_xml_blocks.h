#pragma once
// Checks a VTK XML file (.vtp, .vti) before VTK's reader sees it (fuzzers found a 4 KB .vtp asking
// for 4 GB and an 805-byte .vti for 2.9 GB). Internal: shared by io/vtp_format.cpp and
// volume/load_vtk_image.cpp, not installed.
#include <string>

namespace isocurv::detail {

/// Refuses compressed arrays whose block header claims more than the file can hold: VTK's XML
/// reader allocates each block, and the header itself, from those sizes before reading any data
/// (a 4 KB file asked for 4 GB). Each header is (number of blocks, block size, last block size,
/// the blocks' compressed sizes), in words of the file's header_type, raw or base64, appended or
/// inline. A block's compressed size must fit in the file and its size be one deflate can
/// reach from it (at most ~1032 bytes out per byte in).
/// Also refuses appended data whose first byte after `<AppendedData ...>` is not '_' (VTK takes
/// whatever byte is there as the marker and reads every header shifted). Reads only the XML text
/// and the block headers. Thread-safe.
/// @param path  the file; one that cannot be opened is left to VTK to report
/// @throw isocurv::Error naming `path` and the array, with the size claimed and the file's size
void check_vtk_xml_compressed_blocks(const std::string& path);

}  // namespace isocurv::detail
