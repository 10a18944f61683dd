#pragma once
// G-buffer producer (ii): a mesh rasterised in software (SEEDS-SPEC 4.4), so that meshes from
// files give screen-space curvature too.
// Tested in tests/screen/test_mesh_vs_volume.cpp, tests/screen/test_pull_back.cpp.
#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "screen/gbuffer.h"

namespace isocurv::screen {

/// Which triangle each pixel of a rasterised G-buffer sees, and where on it: the barycentric
/// weights (u, v) of its corners 1 and 2 (corner 0 has 1 - u - v). kNone where no triangle is hit.
struct RasterHits {
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> triangle;   ///< per pixel (the G-buffer's layout)
  std::vector<std::array<float, 2>> uv;  ///< per pixel
};

/// Per pixel of `frame`, the nearest triangle of `mesh` its ray crosses (exact ray-triangle
/// intersection at the pixel centre, so positions lie on the triangles for perspective and
/// orthographic cameras alike; both sides of a triangle count); the position is that point, the
/// normal the barycentric interpolation of `normals` (unit, one per vertex) renormalised, the
/// depth its eye depth (a z-buffer; equal depths keep the lower triangle index). Points nearer
/// than near (perspective) are clipped. near/far from the mesh's bounds. Deterministic (TBB
/// over image bands, every band visits the triangles in order).
/// When `hits` is given it receives the triangle and barycentric weights of every pixel.
/// @throw Error when normals.size() != the vertex count or an index is out of range
GBuffer rasterise(const Mesh& mesh, const std::vector<Vec3f>& normals, const ViewFrame& frame,
                  RasterHits* hits = nullptr);

/// Per-vertex `values` of the mesh that was rasterised into `hits`, interpolated linearly in the
/// triangle each pixel sees (the object-space curvature the paper's protocol compares a
/// screen-space estimate with); NaN where no triangle is hit.
/// @throw Error when values.size() != the vertex count or a triangle index is out of range
std::vector<float> interpolate(const Mesh& mesh, const RasterHits& hits,
                               const std::vector<float>& values);

}  // namespace isocurv::screen
