// Feature-line extraction per face: the OpenCL version of lines/reference.cpp (read it beside
// that file; lines/reference.h states the rules). Built with -D options from lines/extract.cpp:
//   TYPE_CONTOUR, TYPE_SUGGESTIVE, TYPE_RIDGE, TYPE_VALLEY  the LineType values
//   MAX_SEGMENTS  segments a face can give (one per type)
//   NO_SEGMENT    the type of an emitting slot left empty
//   NO_EDGE       the key of an endpoint inside its face (kInsideFace)
//   VERTEX_SNAP   crossings this close to an edge's end move onto the vertex (kVertexSnap)

// What a launch extracts and with which thresholds (lines::Thresholds).
typedef struct {
  int contours, suggestive, ridges, valleys;
  float t_d;        // suggestive: num/den threshold
  float cos_angle;  // suggestive: n.v below this
  float t_r;        // ridges and valleys: |k| threshold
} Params;

// selection: (contours, suggestive, ridges, valleys); thresholds: (t_d, cos_angle, t_r, 0).
Params make_params(int4 selection, float4 thresholds) {
  Params P;
  P.contours = selection.x;
  P.suggestive = selection.y;
  P.ridges = selection.z;
  P.valleys = selection.w;
  P.t_d = thresholds.x;
  P.cos_angle = thresholds.y;
  P.t_r = thresholds.z;
  return P;
}

typedef struct {
  float3 a, b;
  ulong edge_a, edge_b;
  float strength;
  uint type;
} Seg;

bool finite3(float3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

// Per vertex: view = (ndotv, kr, num, finite) for the camera, and kn = (kr, num) for the
// smoothing. `finite` is 1 where the vertex's curvature inputs (k1, k2, normal, directions when
// with_dirs and, with check_dcurv, dcurv) are all finite, else 0: face_segments then need not read
// them. eye.w != 0: orthographic, `toward` is the direction towards the camera; else
// v = normalize(eye - p).
__kernel void line_vertex_view(__global const float* positions, __global const float* normals,
                               __global const float* dir1, __global const float* dir2,
                               __global const float* k1s, __global const float* k2s,
                               __global const float4* dcurv, int with_dcurv, int check_dcurv,
                               int with_dirs, uint vertex_count, float4 eye, float4 toward,
                               __global float4* view, __global float2* kn) {
  const uint i = get_global_id(0);
  if (i >= vertex_count) return;
  const float3 p = vload3(i, positions);
  const float3 v = eye.w != 0 ? toward.xyz : normalize(eye.xyz - p);
  const float3 normal = vload3(i, normals);
  // Contours alone: a field without directions (kr, num stay 0).
  const float3 d1 = with_dirs ? vload3(i, dir1) : (float3)(0),
               d2 = with_dirs ? vload3(i, dir2) : (float3)(0);
  const float ndotv = dot(normal, v);
  const float u = dot(v, d1), w = dot(v, d2);
  const float u2 = u * u, w2 = w * w, sin2 = u2 + w2;
  const float k1 = k1s[i], k2 = k2s[i];
  const float kr = k1 * u2 + k2 * w2;
  float num = 0;
  if (with_dcurv && sin2 > 0) {
    const float4 C = dcurv[i];
    const float tau = (k2 - k1) * u * w / sin2;
    num = (u2 * (u * C.x + 3 * w * C.y) + w2 * (3 * u * C.z + w * C.w)) / sin2 -
          2 * ndotv * tau * tau;
  }
  bool finite = isfinite(k1) && isfinite(k2) && finite3(normal) && finite3(d1) && finite3(d2);
  if (check_dcurv) finite = finite && all(isfinite(dcurv[i]));
  view[i] = (float4)(ndotv, kr, num, finite ? 1.0f : 0.0f);
  kn[i] = (float2)(kr, num);
}

// One smoothing pass over kr and num (kn: the view's .y and .z, written by line_vertex_view): the
// mean over the vertex and the two other corners of each of its triangles, whose indices are
// pairs[offsets[i] ..] (lines/detail/vertex_pairs.h). The last pass (`last` != 0) also stores the
// result in the view's .y and .z; n.v and the finite flag are kept.
__kernel void line_vertex_smooth(__global const uint* offsets, __global const uint2* pairs,
                                 __global const float2* kn_in, uint vertex_count, int last,
                                 __global float2* kn_out, __global float4* view) {
  const uint i = get_global_id(0);
  if (i >= vertex_count) return;
  const uint begin = offsets[i], end = offsets[i + 1];
  float2 sum = kn_in[i];
  for (uint k = begin; k < end; ++k) {
    const uint2 other = pairs[k];
    sum += kn_in[other.x] + kn_in[other.y];
  }
  const float2 mean = sum / (float)(1 + 2 * (end - begin));
  kn_out[i] = mean;
  if (last) view[i] = (float4)(view[i].x, mean, view[i].w);
}

typedef struct {
  uint lo, hi;  // the edge's vertices, lo < hi
  float t;      // from lo towards hi
} Crossing;

// The two edge crossings of the zero set of f over face v; 0 when f keeps one sign.
int face_crossings(const uint v[3], const float f[3], Crossing out[2]) {
  int n = 0;
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3;
    if ((f[j] > 0) == (f[k] > 0)) continue;
    const bool j_lo = v[j] < v[k];
    const float f_lo = j_lo ? f[j] : f[k], f_hi = j_lo ? f[k] : f[j];
    if (n < 2) {
      out[n].lo = j_lo ? v[j] : v[k];
      out[n].hi = j_lo ? v[k] : v[j];
      float t = f_lo / (f_lo - f_hi);
      if (t < VERTEX_SNAP) t = 0;  // on the vertex (kVertexSnap)
      if (t > 1 - VERTEX_SNAP) t = 1;
      out[n].t = t;
    }
    ++n;
  }
  return n == 2 ? 2 : 0;
}

