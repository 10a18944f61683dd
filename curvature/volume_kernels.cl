// The volume estimator's kernels, the float twins of volume_estimate_reference
// (curvature/volume_reference.cpp, volume/prefilter.cpp, volume/spline_jet.cpp and
// curvature/implicit_curvature.cpp): smooth_axis, three times (one pass of the separable
// prefilter per axis, one work item per voxel of the bricks the next pass reads), then
// volume_curvature (one work item per mesh vertex, reading 5^3 smoothed samples).
// Built from curvature/detail/volume_layout.h (the brick layout and VolumeParams, shared with the
// host), curvature_math.cl and this file, in that order, with -DNEWTON_STEPS, -DSURFACE_Y1,
// -DSURFACE_Y2, -DMIN_CORRECTION and curvature_math.cl's constants from their C++ definitions.

// The index-space frame and the scalars of one evaluation: VolumeParams (volume_layout.h), copied
// from __constant memory into each work item's private memory.
typedef VolumeParams frame_t;

// The orders (nx, ny, nz) of the distinct second and third index-space derivatives, in the order
// of the Hessian (xx xy xz yy yz zz) and third-derivative (xxx xxy ... zzz) components.
__constant int PAIR_ORDERS[6][3] = {{2, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};
__constant int TRIPLE_ORDERS[10][3] = {{3, 0, 0}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0}, {1, 1, 1},
                                       {1, 0, 2}, {0, 3, 0}, {0, 2, 1}, {0, 1, 2}, {0, 0, 3}};

// Samples in 8^3 bricks (x fastest within a brick) found through `table`, a dense grid of brick
// numbers (-1: not in the set) over the region; voxel coordinates relative to the region's first
// voxel.
typedef struct {
  __global const float* pool;
  __global const int* table;
  int4 dims;  // table size in bricks
} samples_t;

// The number of brick (bx, by, bz) (region brick coordinates), -1 where there is none.
INLINE int brick_number(const samples_t* s, int bx, int by, int bz) {
  if (bx < 0 || by < 0 || bz < 0 || bx >= s->dims.x || by >= s->dims.y || bz >= s->dims.z)
    return -1;
  return s->table[(bz * s->dims.y + by) * s->dims.x + bx];
}

// Input sample p of a row (value v) added to the row's 8 outputs through its 8 weights in
// `spread` (see smooth_axis), into one of two accumulators by the parity of p.
INLINE void spread_sample(float v, int p, __constant const float* spread, int last_weight,
                          float8* even, float8* odd) {
  const float8 w = vload8(0, spread + last_weight - p);
  if (p & 1) *odd += v * w;
  else *even += v * w;
}

