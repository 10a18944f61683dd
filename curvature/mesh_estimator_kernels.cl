// The one-pass mesh estimators on the device: Batagelo & Wu's per-vertex tensor and derivative
// (curvature/batagelo.cpp) and Prantl et al.'s per-triangle shape operator (curvature/prantl.cpp),
// float twins of those double references, step for step. Needs curvature_math.cl and
// curvature_kernels.cl (whose normal, area and boundary kernels run first). No atomics: per-vertex
// kernels loop over a vertex's distinct neighbours (offsets, ids: increasing index order) or its
// corners in adjacency order, so every sum has a fixed order and results are bit-identical run to
// run. Per-vertex kernels are launched over a multiple of the work-group size; the padding
// recomputes the last vertex (or face) but never stores.

// k1 >= k2 and dir1 of the symmetric tensor (ku, kuv, kv) in the basis (bu, bv): one Jacobi
// rotation, as in vertex_principal and the references' diagonalise.
INLINE void principal(float ku, float kuv, float kv, vec3 bu, vec3 bv, float* k1, float* k2,
                      vec3* d1) {
  const float h = 0.5f * (kv - ku) / kuv;
  const float tt0 = h < 0.0f ? 1.0f / (h - sqrt(1.0f + h * h)) : 1.0f / (h + sqrt(1.0f + h * h));
  const float tt = kuv != 0.0f ? tt0 : 0.0f;
  const float c = 1.0f / sqrt(1.0f + tt * tt), s = tt * c;
  const float ka = ku - tt * kuv, kb = kv + tt * kuv;
  const bool swap = ka < kb;
  *k1 = swap ? kb : ka, *k2 = swap ? ka : kb;
  *d1 = swap ? add3(mul3(bu, s), mul3(bv, c)) : sub3(mul3(bu, c), mul3(bv, s));
}

// The arrays every estimator derives from k1, k2 at vertex v.
INLINE void store_derived(uint v, float k1, float k2, float ao_scale, __global float* k1_out,
                          __global float* k2_out, __global float* H, __global float* K,
                          __global float* shape, __global float* curved, __global float* ao) {
  k1_out[v] = k1, k2_out[v] = k2;
  H[v] = 0.5f * (k1 + k2), K[v] = k1 * k2;
  shape[v] = shape_index(k1, k2);
  curved[v] = curvedness(k1, k2);
  ao[v] = ambient_occlusion(k1, k2, ao_scale);
}

// Batagelo 1. Per vertex: the one-pass tensor from the distinct 1-ring (rows
// [xu xv 0; 0 xu xv] (e, f, g) = (yu, yv), x = q - P and y = n_q - n_P on P's basis), solved by
// LDL^T (solve_tensor: the same structured system as a triangle's) and diagonalised; each
// neighbour's rows weighted 1, or 1 / |x|^2 when inverse_square (x projected). A vertex
// whose neighbours do not span the plane (or with a zero normal) gets zeros, dir1 = bu and
// no_tensor = 1.
__kernel void batagelo_tensor(__global const float* positions, __global const float* normals,
                              __global const uint* nb_offsets, __global const uint* nb_ids,
                              const uint vertex_count, const float ao_scale,
                              const uint inverse_square, __global float* k1_out,
                              __global float* k2_out, __global float* dir1_out,
                              __global float* dir2_out, __global float* H, __global float* K,
                              __global float* shape, __global float* curved, __global float* ao,
                              __global uchar* no_tensor) {
  const uint v = min((uint)get_global_id(0), vertex_count - 1);
  const vec3 p = load3(positions, v), n = load3(normals, v);
  vec3 bu, bv;
  tangent_basis(n, &bu, &bv);
  float a = 0.0f, b = 0.0f, c = 0.0f;
  tensor2 r = {0.0f, 0.0f, 0.0f};
  for (uint i = nb_offsets[v]; i < nb_offsets[v + 1]; ++i) {
    const uint q = nb_ids[i];
    const vec3 dx = sub3(load3(positions, q), p), dn = sub3(load3(normals, q), n);
    const float xu = dot3(dx, bu), xv = dot3(dx, bv), yu = dot3(dn, bu), yv = dot3(dn, bv);
    const float r2 = xu * xu + xv * xv;
    const float w = !inverse_square ? 1.0f : r2 > 0.0f ? 1.0f / r2 : 0.0f;
    a += w * xu * xu, b += w * xu * xv, c += w * xv * xv;
    r.u += w * xu * yu, r.uv += w * (xv * yu + xu * yv), r.v += w * xv * yv;
  }
  tensor2 k;
  const bool ok = solve_tensor(a, b, c, r, &k) && dot3(n, n) > 0.0f;
  float k1, k2;
  vec3 d1;
  principal(ok ? k.u : 0.0f, ok ? k.uv : 0.0f, ok ? k.v : 0.0f, bu, bv, &k1, &k2, &d1);
  if (get_global_id(0) >= vertex_count) return;
  store_derived(v, k1, k2, ao_scale, k1_out, k2_out, H, K, shape, curved, ao);
  store3(d1, dir1_out, v);
  store3(cross3(n, d1), dir2_out, v);
  no_tensor[v] = !ok;
}

