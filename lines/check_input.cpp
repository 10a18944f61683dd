#include <algorithm>
#include <string>

#include "core/error.h"
#include "lines/segments.h"

namespace isocurv::lines {

void check_input(const Mesh& mesh, const curvature::CurvatureField& field, const Options& options) {
  const std::size_t nv = mesh.vertex_count();
  auto need = [&](std::size_t n, const char* name) {
    if (n != nv)
      throw Error(std::string("lines: the curvature field's ") + name + " has " +
                  std::to_string(n) + " values for " + std::to_string(nv) + " vertices");
  };
  need(field.normals.size(), "Normals");
  need(field.k1.size(), "k1");
  need(field.k2.size(), "k2");
  // Contours need no directions: estimators without them (prantl2, prantl3, meyer) still draw
  // contours, their dir1/dir2 empty.
  if (options.lines.needs_directions() || !field.dir1.empty() || !field.dir2.empty()) {
    if (options.lines.needs_directions() && field.dir1.empty() && nv > 0) {
      LineSelection need_d = options.lines;
      need_d.contours = false;
      throw Error("lines: " + need_d.to_string() +
                  " need the principal directions (dir1, dir2), which this curvature field "
                  "lacks (an estimator without them?); only contours can be drawn");
    }
    need(field.dir1.size(), "dir1");
    need(field.dir2.size(), "dir2");
  }
  if (options.lines.needs_dcurv()) {
    if (field.dcurv.empty() && nv > 0) {
      LineSelection need_d = options.lines;
      need_d.contours = false;
      throw Error("lines: " + need_d.to_string() +
                  " need the curvature derivative (dcurv), which this "
                  "curvature field lacks "
                  "(an estimator without it?); only contours can be drawn");
    }
    need(field.dcurv.size(), "dcurv");
  }
  // The largest index first (a loop the compiler vectorises), the culprit only when it is bad.
  std::uint32_t largest = 0;
  for (const Tri& t : mesh.triangles)
    largest = std::max(largest, std::max(t[0], std::max(t[1], t[2])));
  if (!mesh.triangles.empty() && largest >= nv)
    for (const Tri& t : mesh.triangles)
      for (std::uint32_t i : t)
        if (i >= nv)
          throw Error("lines: a triangle uses vertex " + std::to_string(i) + " of " +
                      std::to_string(nv));
}

}  // namespace isocurv::lines