// One pass of the separable prefilter along `axis` (volume::smooth_reference): voxel v of an
// output brick (region brick coordinates out_bricks[b]) gets sum_k taps[k + radius] in(v + k e)
// (taps as `spread` holds them, below),
// e the unit step along the axis, the coordinate along the axis clamped to [lo, hi] when
// clamp_axis (a dense volume's domain). One work item per row of 8 voxels along the axis (64
// rows per brick): it reads the row's 8 + 2 radius input samples once, looking up a brick only
// when the row enters it.
__kernel void smooth_axis(__global const float* in_pool, __global const int* in_table, int4 dims,
                          float background, __global const int4* out_bricks, uint out_count,
                          __global float* out_pool, int axis, int clamp_axis, int lo, int hi,
                          __constant const float* spread, int radius) {
  const uint item = get_global_id(0);
  if (item >= out_count * BRICK_ROWS) return;
  const uint b = item / BRICK_ROWS, row = item % BRICK_ROWS;
  const int4 brick = out_bricks[b];
  // The row's other two local coordinates, and the strides of the axis in a brick and the table.
  const int u = (int)(row & 7), w = (int)(row >> 3);
  int at[3], start[3] = {brick.x * 8, brick.y * 8, brick.z * 8};
  at[axis] = 0;
  at[axis == 0 ? 1 : 0] = u;
  at[axis == 2 ? 1 : 2] = w;
  const int stride = axis == 0 ? 1 : (axis == 1 ? 8 : 64);
  const int table_stride = axis == 0 ? 1 : (axis == 1 ? dims.x : dims.x * dims.y);
  const int extent = axis == 0 ? dims.x : (axis == 1 ? dims.y : dims.z);
  const int row_offset = (at[2] * 8 + at[1]) * 8 + at[0];
  int cell = 0;  // the table cell of the output brick with its coordinate along the axis zeroed
  {
    int bc[3] = {brick.x, brick.y, brick.z};
    bc[axis] = 0;
    cell = (bc[2] * dims.y + bc[1]) * dims.x + bc[0];
  }
  // Each input sample p of the row (0 .. 8 + 2 radius - 1) adds to all 8 outputs at once:
  // out[k] += in[p] taps[p - k], the weights of sample p being 8 consecutive entries of
  // `spread` (the taps reversed, with 7 zeros either side: spread[L - 8 - p + k] = taps[p - k],
  // L = 2 radius + 15). Two accumulators halve the chain of dependent FMAs.
  const int from = start[axis] - radius, to = start[axis] + 7 + radius, last_weight = 2 * radius + 7;
  float8 even = (float8)(0.0f), odd = (float8)(0.0f);
  int p = 0;
  if (clamp_axis && (from < lo || to > hi)) {
    // Near the domain's border: clamp every coordinate.
    int current = -1, number = -1;
    for (; p < 8 + 2 * radius; ++p) {
      const int c = clamp(from + p, lo, hi), cb = c >> 3;
      if (cb != current) {
        current = cb;
        number = c >= 0 && cb < extent ? in_table[cell + cb * table_stride] : -1;
      }
      const float v = number < 0 ? background
                                 : in_pool[(size_t)number * BRICK_VOXELS + row_offset + (c & 7) * stride];
      spread_sample(v, p, spread, last_weight, &even, &odd);
    }
  } else {
    // Brick by brick: one lookup, then the row's part in that brick.
    for (int cb = from >> 3; cb <= to >> 3; ++cb) {
      const int number = cb >= 0 && cb < extent ? in_table[cell + cb * table_stride] : -1;
      const int first = max(from - cb * 8, 0), last = min(to - cb * 8, 7);
      __global const float* src = in_pool + (size_t)max(number, 0) * BRICK_VOXELS + row_offset;
      for (int l = first; l <= last; ++l, ++p) {
        const float v = number < 0 ? background : src[l * stride];
        spread_sample(v, p, spread, last_weight, &even, &odd);
      }
    }
  }
  const float8 sum = even + odd;
  __global float* out = out_pool + (size_t)b * BRICK_VOXELS + row_offset;
  if (stride == 1) {
    vstore8(sum, 0, out);
  } else {
    const float values[8] = {sum.s0, sum.s1, sum.s2, sum.s3, sum.s4, sum.s5, sum.s6, sum.s7};
    for (int k = 0; k < 8; ++k) out[k * stride] = values[k];
  }
}

// The smoothed samples copied into padded blocks for the per-vertex kernel: block b holds the
// PADDED^3 voxels from 8 brick - PAD_BEFORE on of stage brick b, so that every tap of an
// evaluation whose cell lies in brick b comes from block b at a fixed offset (no brick lookups
// per tap). Voxels outside the stage's bricks (never read: every tap lies in the stage) get
// `background`. One work item per row of PADDED voxels along x.
__kernel void pad_bricks(__global const float* pool, __global const int* table, int4 dims,
                         float background, __global const int4* bricks, uint count,
                         __global float* blocks) {
  const uint item = get_global_id(0);
  if (item >= count * PADDED * PADDED) return;
  const samples_t s = {pool, table, dims};
  const uint b = item / (PADDED * PADDED), r = item % (PADDED * PADDED);
  const int4 brick = bricks[b];
  const int y = brick.y * 8 - PAD_BEFORE + (int)(r % PADDED);
  const int z = brick.z * 8 - PAD_BEFORE + (int)(r / PADDED);
  const int row = ((z & 7) * 8 + (y & 7)) * 8;
  __global float* out = blocks + (size_t)item * PADDED;
  // The row's three parts: PAD_BEFORE voxels from the brick before, the brick's own 8, and the
  // rest from the brick after.
  const bool inside = y >= 0 && z >= 0;
  const int before = inside ? brick_number(&s, brick.x - 1, y >> 3, z >> 3) : -1;
  const int own = inside ? brick_number(&s, brick.x, y >> 3, z >> 3) : -1;
  const int after = inside ? brick_number(&s, brick.x + 1, y >> 3, z >> 3) : -1;
  for (int i = 0; i < PAD_BEFORE; ++i)
    out[i] = before < 0 ? background : pool[(size_t)before * BRICK_VOXELS + row + 8 - PAD_BEFORE + i];
  if (own < 0) {
    for (int i = 0; i < 8; ++i) out[PAD_BEFORE + i] = background;
  } else {
    vstore8(vload8(0, pool + (size_t)own * BRICK_VOXELS + row), 0, out + PAD_BEFORE);
  }
  for (int i = 0; i < PADDED - 8 - PAD_BEFORE; ++i)
    out[PAD_BEFORE + 8 + i] = after < 0 ? background : pool[(size_t)after * BRICK_VOXELS + row + i];
}

