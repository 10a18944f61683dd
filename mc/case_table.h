#pragma once
// The marching-cubes case table: for each of the 256 corner sign patterns, the triangles' edges.
// Tested in tests/mc/extract_test.cpp (the kernels against mc/extract_reference.h).
#include <array>
#include <cstdint>

namespace isocurv::mc {

/// Cube corners (bit i of the case index = corner i inside): 0 (0,0,0) 1 (1,0,0) 2 (1,1,0)
/// 3 (0,1,0) 4 (0,0,1) 5 (1,0,1) 6 (1,1,1) 7 (0,1,1). Edge e joins corner kEdgeLow[e] to its
/// neighbour kEdgeHigh[e] along axis kEdgeAxis[e].
constexpr std::array<int, 8> kCornerX{0, 1, 1, 0, 0, 1, 1, 0};
constexpr std::array<int, 8> kCornerY{0, 0, 1, 1, 0, 0, 1, 1};
constexpr std::array<int, 8> kCornerZ{0, 0, 0, 0, 1, 1, 1, 1};
constexpr std::array<int, 12> kEdgeLow{0, 1, 3, 0, 4, 5, 7, 4, 0, 1, 3, 2};
constexpr std::array<int, 12> kEdgeHigh{1, 2, 2, 3, 5, 6, 6, 7, 4, 5, 7, 6};
constexpr std::array<int, 12> kEdgeAxis{0, 1, 0, 1, 0, 1, 0, 1, 2, 2, 2, 2};

struct CaseTable {
  std::array<std::uint8_t, 256> triangle_count;       ///< 0..5
  std::array<std::array<std::int8_t, 16>, 256> edges; ///< 3 edges a triangle, -1 padded;
                                                      ///< wound so normals point to outside corners
  std::array<std::uint16_t, 256> crossed;             ///< bit e set when edge e joins an inside
                                                      ///< corner to an outside one
};

/// The table (Lorensen's cases as VTK ships them, wound for isocurv's orientation). Built once.
const CaseTable& case_table();

}  // namespace isocurv::mc