// The key of the point: the edge's, or the vertex's (lo = hi) when it lies on one.
ulong edge_key(const Crossing c) {
  const uint lo = c.t == 1 ? c.hi : c.lo, hi = c.t == 0 ? c.lo : c.hi;
  return ((ulong)lo << 32) | hi;
}

bool same_point(float3 a, float3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

float3 point_at(__global const float* positions, const Crossing c) {
  const float3 a = vload3(c.lo, positions), b = vload3(c.hi, positions);
  return a + c.t * (b - a);
}

float lerp_at(float a, float b, float t) { return a + t * (b - a); }

// Clips [s0, s1] to where g0 + s (g1 - g0) > 0; false when nothing is left.
bool clip_positive(float g0, float g1, float* s0, float* s1) {
  if (g0 > 0 && g1 > 0) return true;
  if (g0 <= 0 && g1 <= 0) return false;
  const float s = g0 / (g0 - g1);
  if (g0 > 0) *s1 = min(*s1, s);
  else *s0 = max(*s0, s);
  return *s0 < *s1;
}

// The segments of face f (in type order) into out; returns how many.
int face_segments(uint f, __global const uint* triangles, __global const float* positions,
                  __global const float* normals, __global const float* dir1s,
                  __global const float* dir2s, __global const float* k1s,
                  __global const float* k2s, __global const float4* dcurv,
                  __global const float4* view, const Params P, Seg out[MAX_SEGMENTS]) {
  const uint v[3] = {triangles[3 * f], triangles[3 * f + 1], triangles[3 * f + 2]};
  if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) return 0;
  const float3 p[3] = {vload3(v[0], positions), vload3(v[1], positions), vload3(v[2], positions)};
  const float3 normal2 = cross(p[1] - p[0], p[2] - p[0]);  // twice the area
  const float area2 = length(normal2);
  if (!(area2 > 0) || !isfinite(area2)) return 0;
  const bool view_dependent = P.contours || P.suggestive;
  const bool with_dcurv = P.suggestive || P.ridges || P.valleys;
  float4 q[3];
  for (int j = 0; j < 3; ++j) {
    const uint i = v[j];
    bool ok;
    if (view_dependent) {  // .w: line_vertex_view checked the vertex's curvature inputs
      q[j] = view[i];
      ok = q[j].w != 0 && isfinite(q[j].x) && isfinite(q[j].y) && isfinite(q[j].z);
    } else {
      q[j] = (float4)(0);
      ok = isfinite(k1s[i]) && isfinite(k2s[i]) && finite3(vload3(i, normals)) &&
           finite3(vload3(i, dir1s)) && finite3(vload3(i, dir2s));
      if (with_dcurv) ok = ok && all(isfinite(dcurv[i]));
    }
    if (!ok) return 0;
  }
  int n = 0;
  Crossing c[2];

  if (P.contours) {
    const float g[3] = {q[0].x, q[1].x, q[2].x};
    if (face_crossings(v, g, c)) {
      out[n].a = point_at(positions, c[0]);
      out[n].b = point_at(positions, c[1]);
      out[n].edge_a = edge_key(c[0]);
      out[n].edge_b = edge_key(c[1]);
      out[n].strength = 1;
      out[n].type = TYPE_CONTOUR;
      ++n;
    }
  }

  if (P.suggestive) {
    const float g[3] = {q[0].y, q[1].y, q[2].y};
    if (face_crossings(v, g, c)) {
      float num[2], den[2];
      for (int e = 0; e < 2; ++e) {
        const float4 lo = view[c[e].lo], hi = view[c[e].hi];
        num[e] = lerp_at(lo.z, hi.z, c[e].t);
        den[e] = lerp_at(lo.x, hi.x, c[e].t);
      }
      float s0 = 0, s1 = 1;
      const bool keep = clip_positive(num[0] - P.t_d * den[0], num[1] - P.t_d * den[1], &s0, &s1) &&
                        clip_positive(den[0], den[1], &s0, &s1) &&
                        clip_positive(P.cos_angle - den[0], P.cos_angle - den[1], &s0, &s1);
      if (keep) {
        const float3 a = point_at(positions, c[0]), b = point_at(positions, c[1]);
        float fade = 0;
        const float s[2] = {s0, s1};
        for (int e = 0; e < 2; ++e) {
          const float nn = lerp_at(num[0], num[1], s[e]), d = lerp_at(den[0], den[1], s[e]);
          // d <= 0 only where the segment was clipped at den = 0, where num > 0: the test is +inf
          fade += P.t_d > 0 && d > 0 ? clamp((nn / d - P.t_d) / P.t_d, 0.0f, 1.0f) : 1.0f;
        }
        out[n].a = a + s0 * (b - a);
        out[n].b = a + s1 * (b - a);
        out[n].edge_a = s0 == 0 ? edge_key(c[0]) : NO_EDGE;
        out[n].edge_b = s1 == 1 ? edge_key(c[1]) : NO_EDGE;
        out[n].strength = fade / 2;
        out[n].type = TYPE_SUGGESTIVE;
        ++n;
      }
    }
  }

  // Ridges (k1 along dir1, a maximum) and valleys (k2 along dir2, a minimum).
  for (int kind = 0; kind < 2; ++kind) {
    const bool ridge = kind == 0;
    if (!(ridge ? P.ridges : P.valleys)) continue;
    float e[3];
    float3 mean_dir = (float3)(0);
    bool ok = true;
    const float3 dir0 = ridge ? vload3(v[0], dir1s) : vload3(v[0], dir2s);
    for (int j = 0; j < 3; ++j) {
      const uint i = v[j];
      const float k1 = k1s[i], k2 = k2s[i];
      ok = ok && (ridge ? k1 > fabs(k2) : k2 < -fabs(k1));
      const float3 d = ridge ? vload3(i, dir1s) : vload3(i, dir2s);
      const float sign = dot(d, dir0) < 0 ? -1.0f : 1.0f;
      e[j] = sign * (ridge ? dcurv[i].x : dcurv[i].w);
      mean_dir += sign * d;
    }
    if (!ok || !face_crossings(v, e, c)) continue;
    // Gradient of the linear interpolant of e: sum_j e_j (n x (opposite edge)) / (2 area).
    const float3 nrm = normal2 / area2;
    float3 grad = (float3)(0);
    for (int j = 0; j < 3; ++j) grad += cross(nrm, p[(j + 2) % 3] - p[(j + 1) % 3]) * (e[j] / area2);
    const float slope = dot(grad, mean_dir);
    if (ridge ? !(slope < 0) : !(slope > 0)) continue;
    float kk = 0;
    for (int x = 0; x < 2; ++x) {
      const float lo = ridge ? k1s[c[x].lo] : -k2s[c[x].lo], hi = ridge ? k1s[c[x].hi] : -k2s[c[x].hi];
      kk += lerp_at(lo, hi, c[x].t);
    }
    kk *= 0.5f;
    if (!(kk > P.t_r)) continue;
    out[n].a = point_at(positions, c[0]);
    out[n].b = point_at(positions, c[1]);
    out[n].edge_a = edge_key(c[0]);
    out[n].edge_b = edge_key(c[1]);
    out[n].strength = P.t_r > 0 ? clamp((kk - P.t_r) / P.t_r, 0.0f, 1.0f) : 1.0f;
    out[n].type = ridge ? TYPE_RIDGE : TYPE_VALLEY;
    ++n;
  }
  // Drop segments whose two crossings fell on one vertex (zero length), keeping the order.
  int kept = 0;
  for (int j = 0; j < n; ++j)
    if (!same_point(out[j].a, out[j].b)) out[kept++] = out[j];
  return kept;
}

