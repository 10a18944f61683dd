#include "io/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/field_arrays.h"
#include "io/mesh_formats.h"

namespace isocurv::io {
namespace {

enum class Format { Vtp, Ply, Obj, Stl };

Format format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".vtp") return Format::Vtp;
  if (ext == ".ply") return Format::Ply;
  if (ext == ".obj") return Format::Obj;
  if (ext == ".stl") return Format::Stl;
  throw Error(path, "unknown mesh file extension '" + ext + "' (expected one of " +
                        mesh_extensions() + ")");
}

void check_mesh(const Mesh& mesh, const std::string& path) {
  const std::size_t n = mesh.positions.size();
  for (const Tri& t : mesh.triangles)
    for (std::uint32_t v : t)
      if (v >= n)
        throw Error(path, "cannot write: triangle index " + std::to_string(v) + " out of range (" +
                              std::to_string(n) + " vertices)");
}

}  // namespace

const char* mesh_extensions() { return ".vtp, .ply, .obj, .stl"; }

void write_mesh(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field,
                const Compression& compression, const Metadata* context, const CellArrays* cells) {
  const Format format = format_of(path);
  check_mesh(mesh, path);
  if (field) check_field_sizes(*field, mesh.positions.size(), path);
  if (cells)
    for (const CellArray& c : *cells)
      if (c.values.size() != mesh.triangles.size())
        throw Error(path, "cell array '" + c.name + "' has " + std::to_string(c.values.size()) +
                              " values for " + std::to_string(mesh.triangles.size()) + " triangles");
  write_atomically(path, [&](const std::string& tmp) {
    try {
      switch (format) {
        case Format::Vtp: detail::write_vtp(tmp, mesh, field, compression, context, cells); break;
        case Format::Ply: detail::write_ply(tmp, mesh, field, cells); break;
        case Format::Obj: detail::write_obj(tmp, mesh, field); break;
        case Format::Stl: detail::write_stl(tmp, mesh); break;
      }
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(path, std::string("cannot write: ") + e.what());
    }
  });
}

MeshFile read_mesh(const std::string& path) {
  const Format format = format_of(path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(path, "no such file");
  if (std::filesystem::is_directory(path, ec)) throw Error(path, "is a folder, not a mesh file");
  switch (format) {
    case Format::Vtp: return detail::read_vtp(path);
    case Format::Ply: return detail::read_ply(path);
    case Format::Obj: return detail::read_obj(path);
    case Format::Stl: return detail::read_stl(path);
  }
  throw Error(path, "unsupported format");
}

}  // namespace isocurv::io
