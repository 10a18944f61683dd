// The volume estimator's kernel: one work item per mesh vertex, the float twin of
// volume_estimate_reference (curvature/volume_reference.cpp, volume/gaussian_jet.cpp and
// curvature/implicit_curvature.cpp). Appended to curvature_math.cl; built with -DMAX_TAPS,
// -DGAUSSIAN_RADIUS, -DFIRST_ORDER_RADIUS, -DNEWTON_STEPS, -DON_SURFACE_VOXELS,
// -DMAX_FINAL_STEP_VOXELS and curvature_math.cl's constants.
//
// The samples come as 8^3 bricks (`pool`, x fastest within a brick) found through `table`, a
// dense grid of brick numbers (-1: not gathered) over the gathered region; voxel coordinates are
// relative to the region's first voxel. Dense volumes clamp coordinates to the domain [lo, hi].

// Index-space frame and filter: the world -> index matrix B (row-major), the world position of
// the region's first voxel, and the Gaussian's deviation along each index axis (voxels).
typedef struct {
  float b[9];
  float origin[3];
  float deviation[3];
} frame_t;

// One axis's taps first .. first + count - 1 and their weights, derivative orders 0..3.
typedef struct {
  int first, count;
  float w[4][MAX_TAPS];
} axis_t;

// Gaussian derivative weights at coordinate q for deviation s, each order normalised by its
// discrete moment (volume::axis_weights).
INLINE void axis_weights(float q, float s, float radius, axis_t* a) {
  const float reach = radius * s, s2 = s * s;
  a->first = (int)ceil(q - reach);
  const int last = (int)floor(q + reach);
  a->count = min(last - a->first + 1, MAX_TAPS);
  float m0 = 0.0f, m1 = 0.0f, m2 = 0.0f, m3 = 0.0f;
  for (int t = 0; t < a->count; ++t) {
    const float d = (float)(a->first + t) - q;
    const float g = exp(-d * d / (2.0f * s2));
    a->w[0][t] = g;
    a->w[1][t] = d / s2 * g;
    a->w[2][t] = (d * d / s2 - 1.0f) / s2 * g;
    a->w[3][t] = (d * d / s2 - 3.0f) * d / (s2 * s2) * g;
    m0 += a->w[0][t];
    m1 += a->w[1][t] * d;
    m2 += a->w[2][t] * d * d * 0.5f;
    m3 += a->w[3][t] * d * d * d * (1.0f / 6.0f);
  }
  const float i0 = 1.0f / m0, i1 = 1.0f / m1, i2 = 1.0f / m2, i3 = 1.0f / m3;
  for (int t = 0; t < a->count; ++t) {
    a->w[0][t] *= i0;
    a->w[1][t] *= i1;
    a->w[2][t] *= i2;
    a->w[3][t] *= i3;
  }
}

// The sample at region voxel (x, y, z), clamped to the domain for dense volumes; `background`
// outside the gathered bricks.
typedef struct {
  __global const float* pool;
  __global const int* table;
  int4 dims;  // table size in bricks
  int4 lo, hi;
  int clamp;
  float background;
} samples_t;

INLINE float sample_at(const samples_t* s, int x, int y, int z) {
  if (s->clamp) {
    x = min(max(x, s->lo.x), s->hi.x);
    y = min(max(y, s->lo.y), s->hi.y);
    z = min(max(z, s->lo.z), s->hi.z);
  }
  if (x < 0 || y < 0 || z < 0) return s->background;
  const int bx = x >> 3, by = y >> 3, bz = z >> 3;
  if (bx >= s->dims.x || by >= s->dims.y || bz >= s->dims.z) return s->background;
  const int brick = s->table[(bz * s->dims.y + by) * s->dims.x + bx];
  if (brick < 0) return s->background;
  return s->pool[(size_t)brick * 512 + (((z & 7) * 8 + (y & 7)) * 8 + (x & 7))];
}