// The quartic B-spline's weights along one axis at q (volume::spline_weights): taps first ..
// first + 4, w[n][t] the n-th derivative of beta4(q - first - t).
typedef struct {
  int first;
  float w[4][SPLINE_TAPS];
} axis_t;

// The weights as polynomials in u = frac(q + 2.5): tap t's weight is M4(u + 4 - t), whose pieces
// are 24 M4(u + j) = 1 + 4u + 6u^2 + 4u^3 - 4u^4 (j = 1), 11 + 12u - 6u^2 - 12u^3 + 6u^4 (j = 2),
// 11 - 12u - 6u^2 + 12u^3 - 4u^4 (j = 3), (1 - u)^4 (j = 4) and u^4 (j = 0): the same values as
// volume::spline_weights's recursion. SPLINE_U[k] holds the u^k coefficients of taps 0..4 in
// lanes 0..4; the derivatives in q are those in u.
__constant float8 SPLINE_U[5] = {
    (float8)(1.0f, 11.0f, 11.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f) / 24.0f,
    (float8)(-4.0f, -12.0f, 12.0f, 4.0f, 0.0f, 0.0f, 0.0f, 0.0f) / 24.0f,
    (float8)(6.0f, -6.0f, -6.0f, 6.0f, 0.0f, 0.0f, 0.0f, 0.0f) / 24.0f,
    (float8)(-4.0f, 12.0f, -12.0f, 4.0f, 0.0f, 0.0f, 0.0f, 0.0f) / 24.0f,
    (float8)(1.0f, -4.0f, 6.0f, -4.0f, 1.0f, 0.0f, 0.0f, 0.0f) / 24.0f};

INLINE void spline_weights(float q, axis_t* a) {
  const float x = q + 2.5f, base = floor(x), u = x - base;
  const __constant float8* c = SPLINE_U;
  const float8 w0 = (((c[4] * u + c[3]) * u + c[2]) * u + c[1]) * u + c[0];
  const float8 w1 = ((4.0f * c[4] * u + 3.0f * c[3]) * u + 2.0f * c[2]) * u + c[1];
  const float8 w2 = (12.0f * c[4] * u + 6.0f * c[3]) * u + 2.0f * c[2];
  const float8 w3 = 24.0f * c[4] * u + 6.0f * c[3];
  a->first = (int)base - (SPLINE_TAPS - 1);
  const float8 w[4] = {w0, w1, w2, w3};
  #pragma unroll
  for (int n = 0; n < 4; ++n) {
    a->w[n][0] = w[n].s0;
    a->w[n][1] = w[n].s1;
    a->w[n][2] = w[n].s2;
    a->w[n][3] = w[n].s3;
    a->w[n][4] = w[n].s4;
  }
}

// The world-space jet: value, gradient g, Hessian h (xx xy xz yy yz zz), third derivatives t
// (xxx xxy xxz xyy xyz xzz yyy yyz yzz zzz), orders up to `order` (1 or 3).
typedef struct {
  float value;
  float g[3];
  float h[6];
  float t[10];
} jet_t;

