// .stl: geometry only, through vtkSTLWriter (binary) and vtkSTLReader (merging coincident points).
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>

#include "core/error.h"
#include "io/mesh_formats.h"
#include "io/polydata.h"
#include "io/vtk_errors.h"

namespace isocurv::io::detail {

void write_stl(const std::string& path, const Mesh& mesh) {
  vtkNew<vtkSTLWriter> writer;
  VtkErrorCapture errors(writer);
  writer->SetInputData(to_polydata(mesh));
  writer->SetFileName(path.c_str());
  writer->SetFileTypeToBinary();
  const int ok = writer->Write();
  if (!ok || errors.failed() || writer->GetErrorCode() != vtkErrorCode::NoError)
    throw std::runtime_error(errors.failed() ? errors.message()
                                             : vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode()));
}

namespace {

/// Binary STL has no magic number: accept a file as binary only when its triangle count matches
/// its size, and otherwise only when it looks like ASCII STL ("solid").
void check_stl_framing(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  const auto size = static_cast<std::uint64_t>(in.tellg());
  char head[84] = {};
  in.seekg(0);
  in.read(head, sizeof head);
  std::uint32_t count = 0;
  std::memcpy(&count, head + 80, 4);  // little-endian on the hosts VTK supports here
  if (size >= 84 && size == 84 + 50ull * count) return;
  // ASCII: "solid" and text. (VTK takes a file with bytes above 127 near its start for binary
  // whatever it begins with, and then trusts the triangle count at byte 80.)
  char text[512] = {};
  in.clear();
  in.seekg(0);
  in.read(text, sizeof text);
  const std::streamsize got = in.gcount();
  bool ascii = std::strncmp(text, "solid", 5) == 0;
  for (std::streamsize i = 0; ascii && i < got; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    ascii = (c >= 32 && c < 127) || c == '\n' || c == '\r' || c == '\t';
  }
  if (ascii) return;
  throw Error(path, "not an STL file (neither ASCII 'solid' text nor a binary file of " + std::to_string(count) +
                        " triangles: " + std::to_string(size) + " bytes)");
}

}  // namespace

MeshFile read_stl(const std::string& path) {
  check_stl_framing(path);
  vtkNew<vtkSTLReader> reader;
  VtkErrorCapture errors(reader);
  reader->SetFileName(path.c_str());
  reader->MergingOn();
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  if (errors.failed() || reader->GetErrorCode() != vtkErrorCode::NoError || !poly)
    throw Error(path, "not a readable STL file" + (errors.failed() ? " (" + errors.message() + ")" : std::string()));
  MeshFile out = from_polydata(poly, path);
  out.field.reset();  // STL carries no per-vertex arrays (the reader's face normals are not ours)
  return out;
}

}  // namespace isocurv::io::detail