// The world-space jet: value, gradient g, Hessian h (xx xy xz yy yz zz), third derivatives t
// (xxx xxy xxz xyy xyz xzz yyy yyz yzz zzz), orders up to `order` (1 or 3).
typedef struct {
  float value;
  float g[3];
  float h[6];
  float t[10];
} jet_t;

INLINE jet_t gaussian_jet(const samples_t* s, const frame_t* f, vec3 p, int order) {
  const vec3 rel = sub3(p, v3(f->origin[0], f->origin[1], f->origin[2]));
  const float q[3] = {f->b[0] * rel.x + f->b[1] * rel.y + f->b[2] * rel.z,
                      f->b[3] * rel.x + f->b[4] * rel.y + f->b[5] * rel.z,
                      f->b[6] * rel.x + f->b[7] * rel.y + f->b[8] * rel.z};
  axis_t ax, ay, az;
  // Orders <= 1 (the Newton steps) reach FIRST_ORDER_RADIUS deviations, the full jet
  // GAUSSIAN_RADIUS (volume::kFirstOrderRadius, volume::kGaussianRadius).
  const float radius = order <= 1 ? (float)FIRST_ORDER_RADIUS : (float)GAUSSIAN_RADIUS;
  axis_weights(q[0], f->deviation[0], radius, &ax);
  axis_weights(q[1], f->deviation[1], radius, &ay);
  axis_weights(q[2], f->deviation[2], radius, &az);
  float d[4][4][4];  // index-space derivatives of orders (nx, ny, nz)
  for (int i = 0; i < 64; ++i) ((float*)d)[i] = 0.0f;
  for (int tz = 0; tz < az.count; ++tz) {
    float dxy[4][4];
    for (int i = 0; i < 16; ++i) ((float*)dxy)[i] = 0.0f;
    for (int ty = 0; ty < ay.count; ++ty) {
      float dx[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      if (order == 1) {  // the Newton steps: value and first derivative only
        for (int tx = 0; tx < ax.count; ++tx) {
          const float v = sample_at(s, ax.first + tx, ay.first + ty, az.first + tz);
          dx[0] += v * ax.w[0][tx];
          dx[1] += v * ax.w[1][tx];
        }
      } else {
        for (int tx = 0; tx < ax.count; ++tx) {
          const float v = sample_at(s, ax.first + tx, ay.first + ty, az.first + tz);
          dx[0] += v * ax.w[0][tx];
          dx[1] += v * ax.w[1][tx];
          dx[2] += v * ax.w[2][tx];
          dx[3] += v * ax.w[3][tx];
        }
      }
      for (int nx = 0; nx <= order; ++nx)
        for (int ny = 0; nx + ny <= order; ++ny) dxy[nx][ny] += dx[nx] * ay.w[ny][ty];
    }
    for (int nx = 0; nx <= order; ++nx)
      for (int ny = 0; nx + ny <= order; ++ny)
        for (int nz = 0; nx + ny + nz <= order; ++nz) d[nx][ny][nz] += dxy[nx][ny] * az.w[nz][tz];
  }
  // To world space: d/dworld_k = sum_a B(a, k) d/dindex_a on each index of each tensor.
  jet_t j;
  j.value = d[0][0][0];
  for (int k = 0; k < 3; ++k)
    j.g[k] = f->b[k] * d[1][0][0] + f->b[3 + k] * d[0][1][0] + f->b[6 + k] * d[0][0][1];
  for (int i = 0; i < 6; ++i) j.h[i] = 0.0f;
  for (int i = 0; i < 10; ++i) j.t[i] = 0.0f;
  if (order < 3) return j;
  const int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  const int triples[10][3] = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0, 1, 1}, {0, 1, 2},
                              {0, 2, 2}, {1, 1, 1}, {1, 1, 2}, {1, 2, 2}, {2, 2, 2}};
  for (int e = 0; e < 6; ++e) {
    const int k = pairs[e][0], l = pairs[e][1];
    float sum = 0.0f;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        int n[3] = {0, 0, 0};
        ++n[a], ++n[b];
        sum += f->b[3 * a + k] * f->b[3 * b + l] * d[n[0]][n[1]][n[2]];
      }
    j.h[e] = sum;
  }
  for (int e = 0; e < 10; ++e) {
    const int k = triples[e][0], l = triples[e][1], m = triples[e][2];
    float sum = 0.0f;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c) {
          int n[3] = {0, 0, 0};
          ++n[a], ++n[b], ++n[c];
          sum += f->b[3 * a + k] * f->b[3 * b + l] * f->b[3 * c + m] * d[n[0]][n[1]][n[2]];
        }
    j.t[e] = sum;
  }
  return j;
}

