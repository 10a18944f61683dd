// .vtp: VTK XML PolyData through vtkXMLPolyDataWriter/Reader (binary appended; LZ4, zlib or none).
#include <vtkCellArray.h>
#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/vtk_progress.h"
#include "core/vtk_xml_blocks.h"
#include "io/mesh_formats.h"
#include "io/polydata.h"
#include "io/vtk_errors.h"

namespace isocurv::io::detail {

void write_vtp(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field,
               const Compression& compression, const Metadata* context, const CellArrays* cells) {
  write_polydata(path, to_polydata(mesh, field, context, cells), compression);
}

}  // namespace isocurv::io::detail

namespace isocurv::io {

void write_polydata(const std::string& path, vtkPolyData* poly, const Compression& compression) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  VtkErrorCapture errors(writer);
  writer->SetInputData(poly);
  writer->SetFileName(path.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary, not base64
  switch (compression.compressor) {
    case Compressor::none: writer->SetCompressorTypeToNone(); break;
    case Compressor::lz4: writer->SetCompressorTypeToLZ4(); break;
    case Compressor::zlib: writer->SetCompressorTypeToZLib(); break;
  }
  if (compression.compressor != Compressor::none) writer->SetCompressionLevel(compression.level);
  writer->SetHeaderTypeToUInt64();  // arrays over 4 GiB
  VtkProgressReport progress(writer);
  const int ok = writer->Write();
  if (!ok || errors.failed() || writer->GetErrorCode() != vtkErrorCode::NoError)
    throw std::runtime_error(errors.failed() ? errors.message()
                                             : vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode()));
}

}  // namespace isocurv::io

namespace isocurv::io::detail {

namespace {

/// The largest value of every `key="<integer>"` attribute in `head` (0 when there is none).
long long largest_attribute(const std::string& head, const std::string& key) {
  long long largest = 0;
  const std::string pattern = key + "=\"";
  for (std::size_t p = head.find(pattern); p != std::string::npos; p = head.find(pattern, p + 1)) {
    const long long v = std::strtoll(head.c_str() + p + pattern.size(), nullptr, 10);
    largest = std::max(largest, v);
  }
  return largest;
}

/// Refuses, before VTK allocates for them, point and cell counts (times the widest array) that
/// the file cannot hold even deflated (at most ~1032 bytes out per byte in).
void check_claims(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1 << 16, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  std::error_code ec;
  const long double size = (long double)std::filesystem::file_size(path, ec);
  const long double most = size * 1040 + 1024;
  const long double width = std::max(3LL, largest_attribute(head, "NumberOfComponents"));
  for (const char* key : {"NumberOfPoints", "NumberOfPolys", "NumberOfStrips", "NumberOfVerts", "NumberOfLines"}) {
    const long long n = largest_attribute(head, key);
    if ((long double)n * width > most)
      throw Error(path, std::string("header claims ") + key + "=" + std::to_string(n) + " (with arrays " +
                            std::to_string((long long)width) + " wide) but the file holds " +
                            std::to_string((long long)size) + " bytes");
  }
}

}  // namespace

MeshFile read_vtp(const std::string& path) {
  check_claims(path);
  // Every type, header, count and block length against the bytes (core/vtk_xml_blocks.h).
  const isocurv::detail::VtkXmlLayout layout = isocurv::detail::check_vtk_xml(path);
  vtkNew<vtkXMLPolyDataReader> reader;
  VtkErrorCapture errors(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  if (errors.failed() || reader->GetErrorCode() != vtkErrorCode::NoError || !poly)
    throw Error(path, "not a readable VTK XML PolyData file" +
                          (errors.failed() ? " (" + errors.message() + ")" : std::string()));
  // VTK reads a cell array's connectivity up to its last offset and ignores the rest: the file
  // must hold exactly that many ids, else cells were lost (or the offsets are wrong).
  const std::pair<const char*, vtkCellArray*> cells[] = {
      {"Verts", poly->GetVerts()}, {"Lines", poly->GetLines()}, {"Strips", poly->GetStrips()}, {"Polys", poly->GetPolys()}};
  for (const auto& [section, array] : cells) {
    unsigned long long stored = 0;
    for (const auto& a : layout.arrays)
      if (a.section == section && a.name == "connectivity") stored += a.values;
    const auto read = static_cast<unsigned long long>(array ? array->GetNumberOfConnectivityIds() : 0);
    if (stored != read)
      throw Error(path, std::string(section) + " connectivity holds " + std::to_string(stored) +
                            " point ids but the offsets use " + std::to_string(read));
  }
  return from_polydata(poly, path);
}

}  // namespace isocurv::io::detail
