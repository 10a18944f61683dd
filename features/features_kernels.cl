// Neighbourhood features on the device, one work item per vertex (no atomics: deterministic).
//  features_web:  the sampled path's web of normal-plane curves on the trilinear isosurface
//                 (features/detail/geodesic_web.cpp is its double reference, step by step).
//  features_ball: the volume quadrature of Vr and the radius-resolved H_ii
//                 (features/detail/volume_ball.cpp is its double reference).
// Prepended: volume/dense_field.cl (Grid, field_grad_at, gradient_at, affine, linear3).
// Build options: -DWEB_STEPS -DWEB_STEP_DIVISIONS -DWEB_MAX_ATTEMPTS -DWEB_MAX_LENGTH -DPROJECT_STEPS -DCORRECTOR_STEPS -DOFF_SURFACE
// -DMIN_COS -DARC_SAMPLES -DREFINE_STEPS (the constants of geodesic_web.h and volume_ball.h).

#define PI_F 3.14159265358979f

// xform: to_index (12), to_world (12), normal_matrix (9), as volume::DenseField holds them.
typedef struct {
  __global const float* v;
  Grid g;
  __constant const float* xf;
  float iso, voxel;
} Field;

Field volume_field(__global const float* values, int4 dims, float iso, float sign,
                   __constant const float* xform, float voxel) {
  Field f;
  f.v = values;
  f.g.nx = dims.x, f.g.ny = dims.y, f.g.nz = dims.z, f.g.bx = f.g.by = f.g.bz = 0;
  f.g.iso = iso, f.g.sign = sign, f.g.sparse = dims.w;
  f.xf = xform, f.iso = iso, f.voxel = voxel;
  return f;
}

// The signed field at world point w and its world gradient.
float world_field(const Field* f, float3 w, float3* grad) {
  float3 gi;
  const float s = field_grad_at(f->v, &f->g, affine(f->xf, w), &gi);
  *grad = linear3(f->xf + 24, 3, gi);
  return s;
}

bool inside_domain(const Field* f, float3 w) {
  const float3 q = affine(f->xf, w);
  return q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x <= f->g.nx - 1 &&
         q.y <= f->g.ny - 1 && q.z <= f->g.nz - 1;
}

// The unit outward normal at world point w (DenseField::normal); zero for a zero gradient.
float3 world_normal(const Field* f, float3 w) {
  const float3 g = -f->g.sign * linear3(f->xf + 24, 3, gradient_at(f->v, &f->g, affine(f->xf, w)));
  const float len = length(g);
  return len > 0.0f && isfinite(len) ? g / len : (float3)(0.0f);
}

// lowbias32 of the vertex mixed with the seed, 24 bits of angle (web_rotation).
float web_rotation(uint vertex, uint seed) {
  uint x = vertex ^ (seed * 0x9E3779B9u);
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return 2.0f * PI_F * (float)(x >> 8) * (1.0f / 16777216.0f);
}

// Trapezoid sums along one curve (CurveSums): w, w lbe, w nsv, w height over the ball; w over
// the geodesic disc.
typedef struct {
  float4 ball;
  float disc;
} CurveSums;

CurveSums trace_curve(const Field* f, float3 p0, float3 n0, float3 u, float r, bool* boundary) {
  CurveSums out = {(float4)(0.0f), 0.0f};
  const float3 m = cross(n0, u);
  const float h_max = r / WEB_STEPS, h_min = h_max / WEB_STEP_DIVISIONS;
  float h = h_max;
  float3 c = p0, dir = u, grad;
  float4 prev = (float4)(0.0f);
  float s = 0.0f, dist_prev = 0.0f;
  bool ball_done = false, disc_done = false;
  for (int attempt = 0;
       attempt < WEB_MAX_ATTEMPTS && s < WEB_MAX_LENGTH * r && !(ball_done && disc_done);
       ++attempt) {
    float3 c1 = c + h * dir;
    bool lost = false;
    for (int it = 0; it < CORRECTOR_STEPS && !lost; ++it) {
      const float fv = world_field(f, c1, &grad);
      const float3 gp = grad - dot(grad, m) * m;
      const float gg = dot(gp, gp);
      // The last step starts within OFF_SURFACE of the surface, or the curve is lost.
      lost = !(gg > 0.0f) ||
             (it == CORRECTOR_STEPS - 1 && fabs(fv) > OFF_SURFACE * f->voxel * length(grad));
      if (lost) break;
      c1 -= (fv / gg) * gp;
      c1 -= dot(c1 - p0, m) * m;
    }
    if (lost && h > h_min) {  // the cut turns within the step: try a shorter one
      h *= 0.5f;
      continue;
    }
    lost = lost || !inside_domain(f, c1);
    const float3 step_vec = c1 - c;
    const float ds = length(step_vec);
    const float3 nc = lost ? (float3)(0.0f) : world_normal(f, c1);
    if (lost || !(ds > 0.0f) || all(nc == (float3)(0.0f))) {
      *boundary = true;
      break;
    }
    const float3 d1 = step_vec / ds;
    const float3 q = c1 - p0;
    const float dist = length(q), along = dot(q, n0);
    const float rho = sqrt(max(0.0f, dist * dist - along * along));
    const float cosv = max(fabs(dot(cross(m, d1), nc)), MIN_COS);
    const float w = rho / cosv;
    const float3 dn = n0 - nc;
    const float4 node = (float4)(w, w * dot(dn, dn) / (dist * dist), w * 0.5f * (1.0f - along / dist),
                                 w * along);
    if (!ball_done) {
      float t = 1.0f;
      if (dist > r) {
        t = (r - dist_prev) / (dist - dist_prev);
        ball_done = true;
      }
      t = clamp(t, 0.0f, 1.0f);
      out.ball += 0.5f * t * ds * (2.0f * prev + t * (node - prev));
    }
    if (!disc_done) {
      float t = 1.0f;
      if (s + ds >= r) {
        t = (r - s) / ds;
        disc_done = true;
      }
      out.disc += 0.5f * t * ds * (2.0f * prev.x + t * (node.x - prev.x));
    }
    s += ds;
    dist_prev = dist;
    prev = node;
    c = c1;
    dir = d1;
    h = min(h_max, 2.0f * h);
  }
  return out;
}