// The jet's Taylor expansion moved by a small world-space step (volume::shifted_jet).
INLINE jet_t shifted_jet(const jet_t* j, vec3 step) {
  const int pair[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  const int triple[3][3][3] = {{{0, 1, 2}, {1, 3, 4}, {2, 4, 5}},
                               {{1, 3, 4}, {3, 6, 7}, {4, 7, 8}},
                               {{2, 4, 5}, {4, 7, 8}, {5, 8, 9}}};
  const float s[3] = {step.x, step.y, step.z};
  float ts[3][3], hs[3];  // T(., ., s) and H s
  for (int k = 0; k < 3; ++k) {
    hs[k] = 0.0f;
    for (int l = 0; l < 3; ++l) {
      ts[k][l] = 0.0f;
      for (int m = 0; m < 3; ++m) ts[k][l] += j->t[triple[k][l][m]] * s[m];
      hs[k] += j->h[pair[k][l]] * s[l];
    }
  }
  jet_t out = *j;
  for (int k = 0; k < 3; ++k) {
    float tss = 0.0f;
    for (int l = 0; l < 3; ++l) tss += ts[k][l] * s[l];
    out.g[k] += hs[k] + tss * 0.5f;
    out.value += s[k] * (j->g[k] + hs[k] * 0.5f + tss * (1.0f / 6.0f));
  }
  const int pairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  for (int e = 0; e < 6; ++e) out.h[e] += ts[pairs[e][0]][pairs[e][1]];
  return out;
}

// The last Newton step along d on the full jet's Taylor expansion (final_step in
// curvature/volume_reference.cpp); steps over MAX_FINAL_STEP_VOXELS voxels are not taken.
INLINE jet_t final_step(const jet_t* j, vec3 d, float isovalue, float voxel) {
  const float slope = j->g[0] * d.x + j->g[1] * d.y + j->g[2] * d.z;
  if (!(fabs(slope) > 0.0f)) return *j;
  const float t = -(j->value - isovalue) / slope;
  if (!(fabs(t) <= (float)MAX_FINAL_STEP_VOXELS * voxel)) return *j;
  return shifted_jet(j, mul3(d, t));
}

// Hs x for the symmetric Hessian (xx xy xz yy yz zz).
INLINE vec3 hess_mul(const float* h, vec3 x) {
  return v3(h[0] * x.x + h[1] * x.y + h[2] * x.z, h[1] * x.x + h[3] * x.y + h[4] * x.z,
            h[2] * x.x + h[4] * x.y + h[5] * x.z);
}

// T(a, b, c) for the symmetric 3-tensor (xxx xxy xxz xyy xyz xzz yyy yyz yzz zzz).
INLINE float cubic3(const float* t, vec3 a, vec3 b, vec3 c) {
  const int index[27] = {0, 1, 2, 1, 3, 4, 2, 4, 5, 1, 3, 4, 3, 6, 7, 4, 7, 8, 2, 4, 5, 4, 7, 8, 5, 8, 9};
  const float av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z}, cv[3] = {c.x, c.y, c.z};
  float sum = 0.0f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) sum += t[index[9 * i + 3 * j + k]] * av[i] * bv[j] * cv[k];
  return sum;
}