// The jet of the reconstructed field sum_i S_i beta4(q - i) at world point p
// (volume::spline_jet), S the smoothed samples.
INLINE jet_t spline_jet(const samples_t* s, __global const float* blocks, const frame_t* f, vec3 p,
                        int order) {
  const vec3 rel = sub3(p, v3(f->origin[0], f->origin[1], f->origin[2]));
  // Index positions from the anchor: the weights come from these (their rounding the same
  // whatever region the call covers), the taps then shift to the region by whole numbers.
  const float q[3] = {f->b[0] * rel.x + f->b[1] * rel.y + f->b[2] * rel.z,
                      f->b[3] * rel.x + f->b[4] * rel.y + f->b[5] * rel.z,
                      f->b[6] * rel.x + f->b[7] * rel.y + f->b[8] * rel.z};
  const int fx = (int)f->first[0], fy = (int)f->first[1], fz = (int)f->first[2];
  axis_t ax, ay, az;
  spline_weights(q[0], &ax);
  spline_weights(q[1], &ay);
  spline_weights(q[2], &az);
  ax.first -= fx, ay.first -= fy, az.first -= fz;
  // The block of the brick holding the evaluation's cell floor(q): it holds all 5^3 taps, the
  // tap (tx, ty, tz) at a constant offset from the first.
  const int cx = (int)floor(q[0]) - fx, cy = (int)floor(q[1]) - fy, cz = (int)floor(q[2]) - fz;
  const int block = brick_number(s, cx >> 3, cy >> 3, cz >> 3);
  if (block < 0) {  // outside the smoothed bricks (a plan never lets that happen)
    jet_t none = {0};
    return none;
  }
  __global const float* first =
      blocks + (size_t)block * PADDED_VOXELS +
      ((az.first - (cz & ~7) + PAD_BEFORE) * PADDED + (ay.first - (cy & ~7) + PAD_BEFORE)) * PADDED +
      (ax.first - (cx & ~7) + PAD_BEFORE);
  // d[nx][ny][nz]: the index-space derivative of orders (nx, ny, nz), nx + ny + nz <= order, by
  // separable sums: along x within each row, then y, then z. The x orders ride in the lanes of a
  // float4 (lane nx): a row's sum is five vector FMAs. Every loop has a constant trip count and
  // `order` is a constant where this is inlined, so the sums unroll into straight code.
  float4 wx[SPLINE_TAPS];
  #pragma unroll
  for (int t = 0; t < SPLINE_TAPS; ++t)
    wx[t] = (float4)(ax.w[0][t], ax.w[1][t], ax.w[2][t], ax.w[3][t]);
  float4 dyz[4][4];  // [ny][nz], lanes nx
  #pragma unroll
  for (int ny = 0; ny < 4; ++ny)
    #pragma unroll
    for (int nz = 0; nz < 4; ++nz) dyz[ny][nz] = (float4)(0.0f);
  #pragma unroll
  for (int tz = 0; tz < SPLINE_TAPS; ++tz) {
    float4 dy4[4];  // [ny], lanes nx
    #pragma unroll
    for (int ny = 0; ny < 4; ++ny) dy4[ny] = (float4)(0.0f);
    #pragma unroll
    for (int ty = 0; ty < SPLINE_TAPS; ++ty) {
      __global const float* row = first + (tz * PADDED + ty) * PADDED;
      float4 dx = (float4)(0.0f);
      #pragma unroll
      for (int tx = 0; tx < SPLINE_TAPS; ++tx) dx += row[tx] * wx[tx];
      #pragma unroll
      for (int ny = 0; ny < 4; ++ny)
        if (ny <= order) dy4[ny] += dx * ay.w[ny][ty];
    }
    #pragma unroll
    for (int ny = 0; ny < 4; ++ny)
      #pragma unroll
      for (int nz = 0; nz < 4; ++nz)
        if (ny + nz <= order) dyz[ny][nz] += dy4[ny] * az.w[nz][tz];
  }
  float d[4][4][4];
  #pragma unroll
  for (int ny = 0; ny < 4; ++ny)
    #pragma unroll
    for (int nz = 0; nz < 4; ++nz) {
      d[0][ny][nz] = dyz[ny][nz].s0;
      d[1][ny][nz] = dyz[ny][nz].s1;
      d[2][ny][nz] = dyz[ny][nz].s2;
      d[3][ny][nz] = dyz[ny][nz].s3;
    }
  // To world space: d/dworld_k = sum_a B(a, k) d/dindex_a on each index of each tensor, the
  // products of B precomputed per order (frame_t).
  jet_t j;
  j.value = d[0][0][0];
  #pragma unroll
  for (int k = 0; k < 3; ++k)
    j.g[k] = f->b[k] * d[1][0][0] + f->b[3 + k] * d[0][1][0] + f->b[6 + k] * d[0][0][1];
  #pragma unroll
  for (int i = 0; i < 6; ++i) j.h[i] = 0.0f;
  #pragma unroll
  for (int i = 0; i < 10; ++i) j.t[i] = 0.0f;
  if (order < 3) return j;
  #pragma unroll
  for (int e = 0; e < 6; ++e)
    #pragma unroll
    for (int g = 0; g < 6; ++g)
      j.h[e] += f->m2[e][g] * d[PAIR_ORDERS[g][0]][PAIR_ORDERS[g][1]][PAIR_ORDERS[g][2]];
  #pragma unroll
  for (int e = 0; e < 10; ++e)
    #pragma unroll
    for (int g = 0; g < 10; ++g)
      j.t[e] += f->m3[e][g] * d[TRIPLE_ORDERS[g][0]][TRIPLE_ORDERS[g][1]][TRIPLE_ORDERS[g][2]];
  return j;
}