// Batagelo 2. Per vertex: the curvature-derivative tensor C = (C111, C112, C122, C222) in P's
// principal frame (e1 = dir1) from the differences of the neighbours' second fundamental forms
// (their principal frames rotated into P's plane) along the edges; the corrected full-tensor
// form (SEEDS-SPEC 3.3), solved by solve_derivative. Neighbours without a tensor (no_tensor, step
// 1's flags) are skipped; a vertex without a tensor or with a singular system gets zeros and
// unreliable = 1.
__kernel void batagelo_dcurv(__global const float* positions, __global const float* k1_in,
                             __global const float* k2_in, __global const float* dir1,
                             __global const float* dir2, __global const uint* nb_offsets,
                             __global const uint* nb_ids, __global const uchar* no_tensor,
                             const uint vertex_count, __global float* dcurv,
                             __global uchar* unreliable) {
  const uint v = min((uint)get_global_id(0), vertex_count - 1);
  const vec3 p = load3(positions, v), e1 = load3(dir1, v), e2 = load3(dir2, v);
  const vec3 n = cross3(e1, e2);
  const float k1 = k1_in[v], k2 = k2_in[v];
  const bool usable = no_tensor[v] == 0;
  float a = 0.0f, b = 0.0f, c = 0.0f;
  tensor3 r = {0.0f, 0.0f, 0.0f, 0.0f};
  for (uint i = nb_offsets[v]; i < nb_offsets[v + 1]; ++i) {
    const uint q = nb_ids[i];
    const vec3 dx = sub3(load3(positions, q), p);
    const float x = dot3(dx, e1), y = dot3(dx, e2);
    const vec3 qd1 = load3(dir1, q), qd2 = load3(dir2, q);
    // (alpha1, beta1, alpha2, beta2): q's principal axes, rotated into P's plane, on (e1, e2).
    const frame2 f = vertex_to_face(qd1, qd2, cross3(qd1, qd2), e1, e2, n);
    const float qk1 = k1_in[q], qk2 = k2_in[q];
    const float de = qk1 * f.u1 * f.u1 + qk2 * f.u2 * f.u2 - k1;
    const float df = qk1 * f.u1 * f.v1 + qk2 * f.u2 * f.v2;
    const float dg = qk1 * f.v1 * f.v1 + qk2 * f.v2 * f.v2 - k2;
    const float use = no_tensor[q] == 0 ? 1.0f : 0.0f;
    a += use * x * x, b += use * x * y, c += use * y * y;
    r.c0 += use * x * de, r.c1 += use * (y * de + 2.0f * x * df);
    r.c2 += use * (2.0f * y * df + x * dg), r.c3 += use * y * dg;
  }
  tensor3 C;
  const bool ok = usable && solve_derivative(a, b, c, r, &C);
  if (get_global_id(0) >= vertex_count) return;
  dcurv[4 * v] = ok ? C.c0 : 0.0f, dcurv[4 * v + 1] = ok ? C.c1 : 0.0f;
  dcurv[4 * v + 2] = ok ? C.c2 : 0.0f, dcurv[4 * v + 3] = ok ? C.c3 : 0.0f;
  unreliable[v] = !ok;
}

