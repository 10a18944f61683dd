#include "mc/case_table.h"

#include <vtkMarchingCubesTriangleCases.h>

namespace isocurv::mc {

const CaseTable& case_table() {
  static const CaseTable table = [] {
    CaseTable t{};
    // VTK's cases use the same corner and edge numbering and set a corner's bit when it is above
    // the isovalue, i.e. inside, as isocurv does; their winding already makes (b-a)x(c-a) point
    // away from the set corners, out of the object (DESIGN.md). Tests check both.
    const vtkMarchingCubesTriangleCases* cases = vtkMarchingCubesTriangleCases::GetCases();
    for (int c = 0; c < 256; ++c) {
      const int* e = cases[c].edges;
      int n = 0;
      t.edges[c].fill(-1);
      for (; n < 5 && e[3 * n] >= 0; ++n) {
        t.edges[c][3 * n + 0] = static_cast<std::int8_t>(e[3 * n + 0]);
        t.edges[c][3 * n + 1] = static_cast<std::int8_t>(e[3 * n + 1]);
        t.edges[c][3 * n + 2] = static_cast<std::int8_t>(e[3 * n + 2]);
      }
      t.triangle_count[c] = static_cast<std::uint8_t>(n);
      for (int k = 0; k < 12; ++k)
        if (((c >> kEdgeLow[k]) ^ (c >> kEdgeHigh[k])) & 1) t.crossed[c] |= static_cast<std::uint16_t>(1u << k);
    }
    return t;
  }();
  return table;
}

}  // namespace isocurv::mc
