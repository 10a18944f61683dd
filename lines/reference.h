#pragma once
// The specification of the per-face line extraction, written plainly in double
// precision (single-threaded). The OpenCL kernels (lines/extract.h) are tested
// against it.
// Tested in tests/lines/test_bad_input.cpp, tests/lines/test_contours.cpp.
#include "lines/segments.h"

namespace isocurv::lines {

/// The feature-line segments of `mesh` with curvature `field`, seen by `camera`
/// (only the view-dependent lines use it), as seeds spec G-LINE1/2 and DeCarlo
/// et al. 2003 describe.
///
/// Per vertex i (v_i = camera.view_vector(p_i), u = v.dir1, w = v.dir2, C =
/// dcurv):
///   ndotv = n.v;  kr = k1 u^2 + k2 w^2 (the radial curvature times sin^2
///   theta); num = [u^2 (u C111 + 3 w C112) + w^2 (3 u C122 + w C222)] / (u^2 +
///   w^2) - 2 ndotv tau^2, tau = (k2 - k1) u w / (u^2 + w^2) (num = 0 where u =
///   w = 0); den = ndotv.
/// Then, for suggestive contours, options.smoothing_steps passes replace kr and
/// num at every vertex by their mean over the vertex and the two other corners
/// of each of its triangles. Per face, a zero set is cut where the values at an
/// edge's ends differ in sign (> 0 against
/// <= 0), at p_lo + t (p_hi - p_lo), t = f_lo / (f_lo - f_hi), interpolating
/// from the edge's lower vertex index (so neighbouring faces give bit-identical
/// shared endpoints; an endpoint within kVertexSnap of t = 0 or 1 is moved onto
/// that vertex and keyed by it, edge_key(v, v); a segment of zero length is
/// dropped):
///  - contour: f = ndotv; strength 1.
///  - suggestive: f = kr, the part of the segment where num - t_d den > 0, den
///  > 0 and
///    ndotv < cos theta_c (each linear along the segment; the segment is
///    clipped there); strength = mean over the ends of clamp((num/den - t_d) /
///    t_d, 0, 1) (1 when t_d = 0).
///  - ridge: every corner has k1 > |k2|; f = C111 with each corner's sign
///  flipped where its dir1
///    points against corner 0's; kept when the face gradient of f points
///    against the corners' (aligned) mean dir1 (a maximum) and the mean k1 over
///    the ends exceeds t_r; strength = clamp((k1 - t_r) / t_r, 0, 1) at the
///    ends' mean (1 when t_r = 0).
///  - valley: the same with k2 < -|k1|, C222 and dir2, the gradient along dir2
///  (a minimum of k2)
///    and |k2|.
/// Faces with a repeated index, zero area or a non-finite value at a corner
/// give no segment.
/// @throw Error for invalid input (check_input) or thresholds
/// (resolve_thresholds).
Segments extract_reference(const Mesh &mesh,
                           const curvature::CurvatureField &field,
                           const Camera &camera, const Options &options = {});

} // namespace isocurv::lines