// Hs x for the symmetric Hessian (xx xy xz yy yz zz).
INLINE vec3 hess_mul(const float* h, vec3 x) {
  return v3(h[0] * x.x + h[1] * x.y + h[2] * x.z, h[1] * x.x + h[3] * x.y + h[4] * x.z,
            h[2] * x.x + h[4] * x.y + h[5] * x.z);
}

// T(., ., c) for the symmetric 3-tensor t (xxx xxy xxz xyy xyz xzz yyy yyz yzz zzz): a
// symmetric 3x3 in the Hessian's storage (xx xy xz yy yz zz).
INLINE void contract3(const float* t, vec3 c, float* m) {
  m[0] = t[0] * c.x + t[1] * c.y + t[2] * c.z;
  m[1] = t[1] * c.x + t[3] * c.y + t[4] * c.z;
  m[2] = t[2] * c.x + t[4] * c.y + t[5] * c.z;
  m[3] = t[3] * c.x + t[6] * c.y + t[7] * c.z;
  m[4] = t[4] * c.x + t[7] * c.y + t[8] * c.z;
  m[5] = t[5] * c.x + t[8] * c.y + t[9] * c.z;
}

// dcurv in the principal frame: C(a, b, c) of implicit_curvature,
// s/|g| [T(a,b,c) - ((a.Hs c)(m.Hs b) + (b.Hs c)(m.Hs a) + (a.Hs b)(m.Hs c)) / |g|], for
// (e1,e1,e1), (e1,e1,e2), (e1,e2,e2), (e2,e2,e2).
INLINE float4 dcurv_forms(const jet_t* j, vec3 m, float s, float len, vec3 e1, vec3 e2) {
  float t1[6], t2[6];  // T(., ., e1), T(., ., e2)
  contract3(j->t, e1, t1);
  contract3(j->t, e2, t2);
  const vec3 he1 = hess_mul(j->h, e1), he2 = hess_mul(j->h, e2), hm = hess_mul(j->h, m);
  const float h11 = dot3(e1, he1), h12 = dot3(e1, he2), h22 = dot3(e2, he2);
  const float m1 = dot3(hm, e1), m2 = dot3(hm, e2);
  const float4 t = (float4)(dot3(e1, hess_mul(t1, e1)), dot3(e1, hess_mul(t2, e1)),
                            dot3(e1, hess_mul(t2, e2)), dot3(e2, hess_mul(t2, e2)));
  const float4 quad = (float4)(3.0f * h11 * m1, 2.0f * h12 * m1 + h11 * m2,
                               2.0f * h12 * m2 + h22 * m1, 3.0f * h22 * m2);
  return s / len * (t - quad / len);
}