// Rounding allowance of the early tests below, relative to the values compared.
#define EARLY_SLACK 1e-5f

// Per-vertex bits for the count's early test (line_vertex_flags), so that it reads one byte per
// corner instead of the vertex's view quantities and curvature.
#define FLAG_FRONT 1u       // n.v > 0
#define FLAG_KR 2u          // kr > 0
#define FLAG_DERIVATIVE 4u  // num > t_d n.v (up to rounding)
#define FLAG_OBLIQUE 8u     // n.v < cos_angle (up to rounding)
#define FLAG_RIDGE 16u      // k1 > |k2|: a ridge may pass here
#define FLAG_VALLEY 32u     // k2 < -|k1|: a valley may pass here

// The flags of every vertex from its view quantities (when contours or suggestive contours are
// asked for) and its principal curvatures.
__kernel void line_vertex_flags(__global const float4* view, __global const float* k1s,
                                __global const float* k2s, int4 selection, float4 thresholds,
                                uint vertex_count, __global uchar* flags) {
  const uint i = get_global_id(0);
  if (i >= vertex_count) return;
  const Params P = make_params(selection, thresholds);
  uint f = 0;
  if (P.contours || P.suggestive) {
    const float4 q = view[i];
    const float ndotv = q.x, kr = q.y, num = q.z;
    const float slack = EARLY_SLACK * (fabs(num) + P.t_d * fabs(ndotv));
    if (ndotv > 0) f |= FLAG_FRONT;
    if (kr > 0) f |= FLAG_KR;
    if (num - P.t_d * ndotv > -slack) f |= FLAG_DERIVATIVE;
    if (ndotv < P.cos_angle + EARLY_SLACK) f |= FLAG_OBLIQUE;
  }
  const float k1 = k1s[i], k2 = k2s[i];
  if (k1 > fabs(k2)) f |= FLAG_RIDGE;
  if (k2 < -fabs(k1)) f |= FLAG_VALLEY;
  flags[i] = (uchar)f;
}

