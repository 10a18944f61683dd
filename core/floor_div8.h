#pragma once
// Brick coordinates of 8^3 bricks: the voxel-to-brick division that rounds towards minus
// infinity (integer division rounds towards zero, wrong for negative coordinates).
// Tested through its users: tests/mc/bricks_test.cpp (negative brick origins) and tests/volume.
namespace isocurv {

/// floor(v / 8) for any int v.
constexpr int floor_div8(int v) { return v >= 0 ? v / 8 : -((-v + 7) / 8); }

}  // namespace isocurv