// out: (LBE, NSV, geodesic disc area, azimuths traced) per vertex; flags: 1 = boundary.
__kernel void features_web(__global const float* values, int4 dims, float iso, float sign,
                           __constant const float* xform, float voxel,
                           __global const float4* positions, __global const float4* normals,
                           uint count, float r, int azimuths, int adaptive, float threshold,
                           uint seed, __global float4* out, __global uchar* flags, uint first) {
  const uint v = first + get_global_id(0);
  if (v >= count) return;
  const Field f = volume_field(values, dims, iso, sign, xform, voxel);
  const float3 p = positions[v].xyz, n = normals[v].xyz;
  float3 p0 = p, grad;
  for (int it = 0; it < PROJECT_STEPS; ++it) {
    const float fv = world_field(&f, p0, &grad), gn = dot(grad, n);
    if (!(fabs(gn) > 0.0f)) break;
    p0 += clamp(-fv / gn, -0.5f * voxel, 0.5f * voxel) * n;
  }
  if (length(p0 - p) > voxel) p0 = p;
  float3 n0 = world_normal(&f, p0);
  if (all(n0 == (float3)(0.0f))) n0 = n;
  const float sgn = n0.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sgn + n0.z), b = n0.x * n0.y * a;
  const float3 e1 = (float3)(1.0f + sgn * n0.x * n0.x * a, sgn * b, -sgn * n0.x);
  const float3 e2 = (float3)(b, sgn + n0.y * n0.y * a, -n0.y);
  const float rotation = web_rotation(v, seed);
  bool boundary = false;
  float4 ball = (float4)(0.0f);
  float disc = 0.0f, g_sum = 0.0f, g_sq = 0.0f, g_cos = 0.0f, g_sin = 0.0f;
  int g_count = 0, traced = 0;
  // Even azimuths, then (unless adaptive stops) the odd ones.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1 && adaptive && g_count > 0) {
      // adaptive_needs_more: the variance the quadric form a + b cos 2phi + c sin 2phi leaves.
      const float mean = g_sum / g_count, mean_sq = g_sq / g_count;
      float residual = mean_sq - mean * mean;
      if (g_count >= 5) {
        const float ca = 2.0f * g_cos / g_count, sa = 2.0f * g_sin / g_count;
        residual -= 0.5f * (ca * ca + sa * sa);
      }
      if (!(residual > threshold * mean_sq)) break;
    }
    for (int k = pass; k < azimuths; k += 2) {
      const float phi = rotation + 2.0f * PI_F * k / azimuths;
      const float3 u = cos(phi) * e1 + sin(phi) * e2;
      const CurveSums cs = trace_curve(&f, p0, n0, u, r, &boundary);
      ball += cs.ball;
      disc += cs.disc;
      if (cs.ball.x > 0.0f) {
        const float g = -4.0f / (r * r) * cs.ball.w / cs.ball.x;
        g_sum += g, g_sq += g * g, ++g_count;
        g_cos += g * cos(2.0f * phi), g_sin += g * sin(2.0f * phi);
      }
      ++traced;
    }
  }
  float lbe = 0.0f, nsv = 0.5f;
  if (ball.x > 0.0f) {
    lbe = ball.y / ball.x;
    nsv = ball.z / ball.x;
  } else {
    boundary = true;
  }
  out[v] = (float4)(lbe, nsv, 2.0f * PI_F / traced * disc, (float)traced);
  flags[v] = boundary ? 1 : 0;
}

