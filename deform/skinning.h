#pragma once
// deform::Skin: linear blend skinning (Akenine-Moller et al., Real-Time Rendering 3rd ed.,
// section 4.4; Griffin et al. 2012 section 3.4 "Skin"), positions written on the device:
//   p_i(t) = sum_j w_ij M_j(t) p_i^0,   M_j(t) p = R_j(t) (p - c_j) + c_j + T_j(t)
// with each bone's rotation R_j slerped and translation T_j lerped between keyframes.
//
// The skin file (JSON, read with nlohmann-json):
//   {
//     "bones":     [ {"name": "hip", "pivot": [0, 0, 0]}, ... ],       // pivot c_j, default 0
//     "weights":   [ [[0, 1.0]], [[0, 0.25], [1, 0.75]], ... ],       // per vertex, in mesh
//                                                                     // order: 1-4 [bone, weight]
//     "keyframes": [ {"time": 0.0,
//                     "pose": [ {"rotation": [w, x, y, z],            // unit quaternion
//                                "translation": [x, y, z]}, ... ]},  // one per bone
//                    ... ]                                            // times increasing
//   }
// Rules: one "weights" entry per mesh vertex; bone indices < the number of bones; weights finite,
// >= 0, summing to 1 within 1e-3 per vertex; at least one keyframe, each with one pose per bone;
// rotations non-zero (normalised on reading); "rotation" defaults to [1, 0, 0, 0] and
// "translation" to [0, 0, 0]. Before the first keyframe and after the last the pose is held.
// Tested in tests/deform/deformers_test.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "deform/affine.h"

namespace isocurv::deform {

/// A bone's pose at one keyframe.
struct BonePose {
  std::array<double, 4> rotation{1, 0, 0, 0};  ///< unit quaternion (w, x, y, z)
  std::array<double, 3> translation{0, 0, 0};  ///< world units
};

struct Keyframe {
  double time = 0;
  std::vector<BonePose> pose;  ///< one per bone
};

/// A skinned mesh's rig: bones, per-vertex weights and keyframes (see the file format above).
struct Skin {
  std::vector<std::string> bone_names;
  std::vector<std::array<double, 3>> pivots;  ///< c_j per bone
  /// Per vertex four (bone, weight) slots; unused slots have weight 0 and bone 0.
  std::vector<std::array<std::uint32_t, 4>> bones;
  std::vector<std::array<float, 4>> weights;
  std::vector<Keyframe> keyframes;  ///< times strictly increasing
  std::size_t bone_count() const { return bone_names.size(); }
  std::size_t vertex_count() const { return weights.size(); }
  double start_time() const { return keyframes.front().time; }
  double end_time() const { return keyframes.back().time; }
};

/// Parses and checks a skin file for a mesh of `vertex_count` vertices.
/// @throw isocurv::Error, one line naming `path` and the problem: unreadable file, malformed JSON,
///        a missing or mistyped field, a bone index out of range, weights not summing to ~1,
///        more than 4 weights, a vertex count other than the mesh's, keyframes out of order
Skin load_skin(const std::string& path, std::size_t vertex_count);
/// The same from JSON text (`name` is what errors call it).
Skin parse_skin(const std::string& text, const std::string& name, std::size_t vertex_count);

/// Every bone's 3 x 4 matrix at time t: rotations slerped (shortest arc), translations lerped
/// between the keyframes around t, the pose held outside them.
std::vector<Affine> bone_matrices(const Skin& skin, double t);

/// The skin's rig uploaded once to a device (bones, weights), plus a buffer for the matrices.
class DeviceSkin {
 public:
  DeviceSkin(Device& device, const Skin& skin);
  /// out[i] = sum_j w_ij M_j rest[i] (deform_kernels.cl: skin_positions) with `matrices` (one per
  /// bone) uploaded first. Enqueued only.
  /// @throw isocurv::Error for the wrong number of matrices or an OpenCL failure
  void apply(const cl::Buffer& rest, const std::vector<Affine>& matrices, cl::Buffer& out);

 private:
  Device& device_;
  std::size_t vertex_count_, bone_count_;
  cl::Buffer bones_, weights_, matrices_;
};

/// The C++ reference of DeviceSkin::apply, in float with the same order of operations.
Positions skin_reference(const Positions& rest, const Skin& skin,
                         const std::vector<Affine>& matrices);

}  // namespace isocurv::deform
