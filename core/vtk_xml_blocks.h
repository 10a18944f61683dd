#pragma once
// Checks a VTK XML file (.vtp, .vti) before VTK's reader sees it. VTK's XML reader trusts what the
// file declares: it allocated from block headers (a 4 KB .vtp asked for 4 GB, an 805-byte .vti
// for 2.9 GB), read past the data it was given (values from outside the file), crashed on string
// arrays and on extents near 2^31, and silently dropped data a header did not declare (a .vtp
// whose NumberOfPolys said 1 lost 2,351 triangles). Internal: shared by io/vtp_format.cpp and
// volume/load_vtk_image.cpp, not installed.
// Tested through the readers that call it: tests/io/test_mesh_file.cpp,
// tests/volume/test_bad_input.cpp.
#include <cstddef>
#include <string>
#include <vector>

namespace isocurv::detail {

/// One DataArray as the file stores it.
struct VtkXmlArray {
  std::string section;  ///< enclosing element: PointData, CellData, FieldData, Points, Polys, ...
  std::string name;     ///< its Name attribute
  std::string type;     ///< Int8 ... Float64, or String (FieldData only)
  std::size_t piece = 0;                ///< index of the enclosing Piece (0 outside one)
  unsigned long long values = 0;        ///< values stored: bytes / type size, or ASCII numbers
};

/// What check_vtk_xml found: the dataset type ("ImageData", "PolyData") and every array.
struct VtkXmlLayout {
  std::string type;
  std::vector<VtkXmlArray> arrays;
};

/// Checks the whole structure of a VTK XML file against its bytes, before VTK reads it:
///  - the root: byte_order LittleEndian or BigEndian (required when any array is binary),
///    header_type UInt32 or UInt64, a compressor VTK has (zlib, LZ4, LZMA) or none;
///  - every DataArray: a numeric type (Int8 ... Float64; String only inside FieldData), a
///    positive NumberOfComponents, format ascii, binary or appended, an appended offset inside
///    the appended data, which must begin with '_';
///  - its data against its declaration: binary data's header (the byte count, or for compressed
///    data the block header: blocks, block size, last block size and compressed sizes) in words
///    of the header_type, raw or base64, inline or appended, must describe exactly the bytes the
///    declaration needs (tuples x components x type size, the tuples from the Piece: a .vti
///    Extent's points or cells, a .vtp's NumberOfPoints, NumberOfPolys, ...) and lie inside the
///    array's data (before the file's last `</AppendedData>`, or inside its element); ASCII
///    arrays must hold exactly that many numbers. Arrays whose length the header does not fix (a
///    cell array's connectivity, field data without NumberOfTuples) are checked against the bytes
///    only; their stored lengths are returned for the caller to compare with what VTK read;
///  - compressed blocks: a block size other than 0, sizes one deflate could reach from the
///    compressed bytes (at most ~1032 bytes out per byte in) and compressed sizes inside the file
///    (VTK allocates each block, and the header itself, from these before reading any data);
///  - .vti: WholeExtent and every Piece Extent six integers with min <= max and magnitudes below
///    2^31 - 1 (VTK crashed on 2147483647); Origin and Direction finite, Spacing finite and
///    non-zero;
///  - .vtp: NumberOfPoints, NumberOfVerts, ... non-negative integers.
/// Reads only the XML text and the array headers (not the array data). Thread-safe.
/// @param path  the file; one that cannot be opened is left to the reader to report
/// @return the layout, for checks after VTK has read the file
/// @throw isocurv::Error naming `path`, the array and the problem
VtkXmlLayout check_vtk_xml(const std::string& path);

}  // namespace isocurv::detail
