// .obj, written and read by hand: v, vn and f records (geometry and normals only).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "io/mesh_formats.h"

namespace isocurv::io::detail {

void write_obj(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file) throw std::runtime_error(std::string("cannot open for writing: ") + std::strerror(errno));
  std::FILE* f = file.get();
  const bool normals = field && !field->normals.empty();
  std::fprintf(f, "# isocurv mesh: %zu vertices, %zu triangles%s\n", mesh.positions.size(),
               mesh.triangles.size(), normals ? ", per-vertex normals" : "");
  // %.9g round-trips every float exactly.
  for (const Vec3f& p : mesh.positions) std::fprintf(f, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
  if (normals)
    for (const Vec3f& n : field->normals) std::fprintf(f, "vn %.9g %.9g %.9g\n", n[0], n[1], n[2]);
  for (const Tri& t : mesh.triangles) {
    if (normals)
      std::fprintf(f, "f %u//%u %u//%u %u//%u\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
    else
      std::fprintf(f, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
  }
  if (std::ferror(f)) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
  std::FILE* raw = file.release();
  if (std::fclose(raw) != 0) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
}

namespace {

/// Parses "i", "i/t", "i//n" or "i/t/n" (1-based, negative = relative to the end) into 0-based
/// vertex and normal indices (normal -1 when absent).
void parse_corner(const char* token, long long vertices, long long normals, long long& v, long long& n,
                  const std::string& path, std::size_t line) {
  auto resolve = [&](const char* s, char** end, long long count, const char* what) {
    const long long i = std::strtoll(s, end, 10);
    if (*end == s) throw Error(path, "line " + std::to_string(line) + ": bad face index '" + token + "'");
    const long long r = i < 0 ? count + i : i - 1;
    if (i == 0 || r < 0 || r >= count)
      throw Error(path, "line " + std::to_string(line) + ": " + what + " index " + std::to_string(i) +
                            " out of range (" + std::to_string(count) + " so far)");
    return r;
  };
  char* end = nullptr;
  v = resolve(token, &end, vertices, "vertex");
  n = -1;
  if (*end != '/') return;
  const char* t = end + 1;
  if (*t != '/') std::strtoll(t, &end, 10), t = end;  // texture index: ignored
  if (*t != '/') return;
  ++t;
  if (*t == '\0' || *t == ' ') return;
  n = resolve(t, &end, normals, "normal");
}

}  // namespace

MeshFile read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  MeshFile out;
  std::vector<Vec3f> normals;
  std::vector<Vec3f> vertex_normals;
  bool any_normal = false;
  std::string line;
  std::size_t line_number = 0;
  auto parse_vec = [&](const char* s, Vec3f& v) {
    char* end = nullptr;
    for (int c = 0; c < 3; ++c) {
      v[static_cast<std::size_t>(c)] = std::strtof(s, &end);
      if (end == s) throw Error(path, "line " + std::to_string(line_number) + ": expected 3 numbers");
      s = end;
    }
  };
  std::vector<std::uint32_t> polygon;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const char* s = line.c_str();
    while (*s == ' ' || *s == '\t') ++s;
    if (s[0] == 'v' && s[1] == ' ') {
      Vec3f p;
      parse_vec(s + 2, p);
      out.mesh.positions.push_back(p);
    } else if (s[0] == 'v' && s[1] == 'n' && s[2] == ' ') {
      Vec3f n;
      parse_vec(s + 3, n);
      normals.push_back(n);
    } else if (s[0] == 'f' && s[1] == ' ') {
      polygon.clear();
      const std::string rest(s + 2);
      std::size_t pos = 0;
      while ((pos = rest.find_first_not_of(" \t", pos)) != std::string::npos) {
        const std::size_t end = rest.find_first_of(" \t", pos);
        const std::string token = rest.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        pos = end;
        long long v = 0, n = -1;
        parse_corner(token.c_str(), static_cast<long long>(out.mesh.positions.size()),
                     static_cast<long long>(normals.size()), v, n, path, line_number);
        polygon.push_back(static_cast<std::uint32_t>(v));
        if (n >= 0) {
          vertex_normals.resize(out.mesh.positions.size(), Vec3f{0, 0, 0});
          vertex_normals[static_cast<std::size_t>(v)] = normals[static_cast<std::size_t>(n)];
          any_normal = true;
        }
        if (pos == std::string::npos) break;
      }
      if (polygon.size() < 3) throw Error(path, "line " + std::to_string(line_number) + ": face with fewer than 3 vertices");
      for (std::size_t k = 2; k < polygon.size(); ++k)
        out.mesh.triangles.push_back({polygon[0], polygon[k - 1], polygon[k]});
    }
    // other records (vt, o, g, s, usemtl, mtllib, comments) carry nothing we keep
  }
  if (in.bad()) throw Error(path, "read error");
  if (any_normal) {
    vertex_normals.resize(out.mesh.positions.size(), Vec3f{0, 0, 0});
    curvature::CurvatureField field;
    field.normals = std::move(vertex_normals);
    out.field = std::move(field);
  }
  return out;
}

}  // namespace isocurv::io::detail
