// Screen-space curvature on the device: the isosurface ray caster that fills a G-buffer from a
// volume (screen/ray_cast.cpp is its reference), and the per-pixel estimators on a G-buffer:
// Prantl et al.'s per-triangle shape operator on pixel triangles with LOD and the
// depth-discontinuity rule, and Mellado et al.'s screen-space sphere fit
// (screen/estimate.cpp is their reference). One work item per pixel; no atomics: deterministic.
// Build options: -DPIVOT_TOLERANCE=... -DBRICK=8. Prepended: volume/dense_field.cl (Grid, the
// trilinear field and gradient normals, affine maps).

// ---------------------------------------------------------------- ray caster

bool brick_straddles(__global const float2* range, const Grid* g, int b) {
  const float2 r = range[b];
  if (!(r.x <= r.y)) return false;
  return g->sign > 0.0f ? (r.y > g->iso && r.x <= g->iso) : (r.x < g->iso && r.y >= g->iso);
}

// One ray per pixel: march from where it enters the clip box (the straddling bricks' box,
// DenseField::straddling_box: no crossing lies outside it) at `step` voxels (along the ray's
// longest index axis), jumping over bricks without surface (not sampled: the field is sampled
// again where the ray enters a brick that straddles) and, with safe_stride, by 0.9 |s| /
// (slope |d|_1) where that is longer (slopes: DenseField::brick_slope), to the first sample
// inside (signed value > 0) after one outside; bisect that step `bisections` times; the hit is
// the secant point of the last interval (secant) or its midpoint. xform: to_index (12), to_world (12), normal_matrix (9).
// cam: eye, forward, right, up (xyz each), half_height, ortho, then 2 unused.
__kernel void ray_cast(__global const float* values, __global const float2* bricks,
                       __global const float* slopes, const int4 dims, const int4 bdims,
                       const float4 clip_lo, const float4 clip_hi, const float iso, const float sign, __constant const float* xform,
                       __constant const float* cam, const int width, const int height,
                       const float step, const int bisections, const int safe_stride,
                       const int secant, __global float4* out_position, __global float4* out_normal,
                       __global float* out_depth) {
  const int id = get_global_id(0);
  if (id >= width * height) return;
  Grid g = {dims.x, dims.y, dims.z, bdims.x, bdims.y, bdims.z, iso, sign, dims.w};
  const int px = id % width, py = id / width;
  const float3 eye = (float3)(cam[0], cam[1], cam[2]), fwd = (float3)(cam[3], cam[4], cam[5]);
  const float3 right = (float3)(cam[6], cam[7], cam[8]), up = (float3)(cam[9], cam[10], cam[11]);
  const float hh = cam[12];
  const bool ortho = cam[13] != 0.0f;
  const float aspect = (float)width / height;
  const float sx = (((px + 0.5f) / width) * 2 - 1) * aspect * hh;
  const float sy = (((py + 0.5f) / height) * 2 - 1) * hh;
  float3 o, d;
  if (ortho) {
    o = eye + sx * right + sy * up;
    d = fwd;
  } else {
    o = eye;
    d = normalize(fwd + sx * right + sy * up);
  }
  out_position[id] = (float4)(0.0f);
  out_normal[id] = (float4)(0.0f);
  out_depth[id] = 0.0f;
  const float3 oi = affine(xform, o), di = linear3(xform, 4, d);
  // Slab clip against the clip box (index space).
  float t0 = 0.0f, t1 = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const float oa = a == 0 ? oi.x : a == 1 ? oi.y : oi.z;
    const float da = a == 0 ? di.x : a == 1 ? di.y : di.z;
    const float la = a == 0 ? clip_lo.x : a == 1 ? clip_lo.y : clip_lo.z;
    const float ha = a == 0 ? clip_hi.x : a == 1 ? clip_hi.y : clip_hi.z;
    if (da == 0.0f) {
      if (oa < la || oa > ha) t1 = -1.0f;
    } else {
      float ta = (la - oa) / da, tb = (ha - oa) / da;
      if (ta > tb) { const float s = ta; ta = tb; tb = s; }
      t0 = fmax(t0, ta), t1 = fmin(t1, tb);
    }
  }
  if (!(t1 > t0)) return;
  const float3 base = oi + t0 * di;
  const float tl = t1 - t0;
  const float dmax = fmax(fabs(di.x), fmax(fabs(di.y), fabs(di.z)));
  const float dt = step / dmax;
  const float3 inv = (float3)(di.x != 0.0f ? 1.0f / di.x : INFINITY,
                              di.y != 0.0f ? 1.0f / di.y : INFINITY,
                              di.z != 0.0f ? 1.0f / di.z : INFINITY);
  const float l1 = fabs(di.x) + fabs(di.y) + fabs(di.z);
  float t = 0.0f, s_prev = field_at(values, &g, base);
  bool known = true;  // s_prev is the field at t (false after a jump over a brick)
  bool hit = false;
  float a = 0.0f, b = 0.0f, fa = 0.0f, fb = 0.0f;
  while (t < tl) {
    const float3 p = base + t * di;
    const int3 bc = clamp(convert_int3(floor(p / BRICK)), (int3)(0),
                          (int3)(bdims.x - 1, bdims.y - 1, bdims.z - 1));
    const int bi = bc.x + bdims.x * (bc.y + bdims.y * bc.z);
    const float3 lo = convert_float3(bc) * BRICK, up3 = lo + BRICK;
    const float3 ex = (float3)(di.x > 0 ? up3.x : lo.x, di.y > 0 ? up3.y : lo.y,
                               di.z > 0 ? up3.z : lo.z);
    const float3 te3 = (ex - base) * inv;
    const float te = fmin(di.x != 0.0f ? te3.x : INFINITY,
                          fmin(di.y != 0.0f ? te3.y : INFINITY, di.z != 0.0f ? te3.z : INFINITY));
    float tn = t + dt;
    if (!brick_straddles(bricks, &g, bi)) {  // no crossing inside: on to its exit, unsampled
      t = fmin(fmax(tn, te), tl);
      known = false;
      continue;
    }
    if (!known) s_prev = field_at(values, &g, p), known = true;
    if (safe_stride && s_prev < 0.0f) {  // CastOptions::safe_stride
      const float slope = slopes[bi];
      const float ts = slope > 0.0f ? 0.9f * -s_prev / (slope * l1) : INFINITY;
      if (ts > dt) tn = fmax(tn, fmin(t + ts, te));
    }
    tn = fmin(tn, tl);
    const float s = field_at(values, &g, base + tn * di);
    if (s_prev <= 0.0f && s > 0.0f) {
      hit = true, a = t, b = tn, fa = s_prev, fb = s;
      break;
    }
    s_prev = s;
    t = tn;
  }
  if (!hit) return;
  for (int i = 0; i < bisections; ++i) {
    const float m = 0.5f * (a + b), fm = field_at(values, &g, base + m * di);
    if (fm > 0.0f) b = m, fb = fm; else a = m, fa = fm;
  }
  const float tm = secant ? clamp(a + (b - a) * (fa / (fa - fb)), a, b) : 0.5f * (a + b);
  const float3 q = base + tm * di;
  const float3 gi = gradient_at(values, &g, q);
  const float3 gw = -sign * linear3(xform + 24, 3, gi);
  const float len = length(gw);
  if (!(len > 0.0f) || !isfinite(len)) return;
  const float3 pw = affine(xform + 12, q);
  out_position[id] = (float4)(pw, 1.0f);
  out_normal[id] = (float4)(gw / len, 0.0f);
  out_depth[id] = dot(pw - eye, fwd);
}

