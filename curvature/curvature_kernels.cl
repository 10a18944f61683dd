// The curvature pipeline (Griffin et al. section 3.6) without atomics. Per-face kernels write one
// float4 per corner (corner = 3 * face + j) into `corner`; per-vertex kernels sum a vertex's
// corners in increasing order through the vertex -> corner adjacency (offsets, corners), so every
// sum has a fixed order and results are bit-identical run to run. Needs curvature_math.cl.
// Positions, normals and directions are packed float triples. Edge j of a triangle is opposite
// corner j: e0 = p2 - p1, e1 = p0 - p2, e2 = p1 - p0. Face kernels are launched over a multiple
// of the work-group size; the padding recomputes the last face but never stores. MAX_FAN (a build
// option) is the largest fan vertex_boundary handles; vertex_boundary_large takes the others.


// The sum of vertex v's corner values, in adjacency order.
INLINE float4 corner_sum(__global const uint* offsets, __global const uint* corners,
                         __global const float4* corner, uint v) {
  float4 sum = (float4)(0.0f);
  for (uint i = offsets[v]; i < offsets[v + 1]; ++i) sum += corner[corners[i]];
  return sum;
}

// 1a. Per face: each corner's weighted face normal (xyz) and Meyer mixed area (w).
__kernel void corner_normals_areas(__global const float* positions, __global const uint* triangles,
                                   const uint face_count, const int area_weights,
                                   __global float* corner) {
  const uint f = min((uint)get_global_id(0), face_count - 1);
  const uint i0 = triangles[3 * f], i1 = triangles[3 * f + 1], i2 = triangles[3 * f + 2];
  const vec3 p0 = load3(positions, i0), p1 = load3(positions, i1), p2 = load3(positions, i2);
  const vec3 e0 = sub3(p2, p1), e1 = sub3(p0, p2), e2 = sub3(p1, p0);
  const vec3 face_n = cross3(e2, sub3(p2, p0));  // outward, twice the area
  const vec3 c01 = cross3(e0, e1);
  const bool usable = !(i0 == i1 || i1 == i2 || i2 == i0);
  const float area = usable ? 0.5f * sqrt(dot3(c01, c01)) : 0.0f;
  const float l0 = dot3(e0, e0), l1 = dot3(e1, e1), l2 = dot3(e2, e2);
  // Meyer's mixed areas: half to an obtuse corner and a quarter to the others; else Voronoi
  // regions, from the circumcentre's barycentric coordinates w (their sum is 16 area^2).
  const bool obtuse0 = l0 > l1 + l2, obtuse1 = l1 > l2 + l0, obtuse2 = l2 > l0 + l1;
  const bool obtuse = obtuse0 || obtuse1 || obtuse2, flat = !(area > 0.0f);
  const float w0 = l0 * (l1 + l2 - l0), w1 = l1 * (l2 + l0 - l1), w2 = l2 * (l0 + l1 - l2);
  const float sum = w0 + w1 + w2;
  const float s = area / (2.0f * sum), third = area / 3.0f;
  const float v0 = sum > 0.0f ? s * (w1 + w2) : third, v1 = sum > 0.0f ? s * (w2 + w0) : third;
  const float v2 = sum > 0.0f ? s * (w0 + w1) : third;
  const float a0 = flat ? 0.0f : obtuse ? (obtuse0 ? 0.5f : 0.25f) * area : v0;
  const float a1 = flat ? 0.0f : obtuse ? (obtuse1 ? 0.5f : 0.25f) * area : v1;
  const float a2 = flat ? 0.0f : obtuse ? (obtuse2 ? 0.5f : 0.25f) * area : v2;
  // Max's weights: the face normal divided by the squared lengths of the corner's two edges;
  // dropped when not finite (a zero-length edge, whose face normal is zero anyway).
  const float m0 = area_weights ? 1.0f : 1.0f / (l2 * l1);
  const float m1 = area_weights ? 1.0f : 1.0f / (l0 * l2);
  const float m2 = area_weights ? 1.0f : 1.0f / (l1 * l0);
  const bool keep = usable && finite((m0 + m1 + m2) * (face_n.x + face_n.y + face_n.z));
  if (get_global_id(0) >= face_count) return;
  __global float* o = corner + 12 * f;
  o[0] = keep ? m0 * face_n.x : 0.0f, o[1] = keep ? m0 * face_n.y : 0.0f;
  o[2] = keep ? m0 * face_n.z : 0.0f, o[3] = a0;
  o[4] = keep ? m1 * face_n.x : 0.0f, o[5] = keep ? m1 * face_n.y : 0.0f;
  o[6] = keep ? m1 * face_n.z : 0.0f, o[7] = a1;
  o[8] = keep ? m2 * face_n.x : 0.0f, o[9] = keep ? m2 * face_n.y : 0.0f;
  o[10] = keep ? m2 * face_n.z : 0.0f, o[11] = a2;
}