// The inside length in s of the arc t (c u + s n), c = sqrt(1 - s^2), in index space, from
// ARC_SAMPLES samples of s with every crossing refined by Illinois regula falsi (VolumeBall).
float arc_inside(const Field* f, float3 pi, float3 ui, float3 ni, float t) {
  float length = 0.0f, s0 = -1.0f;
  float g0 = field_at(f->v, &f->g, pi + t * (-1.0f * ni));
  for (int i = 1; i < ARC_SAMPLES; ++i) {
    const float s1 = -1.0f + 2.0f * i / (ARC_SAMPLES - 1);
    const float c1 = sqrt(max(0.0f, 1.0f - s1 * s1));
    const float g1 = field_at(f->v, &f->g, pi + t * (c1 * ui + s1 * ni));
    const bool in0 = g0 > 0.0f, in1 = g1 > 0.0f;
    if (in0 && in1) {
      length += s1 - s0;
    } else if (in0 != in1) {
      float lo = s0, hi = s1, glo = g0, ghi = g1, s = 0.5f * (lo + hi);
      int side = 0;
      for (int it = 0; it < REFINE_STEPS; ++it) {
        s = (lo * ghi - hi * glo) / (ghi - glo);
        const float cs = sqrt(max(0.0f, 1.0f - s * s));
        const float gs = field_at(f->v, &f->g, pi + t * (cs * ui + s * ni));
        if ((gs > 0.0f) == (glo > 0.0f)) {
          lo = s, glo = gs;
          if (side == -1) ghi *= 0.5f;
          side = -1;
        } else {
          hi = s, ghi = gs;
          if (side == 1) glo *= 0.5f;
          side = 1;
        }
      }
      length += in0 ? s - s0 : s1 - s;
    }
    s0 = s1, g0 = g1;
  }
  return length;
}

// out: (Vr, H fitted over the radii) per vertex; flags |= 1 where the ball leaves the domain.
// gl: Gauss-Legendre nodes (radial) then weights (radial) on [-1, 1].
__kernel void features_ball(__global const float* values, int4 dims, float iso, float sign,
                            __constant const float* xform, __constant const float* gl,
                            int azimuths, int radial, __global const float4* positions,
                            __global const float4* normals, uint count, float r,
                            __global float2* out, __global uchar* flags, uint first) {
  const uint v = first + get_global_id(0);
  if (v >= count) return;
  const Field f = volume_field(values, dims, iso, sign, xform, 0.0f);
  const float3 p = positions[v].xyz, n = normals[v].xyz;
  bool leaves = false;
  for (int corner = 0; corner < 8; ++corner) {
    const float3 w = p + (float3)((corner & 1) ? r : -r, (corner & 2) ? r : -r,
                                  (corner & 4) ? r : -r);
    if (!inside_domain(&f, w)) leaves = true;
  }
  const float sgn = n.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sgn + n.z), b = n.x * n.y * a;
  const float3 e1 = (float3)(1.0f + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
  const float3 e2 = (float3)(b, sgn + n.y * n.y * a, -n.y);
  const float3 pi = affine(xform, p);
  const float3 ni = linear3(xform, 4, n);
  float outside[16];
  for (int j = 0; j < radial; ++j) outside[j] = 0.0f;
  float vr = 0.0f;
  for (int k = 0; k < azimuths; ++k) {
    const float phi = 2.0f * PI_F * (k + 0.5f) / azimuths;
    const float3 ui = linear3(xform, 4, cos(phi) * e1 + sin(phi) * e2);
    float over_t = 0.0f;
    for (int j = 0; j < radial; ++j) {
      const float t = 0.5f * r * (gl[j] + 1.0f);
      const float length = arc_inside(&f, pi, ui, ni, t);
      over_t += 0.5f * r * gl[radial + j] * t * t * length;
      outside[j] += 1.0f - length;
    }
    vr += (2.0f * PI_F / azimuths) * over_t;
  }
  float sw = 0.0f, sx = 0.0f, sy = 0.0f, sxx = 0.0f, sxy = 0.0f;
  for (int j = 0; j < radial; ++j) {
    // x = (t / r)^2 rather than t^2 (float's range); the slope is then H r^2 / 2.
    const float t = 0.5f * r * (gl[j] + 1.0f), x = 0.25f * (gl[j] + 1.0f) * (gl[j] + 1.0f);
    const float m = t * outside[j] / azimuths;
    const float w = gl[radial + j];
    sw += w, sx += w * x, sy += w * m, sxx += w * x * x, sxy += w * x * m;
  }
  const float det = sw * sxx - sx * sx;
  out[v] = (float2)(vr, det > 0.0f ? 2.0f * (sw * sxy - sx * sy) / (det * r * r) : 0.0f);
  if (leaves) flags[v] |= 1;
}