// ---------------------------------------------------------------- estimators

typedef struct {
  int width, height, edges, lod, size_max, fan, paper_rule, mellado_radius;
  float near, far, f_lod, tau, cos_max;  // cos_max < -1: no normal-angle check
  int ortho, linear_depth;
} Params;

float window_depth(const Params* P, float z) {
  float d;
  if (P->linear_depth) d = z / P->far;
  else if (P->ortho) d = (z - P->near) / (P->far - P->near);
  else d = (1.0f / P->near - 1.0f / z) / (1.0f / P->near - 1.0f / P->far);
  return clamp(d, 0.0f, 1.0f);
}

// Prantl's per-triangle shape operator (curvature/prantl.cpp's prantl_triangle in float):
// returns false for a degenerate triangle, else (H_f, K_f) in *hk.
bool shape_operator(float3 p0, float3 p1, float3 p2, float3 n0, float3 n1, float3 n2, int edges,
                    float2* hk) {
  const float3 e01 = p1 - p0, e02 = p2 - p0;
  if (dot(e01, e01) == 0.0f) return false;
  const float3 m = cross(e01, e02);
  if (dot(m, m) == 0.0f) return false;
  const float3 tu = normalize(e01);
  const float3 tv = cross(normalize(cross(tu, e02)), tu);
  const float3 e0 = p0 - p1, e1 = p1 - p2, e2 = p2 - p0;
  const float3 dn0 = n0 - n1, dn1 = n1 - n2, dn2 = n2 - n0;
  const float u0 = dot(e0, tu), v0 = dot(e0, tv), a0 = dot(dn0, tu), b0 = dot(dn0, tv);
  const float u1 = dot(e1, tu), v1 = dot(e1, tv), a1 = dot(dn1, tu), b1 = dot(dn1, tv);
  const float third = edges == 2 ? 0.0f : 1.0f;
  const float u2 = third * dot(e2, tu), v2 = third * dot(e2, tv);
  const float a2 = third * dot(dn2, tu), b2 = third * dot(dn2, tv);
  const float sp = u0 * u0 + u1 * u1 + u2 * u2, sq = u0 * v0 + u1 * v1 + u2 * v2;
  const float sr = v0 * v0 + v1 * v1 + v2 * v2;
  const float c0 = u0 * a0 + u1 * a1 + u2 * a2;
  const float c1 = v0 * a0 + u0 * b0 + v1 * a1 + u1 * b1 + v2 * a2 + u2 * b2;
  const float c2 = v0 * b0 + v1 * b1 + v2 * b2;
  const float minor = sp * sr - sq * sq;
  if (!(minor > (float)PIVOT_TOLERANCE * (sp + sr) * (sp + sr))) return false;
  const float inv_det = 1.0f / ((sp + sr) * minor);
  const float j00 = sr * (sp + sr) - sq * sq, j01 = -sq * sr, j02 = sq * sq, j11 = sp * sr;
  const float j12 = -sp * sq, j22 = sp * (sp + sr) - sq * sq;
  const float L = inv_det * (j00 * c0 + j01 * c1 + j02 * c2);
  const float M = inv_det * (j01 * c0 + j11 * c1 + j12 * c2);
  const float N = inv_det * (j02 * c0 + j12 * c1 + j22 * c2);
  *hk = (float2)(0.5f * (L + N), L * N - M * M);
  return true;
}