// 1b. Per vertex: the unit normal (or the given one, when finite and non-zero) and mixed area.
__kernel void vertex_normals_areas(__global const uint* offsets, __global const uint* corners,
                                   __global const float4* corner,
                                   __global const float* given_normals, const int has_given,
                                   const uint vertex_count, __global float* normals,
                                   __global float* area) {
  const uint v = get_global_id(0);
  if (v >= vertex_count) return;
  const float4 sum = corner_sum(offsets, corners, corner, v);
  vec3 n = v3(sum.x, sum.y, sum.z);
  if (has_given) {
    const vec3 g = load3(given_normals, v);
    const float g2 = dot3(g, g);
    if (finite(g2) && g2 > 0.0f) n = g;
  }
  const float len = sqrt(dot3(n, n));
  store3(len > 0.0f && finite(len) ? mul3(n, 1.0f / len) : v3(0.0f, 0.0f, 0.0f), normals, v);
  area[v] = sum.w;
}

// The other two vertices of corner c, in the triangle's winding: *next, then *prev.
INLINE void corner_neighbours(__global const uint* triangles, uint c, uint* next, uint* prev) {
  const uint f = c / 3, j = c - 3 * f;
  const uint t0 = triangles[3 * f], t1 = triangles[3 * f + 1], t2 = triangles[3 * f + 2];
  *next = j == 0 ? t1 : j == 1 ? t2 : t0;
  *prev = j == 0 ? t2 : j == 1 ? t0 : t1;
}

// 1c. Per vertex with at most MAX_FAN corners: the boundary flag, set when some edge at the
// vertex is used by one triangle only, i.e. its other end is the next or previous vertex of
// exactly one of the vertex's corners (repeated-index triangles are not in the adjacency).
__kernel void vertex_boundary(__global const uint* offsets, __global const uint* corners,
                              __global const uint* triangles, const uint vertex_count,
                              __global uchar* boundary) {
  const uint v = min((uint)get_global_id(0), vertex_count - 1);
  const uint begin = offsets[v], fan = offsets[v + 1] - begin;
  uint nb[2 * MAX_FAN];  // the neighbours, in registers once unrolled
#pragma unroll
  for (uint i = 0; i < MAX_FAN; ++i) {
    uint next = ~0u, prev = ~0u;  // no vertex has this index
    if (i < fan) corner_neighbours(triangles, corners[begin + i], &next, &prev);
    nb[2 * i] = next, nb[2 * i + 1] = prev;
  }
  bool open = false;
#pragma unroll
  for (uint i = 0; i < 2 * MAX_FAN; ++i) {
    uint uses = 0;
#pragma unroll
    for (uint k = 0; k < 2 * MAX_FAN; ++k) uses += nb[k] == nb[i];
    open = open || (uses == 1 && i < 2 * fan);
  }
  if (get_global_id(0) < vertex_count) boundary[v] = open && fan <= MAX_FAN;
}

// 1d. The same for the listed vertices with more than MAX_FAN corners.
__kernel void vertex_boundary_large(__global const uint* offsets, __global const uint* corners,
                                    __global const uint* triangles, __global const uint* large,
                                    const uint large_count, __global uchar* boundary) {
  if (get_global_id(0) >= large_count) return;
  const uint v = large[get_global_id(0)], begin = offsets[v], end = offsets[v + 1];
  bool open = false;
  for (uint i = begin; i < end && !open; ++i) {
    uint next, prev;
    corner_neighbours(triangles, corners[i], &next, &prev);
    uint uses_next = 0, uses_prev = 0;
    for (uint k = begin; k < end; ++k) {
      uint a, b;
      corner_neighbours(triangles, corners[k], &a, &b);
      uses_next += (a == next) + (b == next);
      uses_prev += (a == prev) + (b == prev);
    }
    open = uses_next == 1 || uses_prev == 1;
  }
  boundary[v] = open;
}