// Prantl 1. Per face: the shape operator [[L, M], [M, N]] from 3 or 2 edges
// (e_i = V_i - V_{i+1}, dN_i = n_i - n_{i+1} in the frame Tu = e(V1 -> V2), Tv = m x Tu) by the
// closed-form inverse of B = [[p, q, 0], [q, p + r, q], [0, q, r]] (corrected eq. 13), then
// (w H_f, w K_f, w) into each corner (w = area or 1; all 0 for a degenerate triangle:
// pr - q^2 <= PIVOT_TOLERANCE (p + r)^2, or a repeated index).
__kernel void prantl_faces(__global const float* positions, __global const uint* triangles,
                           __global const float* normals, const uint face_count,
                           const int two_edges, const int area_weights, __global float* corner) {
  const uint f = min((uint)get_global_id(0), face_count - 1);
  const uint i0 = triangles[3 * f], i1 = triangles[3 * f + 1], i2 = triangles[3 * f + 2];
  const vec3 p0 = load3(positions, i0), p1 = load3(positions, i1), p2 = load3(positions, i2);
  const vec3 n0 = load3(normals, i0), n1 = load3(normals, i1), n2 = load3(normals, i2);
  const vec3 face_n = cross3(sub3(p1, p0), sub3(p2, p0));  // twice the area
  const float area = 0.5f * sqrt(dot3(face_n, face_n));
  const vec3 tu = unit3(sub3(p1, p0));
  const vec3 tv = cross3(unit3(cross3(tu, sub3(p2, p0))), tu);
  const vec3 e0 = sub3(p0, p1), e1 = sub3(p1, p2), e2 = sub3(p2, p0);
  const vec3 dn0 = sub3(n0, n1), dn1 = sub3(n1, n2), dn2 = sub3(n2, n0);
  const float u0 = dot3(e0, tu), v0 = dot3(e0, tv), a0 = dot3(dn0, tu), b0 = dot3(dn0, tv);
  const float u1 = dot3(e1, tu), v1 = dot3(e1, tv), a1 = dot3(dn1, tu), b1 = dot3(dn1, tv);
  const float third = two_edges ? 0.0f : 1.0f;  // the 2-edge system drops e_3
  const float u2 = third * dot3(e2, tu), v2 = third * dot3(e2, tv);
  const float a2 = third * dot3(dn2, tu), b2 = third * dot3(dn2, tv);
  const float sp = u0 * u0 + u1 * u1 + u2 * u2, sq = u0 * v0 + u1 * v1 + u2 * v2;
  const float sr = v0 * v0 + v1 * v1 + v2 * v2;
  const float c0 = u0 * a0 + u1 * a1 + u2 * a2;
  const float c1 = v0 * a0 + u0 * b0 + v1 * a1 + u1 * b1 + v2 * a2 + u2 * b2;
  const float c2 = v0 * b0 + v1 * b1 + v2 * b2;
  const float minor = sp * sr - sq * sq;
  const float inv_det = 1.0f / ((sp + sr) * minor);
  const float j00 = sr * (sp + sr) - sq * sq, j01 = -sq * sr, j02 = sq * sq, j11 = sp * sr;
  const float j12 = -sp * sq, j22 = sp * (sp + sr) - sq * sq;
  const float L = inv_det * (j00 * c0 + j01 * c1 + j02 * c2);
  const float M = inv_det * (j01 * c0 + j11 * c1 + j12 * c2);
  const float N = inv_det * (j02 * c0 + j12 * c1 + j22 * c2);
  const bool ok = minor > (float)PIVOT_TOLERANCE * (sp + sr) * (sp + sr) &&
                  !(i0 == i1 || i1 == i2 || i2 == i0) && area > 0.0f;
  const float w = area_weights ? area : 1.0f;
  const float wh = w * 0.5f * (L + N), wk = w * (L * N - M * M);
  if (get_global_id(0) >= face_count) return;
  __global float* o = corner + 12 * f;  // select, never multiply by zero (see corner_tensors)
  for (int j = 0; j < 3; ++j) {
    o[4 * j] = ok ? wh : 0.0f, o[4 * j + 1] = ok ? wk : 0.0f;
    o[4 * j + 2] = ok ? w : 0.0f, o[4 * j + 3] = 0.0f;
  }
}

// Prantl 2. Per vertex: H and K averaged over its corners (adjacency order), then
// k1,2 = H +- sqrt(max(0, H^2 - K)). No usable triangle: zeros and unreliable = 1.
__kernel void prantl_vertices(__global const uint* offsets, __global const uint* corners,
                              __global const float4* corner, const uint vertex_count,
                              const float ao_scale, __global float* k1_out,
                              __global float* k2_out, __global float* H, __global float* K,
                              __global float* shape, __global float* curved, __global float* ao,
                              __global uchar* unreliable) {
  const uint v = get_global_id(0);
  if (v >= vertex_count) return;
  const float4 sum = corner_sum(offsets, corners, corner, v);
  const bool ok = sum.z > 0.0f;
  const float h = ok ? sum.x / sum.z : 0.0f, k = ok ? sum.y / sum.z : 0.0f;
  const float disc = h * h - k, root = disc > 0.0f ? sqrt(disc) : 0.0f;
  store_derived(v, h + root, h - root, ao_scale, k1_out, k2_out, H, K, shape, curved, ao);
  H[v] = h, K[v] = k;  // the averaged ones (k1, k2 realise them only when H^2 >= K)
  unreliable[v] = !ok;
}