// How many of the asked line types may give face f a segment, from its corners' flags: an upper
// bound of face_segments' count, exact on nearly every face (most have none and skip the rest).
// - a contour: n.v changes sign over the corners;
// - a suggestive contour: kr changes sign, and face_segments' clipping can leave something. It
//   keeps the part of the kr = 0 segment where num > t_d n.v, n.v > 0 and n.v < cos_angle; the
//   values there are interpolated from the corners', so each test must hold at some corner;
// - a ridge or valley: k1 > |k2| (k2 < -|k1|) at every corner, and the derivative along the
//   aligned principal direction changes sign.
int face_line_candidates(uint f, __global const uint* triangles, __global const uchar* flags,
                         __global const float* dir1s, __global const float* dir2s,
                         __global const float4* dcurv, const Params P) {
  const uint v0 = triangles[3 * f], v1 = triangles[3 * f + 1], v2 = triangles[3 * f + 2];
  const uint f0 = flags[v0], f1 = flags[v1], f2 = flags[v2];
  const uint differ = (f0 ^ f1) | (f1 ^ f2), some = f0 | f1 | f2, every = f0 & f1 & f2;
  int n = 0;
  if (P.contours && (differ & FLAG_FRONT)) ++n;
  const uint suggestive_needs = FLAG_FRONT | FLAG_DERIVATIVE | FLAG_OBLIQUE;
  if (P.suggestive && (differ & FLAG_KR) && (some & suggestive_needs) == suggestive_needs) ++n;
  for (int kind = 0; kind < 2; ++kind) {
    const bool ridge = kind == 0;
    if (!(ridge ? P.ridges : P.valleys) || !(every & (ridge ? FLAG_RIDGE : FLAG_VALLEY))) continue;
    const float3 d0 = ridge ? vload3(v0, dir1s) : vload3(v0, dir2s);
    const float3 d1 = ridge ? vload3(v1, dir1s) : vload3(v1, dir2s);
    const float3 d2 = ridge ? vload3(v2, dir1s) : vload3(v2, dir2s);
    const float e0 = ridge ? dcurv[v0].x : dcurv[v0].w;
    const float e1 = (dot(d1, d0) < 0 ? -1.0f : 1.0f) * (ridge ? dcurv[v1].x : dcurv[v1].w);
    const float e2 = (dot(d2, d0) < 0 ? -1.0f : 1.0f) * (ridge ? dcurv[v2].x : dcurv[v2].w);
    if (!((e0 > 0) == (e1 > 0) && (e1 > 0) == (e2 > 0))) ++n;
  }
  return n;
}