// 2a. Per face: the second fundamental form by least squares on the normal differences along the
// edges, rotated into each corner's vertex basis and multiplied by the corner's area (xyz), the
// weight itself in w (0 for a degenerate triangle). Reads the areas left by step 1a.
__kernel void corner_tensors(__global const float* positions, __global const uint* triangles,
                             __global const float* normals, const uint face_count,
                             __global float* corner) {
  const uint f = min((uint)get_global_id(0), face_count - 1);
  const uint i0 = triangles[3 * f], i1 = triangles[3 * f + 1], i2 = triangles[3 * f + 2];
  const float w0 = corner[12 * f + 3], w1 = corner[12 * f + 7], w2 = corner[12 * f + 11];
  const vec3 p0 = load3(positions, i0), p1 = load3(positions, i1), p2 = load3(positions, i2);
  const vec3 e0 = sub3(p2, p1), e1 = sub3(p0, p2), e2 = sub3(p1, p0);
  vec3 t, b, m;
  face_frame(e0, e1, &t, &b, &m);
  const vec3 n0 = load3(normals, i0), n1 = load3(normals, i1), n2 = load3(normals, i2);
  // II (u, v) = (dn.t, dn.b) along each edge (u, v) = (e.t, e.b), dn the change of normal.
  const float u0 = dot3(e0, t), v0 = dot3(e0, b), u1 = dot3(e1, t), v1 = dot3(e1, b);
  const float u2 = dot3(e2, t), v2 = dot3(e2, b);
  const vec3 dn0 = sub3(n2, n1), dn1 = sub3(n0, n2), dn2 = sub3(n1, n0);
  const float dnu0 = dot3(dn0, t), dnv0 = dot3(dn0, b), dnu1 = dot3(dn1, t), dnv1 = dot3(dn1, b);
  const float dnu2 = dot3(dn2, t), dnv2 = dot3(dn2, b);
  const tensor2 r = {dnu0 * u0 + dnu1 * u1 + dnu2 * u2,
                     dnu0 * v0 + dnv0 * u0 + dnu1 * v1 + dnv1 * u1 + dnu2 * v2 + dnv2 * u2,
                     dnv0 * v0 + dnv1 * v1 + dnv2 * v2};
  tensor2 k;
  const bool ok = solve_tensor(u0 * u0 + u1 * u1 + u2 * u2, u0 * v0 + u1 * v1 + u2 * v2,
                               v0 * v0 + v1 * v1 + v2 * v2, r, &k) &&
                  !(i0 == i1 || i1 == i2 || i2 == i0) && w0 + w1 + w2 > 0.0f;
  vec3 bu, bv;
  tangent_basis(n0, &bu, &bv);
  const tensor2 k0 = change_tensor(k, vertex_to_face(bu, bv, n0, t, b, m));
  tangent_basis(n1, &bu, &bv);
  const tensor2 k1 = change_tensor(k, vertex_to_face(bu, bv, n1, t, b, m));
  tangent_basis(n2, &bu, &bv);
  const tensor2 k2 = change_tensor(k, vertex_to_face(bu, bv, n2, t, b, m));
  if (get_global_id(0) >= face_count) return;
  // A rejected triangle's arithmetic may hold Inf or NaN: select, never multiply by zero.
  __global float* o = corner + 12 * f;
  o[0] = ok ? w0 * k0.u : 0.0f, o[1] = ok ? w0 * k0.uv : 0.0f, o[2] = ok ? w0 * k0.v : 0.0f;
  o[3] = ok ? w0 : 0.0f;
  o[4] = ok ? w1 * k1.u : 0.0f, o[5] = ok ? w1 * k1.uv : 0.0f, o[6] = ok ? w1 * k1.v : 0.0f;
  o[7] = ok ? w1 : 0.0f;
  o[8] = ok ? w2 * k2.u : 0.0f, o[9] = ok ? w2 * k2.uv : 0.0f, o[10] = ok ? w2 * k2.v : 0.0f;
  o[11] = ok ? w2 : 0.0f;
}

