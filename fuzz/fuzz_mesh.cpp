// libFuzzer harness for one mesh format (FUZZ_FORMAT, set by fuzz/CMakeLists.txt): the input
// becomes a file of that format and goes through io::read_mesh. A read may fail only with
// isocurv::Error; a read that succeeds must keep what it promises (fuzz/README.md).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "fuzz/fuzz_input.h"
#include "fuzz/vtk_xml_oracle.h"
#include "io/field_arrays.h"
#include "io/mesh_file.h"

namespace {

using isocurv::fuzz::require;

const std::string kFormat = FUZZ_FORMAT;

/// What a simple raw-appended .vtp holds (fuzz/vtk_xml_oracle.h): arrays tiling the appended data,
/// points exactly as many as were read, cell offsets exactly as many as the piece declares.
void check_vtp(const isocurv::io::MeshFile& file, const std::string& text) {
  using namespace isocurv::fuzz;
  bool applies = false;
  std::string problem;
  const auto arrays = raw_appended_arrays(text, applies, problem);
  if (!applies) return;
  require(problem.empty(), "a .vtp whose appended arrays do not tile its data read: " + problem);
  for (const auto& a : arrays) {
    if (a.section == "Points")
      require(a.bytes == file.mesh.positions.size() * 3 * type_bytes(a.type), "the points' bytes are not the points read");
    if (a.name == "offsets" && (a.section == "Verts" || a.section == "Lines" || a.section == "Strips" || a.section == "Polys")) {
      const std::string declared = xml_attribute(text, "Piece", "NumberOf" + a.section);
      const unsigned long long cells = std::strtoull(declared.c_str(), nullptr, 10);
      require(a.bytes == cells * type_bytes(a.type), "a cell array holds other than NumberOf" + a.section + " cells");
    }
  }
}

void check(const isocurv::io::MeshFile& file, std::uint64_t input_bytes) {
  const std::size_t n = file.mesh.positions.size();
  for (const auto& t : file.mesh.triangles)
    require(t[0] < n && t[1] < n && t[2] < n, "triangle index out of range");
  // Each vertex and each triangle costs at least a byte (VTK XML may deflate them).
  const std::uint64_t bound = kFormat == "vtp" ? input_bytes * 1040 + 1024 : input_bytes;
  require(n <= bound && file.mesh.triangles.size() <= bound, "more elements than the data can hold");
  if (file.field) {
    isocurv::io::for_each_array(*file.field, [&](const char* name, const auto& values) {
      require(values.empty() || values.size() == n, std::string("array ") + name + " size");
    });
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto& files = isocurv::fuzz::input_files();
  files.clear();
  const std::string path = files.write("input." + kFormat, data, size);
  try {
    const isocurv::io::MeshFile file = isocurv::io::read_mesh(path);
    check(file, size);
    if (kFormat == "vtp") check_vtp(file, std::string(reinterpret_cast<const char*>(data), size));
  } catch (const isocurv::Error&) {
    // the one allowed failure
  }
  return 0;
}