// One work item per vertex: the curvature of the smoothed field's level set through the vertex,
// or (surface) through the point where its gradient line meets the smoothed isosurface, moved out
// by the smoothing's shrinkage sigma2 H (evaluate_reference in curvature/volume_reference.cpp);
// shift_out the signed distance from the vertex to the smoothed isosurface along the gradient
// (INFINITY where the gradient vanished); surface_out (surface) that parallel surface's point
// (CurvatureField::surface_points), else the vertex.
__kernel void volume_curvature(__global const float* positions, uint count,
                               __global const float* blocks, __global const int* table, int4 dims,
                               __constant const VolumeParams* params,
                               __global float* normals, __global float* k1_out,
                               __global float* k2_out, __global float* dir1_out,
                               __global float* dir2_out, __global float* H_out,
                               __global float* K_out, __global float4* dcurv_out,
                               __global float* shape_out, __global float* curved_out,
                               __global float* ao_out, __global float* gnorm_out,
                               __global float* shift_out, __global float* surface_out) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  const samples_t s = {0, table, dims};
  const frame_t f = *params;
  const float isovalue = f.isovalue, sign = f.sign, ao_scale = f.ao_scale;
  const float max_shift = f.max_shift, sigma2 = f.sigma2;
  const int surface = f.surface;

  const vec3 x0 = load3(positions, i);
  vec3 x = x0;
  float t = 0.0f;
  if (surface) {  // Newton steps along the gradient line x0 + t d to the smoothed isosurface
    const jet_t j0 = spline_jet(&s, blocks, &f, x0, 1);
    const vec3 g0 = v3(j0.g[0], j0.g[1], j0.g[2]);
    const float g0len = sqrt(dot3(g0, g0));
    if (g0len > 0.0f && finite(g0len)) {
      const vec3 d = mul3(g0, 1.0f / g0len);
      jet_t j = j0;
      for (int step = 0; step < NEWTON_STEPS; ++step) {
        if (step > 0) j = spline_jet(&s, blocks, &f, add3(x0, mul3(d, t)), 1);
        const float slope = j.g[0] * d.x + j.g[1] * d.y + j.g[2] * d.z;
        if (!(fabs(slope) > 0.0f)) break;
        t = clamp(t - (j.value - isovalue) / slope, -max_shift, max_shift);
      }
      x = add3(x0, mul3(d, t));
    }
  }
  vec3 surface_point = x0;  // (surface) the point measure::object_measures integrates over
  const jet_t jet = spline_jet(&s, blocks, &f, x, 3);
  const vec3 g = v3(jet.g[0], jet.g[1], jet.g[2]);
  float len = sqrt(dot3(g, g));
  vec3 n = v3(0.0f, 0.0f, 0.0f), e1 = n, e2 = n;
  float k1 = 0.0f, k2 = 0.0f, shift = INFINITY;
  float4 dc = (float4)(0.0f);
  if (len > 0.0f && finite(len)) {
    const vec3 m = mul3(g, 1.0f / len);
    n = mul3(m, sign);
    vec3 u, v;
    tangent_basis(n, &u, &v);
    const float a = sign * dot3(u, hess_mul(jet.h, u)) / len;
    const float b = sign * dot3(u, hess_mul(jet.h, v)) / len;
    const float c = sign * dot3(v, hess_mul(jet.h, v)) / len;
    const float mean = 0.5f * (a + c), diff = 0.5f * (a - c), r = sqrt(diff * diff + b * b);
    const float theta = 0.5f * atan2(2.0f * b, a - c);
    k1 = mean + r;
    k2 = mean - r;
    e1 = add3(mul3(u, cos(theta)), mul3(v, sin(theta)));
    e2 = cross3(n, e1);
    dc = dcurv_forms(&jet, m, sign, len, e1, e2);
    shift = (jet.value - isovalue) / len - t;
    if (surface) {  // shrinkage_corrected: the parallel surface e further out (volume_estimate.h)
      const float h = 0.5f * (k1 + k2);
      const float y = sigma2 * h * h;
      const float e = sigma2 * h * fmax(1.0f - SURFACE_Y1 * y + SURFACE_Y2 * y * y, 0.5f);
      surface_point = add3(x, mul3(n, e));  // that parallel surface's point
      if (fmin(1.0f + e * k1, 1.0f + e * k2) < MIN_CORRECTION) shift = INFINITY;
      k1 /= fmax(1.0f + e * k1, 0.1f);
      k2 /= fmax(1.0f + e * k2, 0.1f);
    }
  } else {
    len = 0.0f;
  }
  store3(n, normals, i);
  k1_out[i] = k1;
  k2_out[i] = k2;
  store3(e1, dir1_out, i);
  store3(e2, dir2_out, i);
  H_out[i] = 0.5f * (k1 + k2);
  K_out[i] = k1 * k2;
  dcurv_out[i] = dc;
  shape_out[i] = shape_index(k1, k2);
  curved_out[i] = curvedness(k1, k2);
  ao_out[i] = ambient_occlusion(k1, k2, ao_scale);
  gnorm_out[i] = len;
  shift_out[i] = shift;
  store3(surface_point, surface_out, i);
}