// 2b. Per vertex: the sum of its corner values (the weighted tensors and their weights).
__kernel void vertex_sums(__global const uint* offsets, __global const uint* corners,
                          __global const float4* corner, const uint vertex_count,
                          __global float4* sums) {
  const uint v = get_global_id(0);
  if (v < vertex_count) sums[v] = corner_sum(offsets, corners, corner, v);
}

// 2c. Per vertex: the averaged tensor diagonalised into k1 >= k2 and dir1, dir2 (one Jacobi
// rotation), and everything derived from k1 and k2.
__kernel void vertex_principal(__global const float* sums, __global const float* normals,
                               const uint vertex_count, const float ao_scale,
                               __global float* k1_out, __global float* k2_out,
                               __global float* dir1_out, __global float* dir2_out,
                               __global float* H, __global float* K, __global float* shape,
                               __global float* curved, __global float* ao) {
  const uint v = min((uint)get_global_id(0), vertex_count - 1);
  const float w = sums[4 * v + 3];
  const float ku = w > 0.0f ? sums[4 * v] / w : 0.0f, kuv = w > 0.0f ? sums[4 * v + 1] / w : 0.0f;
  const float kv = w > 0.0f ? sums[4 * v + 2] / w : 0.0f;
  const vec3 n = load3(normals, v);
  vec3 bu, bv;
  tangent_basis(n, &bu, &bv);
  const float h = 0.5f * (kv - ku) / kuv;
  const float tt0 = h < 0.0f ? 1.0f / (h - sqrt(1.0f + h * h)) : 1.0f / (h + sqrt(1.0f + h * h));
  const float tt = kuv != 0.0f ? tt0 : 0.0f;
  const float c = 1.0f / sqrt(1.0f + tt * tt), s = tt * c;
  const float ka = ku - tt * kuv, kb = kv + tt * kuv;
  const bool swap = ka < kb;
  const float k1 = swap ? kb : ka, k2 = swap ? ka : kb;
  const vec3 d1 = swap ? add3(mul3(bu, s), mul3(bv, c)) : sub3(mul3(bu, c), mul3(bv, s));
  if (get_global_id(0) >= vertex_count) return;
  k1_out[v] = k1, k2_out[v] = k2;
  store3(d1, dir1_out, v);
  store3(cross3(n, d1), dir2_out, v);
  H[v] = 0.5f * (k1 + k2), K[v] = k1 * k2;
  shape[v] = shape_index(k1, k2);
  curved[v] = curvedness(k1, k2);
  ao[v] = ambient_occlusion(k1, k2, ao_scale);
}

