// Device functions of the curvature kernels: float twins of curvature/reference.cpp's helpers,
// written out for the structured systems and frames at hand. Built with -DPIVOT_TOLERANCE,
// -DOPPOSITE_NORMALS and -DAO_C0/C1/C2/SMIN taken from curvature/tolerances.h and derived.h.
//
// Performance note: PoCL (the CPU device) runs a work-group in SIMD lanes only when the kernel has
// no inner loops, no OpenCL vector types and no calls into its built-in library (atan2, fmax,
// clamp...). The per-face kernels and the per-vertex math kernels are written that way: scalars
// and the vec3 struct below, selects instead of branches, a local atan.

#define INLINE inline __attribute__((always_inline))

typedef struct {
  float x, y, z;
} vec3;

INLINE vec3 v3(float x, float y, float z) {
  const vec3 r = {x, y, z};
  return r;
}
INLINE vec3 load3(__global const float* p, uint i) {
  return v3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
}
INLINE void store3(vec3 a, __global float* p, uint i) {
  p[3 * i] = a.x, p[3 * i + 1] = a.y, p[3 * i + 2] = a.z;
}
INLINE vec3 add3(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
INLINE vec3 sub3(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
INLINE vec3 mul3(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
INLINE float dot3(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
INLINE vec3 cross3(vec3 a, vec3 b) {
  return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
INLINE vec3 unit3(vec3 a) { return mul3(a, 1.0f / sqrt(dot3(a, a))); }
INLINE bool finite(float x) { return x - x == 0.0f; }  // 0 for finite x, NaN for Inf and NaN

// A symmetric 2-tensor (ku, kuv, kv), a 2x2 frame change (u1, v1, u2, v2) and a symmetric
// 3-tensor (C111, C112, C122, C222).
typedef struct {
  float u, uv, v;
} tensor2;
typedef struct {
  float u1, v1, u2, v2;
} frame2;
typedef struct {
  float c0, c1, c2, c3;
} tensor3;

// An orthonormal tangent basis (u, v) with (u, v, n) right-handed, from the unit normal alone
// (Duff et al. 2017).
INLINE void tangent_basis(vec3 n, vec3* u, vec3* v) {
  const float sign = n.z < 0.0f ? -1.0f : 1.0f;
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  *u = v3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  *v = v3(b, sign + n.y * n.y * a, -n.y);
}

// A triangle's frame from two edges: t along e0, m the unit normal, b = m x t.
INLINE void face_frame(vec3 e0, vec3 e1, vec3* t, vec3* b, vec3* m) {
  *t = unit3(e0);
  *m = unit3(cross3(e0, e1));
  *b = cross3(*m, *t);
}

// A vertex frame (u, v) with normal n, rotated about n x m onto the plane of the triangle frame
// (t, b) with normal m (the smallest such rotation; a half turn about u when n and m are
// opposite), in the triangle frame's coordinates. For x orthogonal to n the rotation is
// x - (x.m) (n + m) / (1 + n.m), and m.t = m.b = 0.
INLINE frame2 vertex_to_face(vec3 u, vec3 v, vec3 n, vec3 t, vec3 b, vec3 m) {
  const float c = dot3(n, m);
  const bool opposite = 1.0f + c < (float)OPPOSITE_NORMALS;
  const float s = opposite ? 0.0f : 1.0f / (1.0f + c);
  const float alpha = dot3(n, t) * s, beta = dot3(n, b) * s;
  const float um = dot3(u, m), vm = dot3(v, m), flip = opposite ? -1.0f : 1.0f;
  const frame2 x = {dot3(u, t) - um * alpha, dot3(u, b) - um * beta,
                    flip * (dot3(v, t) - vm * alpha), flip * (dot3(v, b) - vm * beta)};
  return x;
}

// The inverse frame change (the triangle's axes in the vertex frame): the transpose.
INLINE frame2 transpose2(frame2 x) {
  const frame2 r = {x.u1, x.u2, x.v1, x.v2};
  return r;
}

// The 2-tensor k in the frame whose axes have coordinates x1 = (u1, v1), x2 = (u2, v2).
INLINE tensor2 change_tensor(tensor2 k, frame2 x) {
  const tensor2 r = {
      k.u * x.u1 * x.u1 + 2.0f * k.uv * x.u1 * x.v1 + k.v * x.v1 * x.v1,
      k.u * x.u1 * x.u2 + k.uv * (x.u1 * x.v2 + x.v1 * x.u2) + k.v * x.v1 * x.v2,
      k.u * x.u2 * x.u2 + 2.0f * k.uv * x.u2 * x.v2 + k.v * x.v2 * x.v2};
  return r;
}

// The 3-tensor C in the frame with axes x1 = (a, b), x2 = (c, d):
// (C(x1,x1,x1), C(x1,x1,x2), C(x1,x2,x2), C(x2,x2,x2)).
INLINE tensor3 change_cubic(tensor3 C, frame2 x) {
  const float a = x.u1, b = x.v1, c = x.u2, d = x.v2;
  const tensor3 r = {
      C.c0 * a * a * a + 3.0f * C.c1 * a * a * b + 3.0f * C.c2 * a * b * b + C.c3 * b * b * b,
      C.c0 * a * a * c + C.c1 * (a * a * d + 2.0f * a * b * c) +
          C.c2 * (b * b * c + 2.0f * a * b * d) + C.c3 * b * b * d,
      C.c0 * a * c * c + C.c1 * (2.0f * a * c * d + b * c * c) +
          C.c2 * (a * d * d + 2.0f * b * c * d) + C.c3 * b * d * d,
      C.c0 * c * c * c + 3.0f * C.c1 * c * c * d + 3.0f * C.c2 * c * d * d + C.c3 * d * d * d};
  return r;
}

// LDL^T solve of the tensor system [[a, b, 0], [b, a + c, b], [0, b, c]] x = r (a = sum u^2,
// b = sum uv, c = sum v^2 over the edges). False when a pivot is not above PIVOT_TOLERANCE times
// the largest diagonal entry (a + c).
INLINE bool solve_tensor(float a, float b, float c, tensor2 r, tensor2* x) {
  const float tol = (float)PIVOT_TOLERANCE * (a + c);
  const float d0 = a, l10 = b / d0;
  const float d1 = (a + c) - l10 * b, l21 = b / d1;
  const float d2 = c - l21 * b;
  const float y1 = r.uv - l10 * r.u, y2 = r.v - l21 * y1;
  x->v = y2 / d2;
  x->uv = y1 / d1 - l21 * x->v;
  x->u = r.u / d0 - l10 * x->uv;
  return d0 > tol && d1 > tol && d2 > tol;
}

// LDL^T solve of the (tridiagonal) derivative system
// [[a, b, 0, 0], [b, 2a + c, 2b, 0], [0, 2b, a + 2c, b], [0, 0, b, c]] x = r.
INLINE bool solve_derivative(float a, float b, float c, tensor3 r, tensor3* x) {
  const float tol = (float)PIVOT_TOLERANCE * ((a > c ? a : c) + a + c);
  const float d0 = a, l1 = b / d0;
  const float d1 = (2.0f * a + c) - l1 * b, l2 = 2.0f * b / d1;
  const float d2 = (a + 2.0f * c) - l2 * 2.0f * b, l3 = b / d2;
  const float d3 = c - l3 * b;
  const float y1 = r.c1 - l1 * r.c0, y2 = r.c2 - l2 * y1, y3 = r.c3 - l3 * y2;
  x->c3 = y3 / d3;
  x->c2 = y2 / d2 - l3 * x->c3;
  x->c1 = y1 / d1 - l2 * x->c2;
  x->c0 = r.c0 / d0 - l1 * x->c1;
  return d0 > tol && d1 > tol && d2 > tol && d3 > tol;
}

// atan(y / x) for x >= 0 (atan2 on the right half-plane; 0 when both are 0), within 2e-7 rad:
// Cephes' atanf (range reduction at tan(pi/8), tan(3pi/8) and a degree-9 odd polynomial).
INLINE float atan_right(float y, float x) {
  const float ay = y < 0.0f ? -y : y;
  const bool big = ay > 2.414213562373095f * x, mid = !big && ay > 0.4142135623730950f * x;
  const float q = big ? -x / ay : mid ? (ay - x) / (ay + x) : (x > 0.0f ? ay / x : 0.0f);
  const float base = big ? 1.5707963267948966f : mid ? 0.7853981633974483f : 0.0f;
  const float z = q * q;
  const float p =
      (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
       3.33329491539e-1f) * z * q + q;
  const float r = base + p;
  return y < 0.0f ? -r : r;
}

// Koenderink's shape index and curvedness, and Griffin et al.'s curvature-based ambient occlusion
// (see curvature/derived.h for the definitions, constants and their derivation).
INLINE float shape_index(float k1, float k2) {
  return 0.6366197723675814f * atan_right(k1 + k2, k1 - k2);
}
INLINE float curvedness(float k1, float k2) { return sqrt((k1 * k1 + k2 * k2) * 0.5f); }
INLINE float ambient_occlusion(float k1, float k2, float scale) {
  const float s0 = scale * (k1 + k2), s = s0 > (float)AO_SMIN ? s0 : (float)AO_SMIN;
  const float ao = (float)AO_C0 + s * ((float)AO_C1 + s * (float)AO_C2);
  return ao < 0.0f ? 0.0f : ao > 1.0f ? 1.0f : ao;
}
