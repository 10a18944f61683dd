#pragma once
// An independent look at the simplest VTK XML files, for the harnesses' promises: a file whose
// arrays are uncompressed and raw appended (the layout the mutation campaign broke: a header_type
// that does not match the headers, a type that does not match the bytes, counts that drop data,
// appended data shorter than its arrays) is walked here with plain string searches, not with the
// loaders' checker (core/vtk_xml_blocks), so a load that succeeds can be held to what the bytes
// really say.
#include <cstdint>
#include <string>
#include <vector>

namespace isocurv::fuzz {

/// One appended array as its header describes it.
struct RawArray {
  std::string name, type;        ///< Name and type attributes
  std::string section;           ///< the element the DataArray sits in (PointData, Points, Polys, ...)
  unsigned long long bytes = 0;  ///< the byte count in its header
};

/// The appended arrays of `file` when it is a simple raw-appended, uncompressed VTK XML file
/// (one Piece, no compressor, no comments, entities or single-quoted attributes, every array
/// appended); `applies` is false for anything else. When it applies, `problem` describes the
/// first way the arrays fail to tile the appended data exactly (each array's offset + header +
/// byte count reaching the next array's offset, the last one the file's `</AppendedData>`, only
/// whitespace between), or is empty.
std::vector<RawArray> raw_appended_arrays(const std::string& file, bool& applies, std::string& problem);

/// The value of attribute `key` in the first start tag named `element` ("" when absent).
std::string xml_attribute(const std::string& file, const std::string& element, const std::string& key);

/// Bytes of one value of a VTK XML numeric type, 0 for anything else.
unsigned type_bytes(const std::string& type);

}  // namespace isocurv::fuzz