// 3a. Per face: the curvature-derivative tensor by least squares on the differences of the vertex
// tensors along the edges, rotated into each corner's principal frame, times the corner weight of
// step 2a (still in corner.w; all three are 0 when step 2a rejected the triangle).
__kernel void corner_dcurv(__global const float* positions, __global const uint* triangles,
                           __global const float* k1, __global const float* k2,
                           __global const float* dir1, __global const float* dir2,
                           const uint face_count, __global float* corner) {
  const uint f = min((uint)get_global_id(0), face_count - 1);
  const uint i0 = triangles[3 * f], i1 = triangles[3 * f + 1], i2 = triangles[3 * f + 2];
  const float w0 = corner[12 * f + 3], w1 = corner[12 * f + 7], w2 = corner[12 * f + 11];
  const vec3 p0 = load3(positions, i0), p1 = load3(positions, i1), p2 = load3(positions, i2);
  const vec3 e0 = sub3(p2, p1), e1 = sub3(p0, p2), e2 = sub3(p1, p0);
  vec3 t, b, m;
  face_frame(e0, e1, &t, &b, &m);
  // x_j: vertex j's principal frame in the face frame; fk_j: its tensor in the face frame. The
  // normal is dir1 x dir2, as in the reference.
  const vec3 a0 = load3(dir1, i0), b0 = load3(dir2, i0), a1 = load3(dir1, i1);
  const vec3 b1 = load3(dir2, i1), a2 = load3(dir1, i2), b2 = load3(dir2, i2);
  const frame2 x0 = vertex_to_face(a0, b0, cross3(a0, b0), t, b, m);
  const frame2 x1 = vertex_to_face(a1, b1, cross3(a1, b1), t, b, m);
  const frame2 x2 = vertex_to_face(a2, b2, cross3(a2, b2), t, b, m);
  const tensor2 kv0 = {k1[i0], 0.0f, k2[i0]}, kv1 = {k1[i1], 0.0f, k2[i1]};
  const tensor2 kv2 = {k1[i2], 0.0f, k2[i2]};
  const tensor2 fk0 = change_tensor(kv0, transpose2(x0));
  const tensor2 fk1 = change_tensor(kv1, transpose2(x1));
  const tensor2 fk2 = change_tensor(kv2, transpose2(x2));
  // dII(u, v) = (a u + b v, b u + c v, c u + d v) for C = (a, b, c, d); the kuv row counts
  // twice (it stands for both off-diagonal entries).
  const float u0 = dot3(e0, t), v0 = dot3(e0, b), u1 = dot3(e1, t), v1 = dot3(e1, b);
  const float u2 = dot3(e2, t), v2 = dot3(e2, b);
  const vec3 dk0 = v3(fk2.u - fk1.u, fk2.uv - fk1.uv, fk2.v - fk1.v);
  const vec3 dk1 = v3(fk0.u - fk2.u, fk0.uv - fk2.uv, fk0.v - fk2.v);
  const vec3 dk2 = v3(fk1.u - fk0.u, fk1.uv - fk0.uv, fk1.v - fk0.v);
  const tensor3 r = {
      u0 * dk0.x + u1 * dk1.x + u2 * dk2.x,
      v0 * dk0.x + 2.0f * u0 * dk0.y + v1 * dk1.x + 2.0f * u1 * dk1.y + v2 * dk2.x +
          2.0f * u2 * dk2.y,
      2.0f * v0 * dk0.y + u0 * dk0.z + 2.0f * v1 * dk1.y + u1 * dk1.z + 2.0f * v2 * dk2.y +
          u2 * dk2.z,
      v0 * dk0.z + v1 * dk1.z + v2 * dk2.z};
  tensor3 C;
  const bool ok = solve_derivative(u0 * u0 + u1 * u1 + u2 * u2, u0 * v0 + u1 * v1 + u2 * v2,
                                   v0 * v0 + v1 * v1 + v2 * v2, r, &C) &&
                  w0 + w1 + w2 > 0.0f;
  const tensor3 c0 = change_cubic(C, x0), c1 = change_cubic(C, x1), c2 = change_cubic(C, x2);
  if (get_global_id(0) >= face_count) return;
  __global float* o = corner + 12 * f;  // select, never multiply by zero (see corner_tensors)
  o[0] = ok ? w0 * c0.c0 : 0.0f, o[1] = ok ? w0 * c0.c1 : 0.0f, o[2] = ok ? w0 * c0.c2 : 0.0f;
  o[3] = ok ? w0 * c0.c3 : 0.0f;
  o[4] = ok ? w1 * c1.c0 : 0.0f, o[5] = ok ? w1 * c1.c1 : 0.0f, o[6] = ok ? w1 * c1.c2 : 0.0f;
  o[7] = ok ? w1 * c1.c3 : 0.0f;
  o[8] = ok ? w2 * c2.c0 : 0.0f, o[9] = ok ? w2 * c2.c1 : 0.0f, o[10] = ok ? w2 * c2.c2 : 0.0f;
  o[11] = ok ? w2 * c2.c3 : 0.0f;
}

// 3b. Per vertex: the weighted average of its corner derivatives (weights summed in step 2b).
__kernel void vertex_dcurv(__global const uint* offsets, __global const uint* corners,
                           __global const float4* corner, __global const float4* sums,
                           const uint vertex_count, __global float4* dcurv) {
  const uint v = get_global_id(0);
  if (v >= vertex_count) return;
  const float4 sum = corner_sum(offsets, corners, corner, v);
  const float w = sums[v].w;
  dcurv[v] = w > 0.0f ? sum / w : (float4)(0.0f);
}