// Pass 1: every face's number of segment slots (face_line_candidates).
__kernel void line_face_count(__global const uint* triangles, __global const uchar* flags,
                              __global const float* dir1s, __global const float* dir2s,
                              __global const float4* dcurv, int4 selection, float4 thresholds,
                              uint face_count, __global uchar* counts) {
  const uint f = get_global_id(0);
  if (f >= face_count) return;
  const Params P = make_params(selection, thresholds);
  counts[f] = (uchar)face_line_candidates(f, triangles, flags, dir1s, dir2s, dcurv, P);
}

// Pass 2: the segments of the faces listed in `faces` (those with slots, in face order), written
// into their slots offsets[i] .. offsets[i + 1]: (a, strength), (b, 0), (edge_a, edge_b),
// (face, type); slots left over get the type NO_SEGMENT.
__kernel void line_face_emit(__global const uint* triangles, __global const float* positions,
                             __global const float* normals, __global const float* dir1s,
                             __global const float* dir2s, __global const float* k1s,
                             __global const float* k2s, __global const float4* dcurv,
                             __global const float4* view, int4 selection, float4 thresholds,
                             __global const uint* faces, __global const uint* offsets,
                             uint listed, __global float4* out_a, __global float4* out_b,
                             __global ulong2* out_edges, __global uint2* out_face_type) {
  const uint i = get_global_id(0);
  if (i >= listed) return;
  const Params P = make_params(selection, thresholds);
  const uint f = faces[i], first = offsets[i], slots = offsets[i + 1] - first;
  Seg s[MAX_SEGMENTS];
  const int n = face_segments(f, triangles, positions, normals, dir1s, dir2s, k1s, k2s, dcurv, view,
                              P, s);
  for (int j = 0; j < n && (uint)j < slots; ++j) {
    const uint o = first + j;
    out_a[o] = (float4)(s[j].a, s[j].strength);
    out_b[o] = (float4)(s[j].b, 0);
    out_edges[o] = (ulong2)(s[j].edge_a, s[j].edge_b);
    out_face_type[o] = (uint2)(f, s[j].type);
  }
  for (uint j = n; j < slots; ++j) out_face_type[first + j] = (uint2)(f, NO_SEGMENT);
}
