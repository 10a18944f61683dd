#pragma once
// G-buffer producer (i): the isosurface of a volume cast per pixel, no mesh involved
// (SEEDS-SPEC 4.4). The OpenCL kernel (screen_kernels.cl, ray_cast) and its C++ reference.
// Tested in tests/screen/test_ray_cast.cpp, tests/screen/test_ct_like.cpp.
#include "core/cl_device.h"
#include "screen/gbuffer.h"
#include "volume/dense_field.h"

namespace isocurv::screen {

struct CastOptions {
  double step = 0.5;  ///< march step in voxels, along the ray's longest index axis (<= 1/2)
  /// Halvings of the crossing step (<= 0.5 voxel along the longest axis): 0.5 / 2^8 ~ 2e-3
  /// voxel, then the secant step (below) lands far under 1e-4 voxel from the surface.
  int bisections = 8;
  /// Safe-stride march: where the field at the ray's point is s < 0 (outside) in a brick with
  /// slope bound L (volume::DenseField::brick_slope), the field stays < 0 for the next |s| / (L
  /// |d|_1) along the ray inside that brick, so the march jumps 0.9 of that (to the brick's exit at
  /// most) when it is longer than `step`: the jumped stretch holds no crossing. (The later
  /// 0.5-voxel samples then fall elsewhere, so a grazing ray that dips in and out within one
  /// step may be caught where the plain march missed it, or the reverse: ~1 pixel in 10^4.)
  bool safe_stride = true;
  /// After the bisections, one secant (regula falsi) step between the bracket's ends instead
  /// of the bracket's midpoint.
  bool secant = true;
};

/// Per pixel of `frame`, the first crossing into the object along the pixel's ray (a sample
/// with signed value sign * (v - iso) > 0 after one <= 0: a sample equal to the isovalue is
/// outside, as for the mesher) of the trilinear field, through the box of the bricks that
/// straddle `iso` (volume::DenseField::straddling_box: no crossing lies outside it);
/// 8^3-cell bricks whose samples do not straddle `iso` are jumped over, and inside the others the
/// march takes the safe stride (CastOptions). The crossing step is bisected and then refined by a
/// secant step; the hit is on the trilinear isosurface to well under 1e-4 voxel. Normal: the
/// volume's gradient normal there (volume::DenseField::normal, volume::gradient_normals' logic); a
/// zero gradient leaves the pixel invalid. A ray starting inside the object finds no surface until
/// it has left it (open surfaces cut by the box show their inner side as nothing). An isovalue
/// that misses the volume gives an all-invalid buffer. near/far from the volume's box.
/// Double precision, TBB over rows, deterministic. @throw Error for a bad step
GBuffer ray_cast_reference(const volume::DenseField& volume, float iso, const ViewFrame& frame,
                           const CastOptions& options = {});

/// The same on `device` in float (positions within ~1e-5 voxel of the reference; a grazing ray
/// may differ). The volume is uploaded on the first call for it and kept (keyed on volume.id).
/// @param work_group work-group size of the launch
/// @throw Error for a bad step or an OpenCL failure
GBuffer ray_cast(const volume::DenseField& volume, float iso, const ViewFrame& frame,
                 Device& device, const CastOptions& options = {}, int work_group = 64);

}  // namespace isocurv::screen
