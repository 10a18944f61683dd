#pragma once
// Comparing meshes and curvature arrays read back from the files isocurv wrote (bit for bit).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::test {

/// True when the two arrays have the same length and the same bytes (so NaNs compare equal and
/// -0 differs from +0: "intact" means exactly what was written).
template <typename T, typename A>
bool same_bits(const std::vector<T, A>& a, const std::vector<T, A>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Index of the first element whose bytes differ, or -1.
template <typename T, typename A>
long first_difference(const std::vector<T, A>& a, const std::vector<T, A>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(T)) != 0) return long(i);
  return a.size() == b.size() ? -1 : long(n);
}

inline void expect_same_mesh(const Mesh& a, const Mesh& b, const std::string& what) {
  EXPECT_EQ(a.positions.size(), b.positions.size()) << what;
  EXPECT_EQ(a.triangles.size(), b.triangles.size()) << what;
  EXPECT_TRUE(same_bits(a.positions, b.positions)) << what << ": positions differ at vertex "
                                                   << first_difference(a.positions, b.positions);
  EXPECT_TRUE(same_bits(a.triangles, b.triangles)) << what << ": triangles differ at "
                                                   << first_difference(a.triangles, b.triangles);
}

/// Every array of DESIGN.md, bit for bit.
inline void expect_same_field(const curvature::CurvatureField& a, const curvature::CurvatureField& b,
                              const std::string& what) {
#define ISOCURV_SAME(member, name)                                                                   \
  EXPECT_TRUE(same_bits(a.member, b.member)) << what << ": array " << name << " differs (sizes "    \
                                             << a.member.size() << ", " << b.member.size()          \
                                             << "; first difference at " << first_difference(a.member, b.member) << ")"
  ISOCURV_SAME(normals, "Normals");
  ISOCURV_SAME(area, "Area");
  ISOCURV_SAME(k1, "k1");
  ISOCURV_SAME(k2, "k2");
  ISOCURV_SAME(dir1, "dir1");
  ISOCURV_SAME(dir2, "dir2");
  ISOCURV_SAME(H, "H");
  ISOCURV_SAME(K, "K");
  ISOCURV_SAME(dcurv, "dcurv");
  ISOCURV_SAME(shape_index, "ShapeIndex");
  ISOCURV_SAME(curvedness, "Curvedness");
  ISOCURV_SAME(ao, "AO");
#undef ISOCURV_SAME
}

/// Every array of DESIGN.md present with one entry per vertex.
inline void expect_complete_field(const curvature::CurvatureField& f, std::size_t n, const std::string& what) {
  EXPECT_EQ(f.normals.size(), n) << what << " Normals";
  EXPECT_EQ(f.area.size(), n) << what << " Area";
  EXPECT_EQ(f.k1.size(), n) << what << " k1";
  EXPECT_EQ(f.k2.size(), n) << what << " k2";
  EXPECT_EQ(f.dir1.size(), n) << what << " dir1";
  EXPECT_EQ(f.dir2.size(), n) << what << " dir2";
  EXPECT_EQ(f.H.size(), n) << what << " H";
  EXPECT_EQ(f.K.size(), n) << what << " K";
  EXPECT_EQ(f.dcurv.size(), n) << what << " dcurv";
  EXPECT_EQ(f.shape_index.size(), n) << what << " ShapeIndex";
  EXPECT_EQ(f.curvedness.size(), n) << what << " Curvedness";
  EXPECT_EQ(f.ao.size(), n) << what << " AO";
}

}  // namespace isocurv::test