__constant int kDX[8] = {1, 1, 0, -1, -1, -1, 0, 1};
__constant int kDY[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// The neighbour `step` pixels along direction k, or -1 when outside the image, invalid, or
// across a depth discontinuity (|d_c - d_n| > tau).
int neighbour(const Params* P, __global const float4* pos, __global const float* depth, int x,
              int y, float dc, int k, int step) {
  const int qx = x + step * kDX[k], qy = y + step * kDY[k];
  if (qx < 0 || qy < 0 || qx >= P->width || qy >= P->height) return -1;
  const int q = qx + P->width * qy;
  if (pos[q].w == 0.0f) return -1;
  if (fabs(window_depth(P, depth[q]) - dc) > P->tau) return -1;
  return q;
}

bool pixel_triangle(const Params* P, __global const float4* pos, __global const float4* nrm,
                    int c, int a, int b, float2* hk) {
  if (a < 0 || b < 0) return false;
  const float3 n0 = nrm[c].xyz, n1 = nrm[a].xyz, n2 = nrm[b].xyz;
  if (P->cos_max >= -1.0f &&
      (dot(n0, n1) < P->cos_max || dot(n1, n2) < P->cos_max || dot(n2, n0) < P->cos_max))
    return false;
  // Positions relative to the centre pixel: differences of nearby floats are exact.
  const float3 pc = pos[c].xyz;
  return shape_operator((float3)(0.0f), pos[a].xyz - pc, pos[b].xyz - pc, n0, n1, n2, P->edges,
                        hk);
}

// Per pixel (H, K, valid, step used): the estimate of screen/estimate.cpp's estimate_reference.
__kernel void screen_prantl(__global const float4* pos, __global const float4* nrm,
                            __global const float* depth, const Params P, __global float4* out) {
  const int c = get_global_id(0);
  if (c >= P.width * P.height) return;
  out[c] = (float4)(0.0f);
  if (pos[c].w == 0.0f) return;
  const int x = c % P.width, y = c / P.width;
  const float dc = window_depth(&P, depth[c]);
  const int s = P.lod ? (int)floor(P.size_max * pow(P.f_lod, -2.0f * dc)) + 1 : 1;
  float2 sum = (float2)(0.0f);
  int count = 0;
  if (s > 1) {
    int nb[8];
    for (int k = 0; k < 8; ++k) {
      nb[k] = -1;
      if (P.fan == 4 && (k & 1)) continue;
      nb[k] = neighbour(&P, pos, depth, x, y, dc, k, s);
      if (nb[k] < 0 && !P.paper_rule) nb[k] = neighbour(&P, pos, depth, x, y, dc, k, 1);
    }
    const int inc = P.fan == 4 ? 2 : 1;
    for (int k = 0; k < 8; k += inc) {
      float2 hk;
      if (pixel_triangle(&P, pos, nrm, c, nb[k], nb[(k + inc) & 7], &hk)) sum += hk, ++count;
    }
  }
  int used = s;
  if (count == 0) {  // the single s = 1 triangle: the first usable quadrant from (c, R, U)
    used = 1;
    for (int k = 0; k < 8 && count == 0; k += 2) {
      float2 hk;
      const int a = neighbour(&P, pos, depth, x, y, dc, k, 1);
      const int b = neighbour(&P, pos, depth, x, y, dc, (k + 2) & 7, 1);
      if (pixel_triangle(&P, pos, nrm, c, a, b, &hk)) sum = hk, count = 1;
    }
  }
  if (count == 0) return;
  out[c] = (float4)(sum / count, 1.0f, (float)used);
}

// Mellado et al.'s algebraic sphere fit with normals over the pixels within mellado_radius of
// c (depth-discontinuity rule as above); H = 2 u_q / |u_l|, K not estimated (0).
__kernel void screen_mellado(__global const float4* pos, __global const float4* nrm,
                             __global const float* depth, const Params P, __global float4* out) {
  const int c = get_global_id(0);
  if (c >= P.width * P.height) return;
  out[c] = (float4)(0.0f);
  if (pos[c].w == 0.0f) return;
  const int x = c % P.width, y = c / P.width, r = P.mellado_radius;
  const float dc = window_depth(&P, depth[c]);
  const float3 pc = pos[c].xyz;
  float h2 = 0.0f;
  int count = 0;
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i) {
      const int qx = x + i, qy = y + j;
      if (i * i + j * j > r * r || qx < 0 || qy < 0 || qx >= P.width || qy >= P.height) continue;
      const int q = qx + P.width * qy;
      if (pos[q].w == 0.0f || fabs(window_depth(&P, depth[q]) - dc) > P.tau) continue;
      const float3 d = pos[q].xyz - pc;
      h2 = fmax(h2, dot(d, d));
      ++count;
    }
  if (count < 6 || !(h2 > 0.0f)) return;
  h2 *= 2.25f;  // h = 1.5 x the farthest point
  // The weighted means first, then the sums about them: u_q's numerator and denominator are
  // differences of nearly equal sums, which float would lose.
  float sw = 0.0f;
  float3 sx = (float3)(0.0f), sn = (float3)(0.0f);
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i) {
      const int qx = x + i, qy = y + j;
      if (i * i + j * j > r * r || qx < 0 || qy < 0 || qx >= P.width || qy >= P.height) continue;
      const int q = qx + P.width * qy;
      if (pos[q].w == 0.0f || fabs(window_depth(&P, depth[q]) - dc) > P.tau) continue;
      const float3 d = pos[q].xyz - pc;
      const float u = 1.0f - dot(d, d) / h2;
      const float w = u * u * u * u;
      sw += w, sx += w * d, sn += w * nrm[q].xyz;
    }
  const float3 mx = sx / sw, mn = sn / sw;
  float cxx = 0.0f, cxn = 0.0f;
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i) {
      const int qx = x + i, qy = y + j;
      if (i * i + j * j > r * r || qx < 0 || qy < 0 || qx >= P.width || qy >= P.height) continue;
      const int q = qx + P.width * qy;
      if (pos[q].w == 0.0f || fabs(window_depth(&P, depth[q]) - dc) > P.tau) continue;
      const float3 d = pos[q].xyz - pc;
      const float u = 1.0f - dot(d, d) / h2;
      const float w = u * u * u * u;
      const float3 dx = d - mx, dn = nrm[q].xyz - mn;
      cxx += w * dot(dx, dx), cxn += w * dot(dx, dn);
    }
  // u_q = 1/2 (sum w x.n - sum w x . sum w n / sum w) / (sum w x.x - |sum w x|^2 / sum w).
  if (!(cxx > 0.0f)) return;
  const float uq = 0.5f * cxn / cxx;
  const float3 ul = mn - 2.0f * uq * mx;
  const float len = length(ul);
  if (!(len > 0.0f)) return;
  out[c] = (float4)(2.0f * uq / len, 0.0f, 1.0f, (float)r);
}
