#pragma once
// Internal to io/: one writer and one reader per mesh format; mesh_file.cpp dispatches on the
// extension. Writers write straight to `path` (the caller makes it atomic and checks the field's
// sizes); `field` may be null. Writers throw std::runtime_error with the bare problem (the caller
// names the target file, not the temporary); readers throw Error naming `path`.
// Tested through io/mesh_file.h: tests/io/test_mesh_file.cpp (every format round trip).
#include <string>

#include "io/compression.h"
#include "io/mesh_file.h"

namespace isocurv::io::detail {

void write_vtp(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field,
               const Compression& compression, const Metadata* context = nullptr,
               const CellArrays* cells = nullptr);
MeshFile read_vtp(const std::string& path);

void write_ply(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field,
               const CellArrays* cells = nullptr);
MeshFile read_ply(const std::string& path);

void write_obj(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field);
MeshFile read_obj(const std::string& path);

void write_stl(const std::string& path, const Mesh& mesh);
MeshFile read_stl(const std::string& path);

}  // namespace isocurv::io::detail