// C(a, b, c) of implicit_curvature: s/|g| [T(a,b,c) - ((a.Hs c)(m.Hs b) + (b.Hs c)(m.Hs a) +
// (a.Hs b)(m.Hs c)) / |g|], Hm = Hs m.
INLINE float dcurv_form(const jet_t* j, vec3 hm, float s, float len, vec3 a, vec3 b, vec3 c) {
  const float quad = (dot3(a, hess_mul(j->h, c)) * dot3(hm, b) +
                      dot3(b, hess_mul(j->h, c)) * dot3(hm, a) +
                      dot3(a, hess_mul(j->h, b)) * dot3(hm, c)) / len;
  return s / len * (cubic3(j->t, a, b, c) - quad);
}

__kernel void volume_curvature(__global const float* positions, uint count,
                               __global const float* pool, __global const int* table, int4 dims,
                               int4 lo, int4 hi, int clamp_domain, float background,
                               __constant const float* frame_params, float isovalue, float sign,
                               float max_shift, float voxel, float ao_scale,
                               __global float* normals, __global float* k1_out,
                               __global float* k2_out, __global float* dir1_out,
                               __global float* dir2_out, __global float* H_out,
                               __global float* K_out, __global float4* dcurv_out,
                               __global float* shape_out, __global float* curved_out,
                               __global float* ao_out, __global float* gnorm_out,
                               __global uchar* missed_out) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  const samples_t s = {pool, table, dims, lo, hi, clamp_domain, background};
  frame_t f;
  for (int k = 0; k < 9; ++k) f.b[k] = frame_params[k];
  for (int k = 0; k < 3; ++k) f.origin[k] = frame_params[9 + k], f.deviation[k] = frame_params[12 + k];

  const vec3 x0 = load3(positions, i);
  const jet_t j0 = gaussian_jet(&s, &f, x0, 1);
  const vec3 g0 = v3(j0.g[0], j0.g[1], j0.g[2]);
  const float g0len = sqrt(dot3(g0, g0));
  vec3 n = v3(0.0f, 0.0f, 0.0f), e1 = n, e2 = n;
  float k1 = 0.0f, k2 = 0.0f, len = 0.0f;
  float4 dc = (float4)(0.0f);
  uchar missed = 1;
  if (g0len > 0.0f && finite(g0len)) {
    // Newton steps along the gradient line x0 + t d to the reconstructed isosurface.
    const vec3 d = mul3(g0, 1.0f / g0len);
    float t = 0.0f;
    jet_t j = j0;
    for (int step = 0; step < NEWTON_STEPS; ++step) {
      if (step > 0) j = gaussian_jet(&s, &f, add3(x0, mul3(d, t)), 1);
      const float slope = j.g[0] * d.x + j.g[1] * d.y + j.g[2] * d.z;
      if (!(fabs(slope) > 0.0f)) break;
      t = clamp(t - (j.value - isovalue) / slope, -max_shift, max_shift);
    }
    const jet_t found = gaussian_jet(&s, &f, add3(x0, mul3(d, t)), 3);
    const jet_t jet = final_step(&found, d, isovalue, voxel);
    const vec3 g = v3(jet.g[0], jet.g[1], jet.g[2]);
    len = sqrt(dot3(g, g));
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
      const vec3 hm = hess_mul(jet.h, m);
      dc = (float4)(dcurv_form(&jet, hm, sign, len, e1, e1, e1),
                    dcurv_form(&jet, hm, sign, len, e1, e1, e2),
                    dcurv_form(&jet, hm, sign, len, e1, e2, e2),
                    dcurv_form(&jet, hm, sign, len, e2, e2, e2));
      missed = !(fabs(found.value - isovalue) <= (float)ON_SURFACE_VOXELS * voxel * len);
    } else {
      len = 0.0f;
    }
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
  missed_out[i] = missed;
}
