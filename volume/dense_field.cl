// A volume's dense samples on the device: the trilinear signed field and the gradient normals
// that volume::DenseField computes on the host (volume/dense_field.cpp is their reference), and
// the affine maps between index and world space. Prepended to the programs that sample volumes
// at arbitrary points (screen_kernels.cl, features_kernels.cl).

typedef struct {
  int nx, ny, nz, bx, by, bz;
  float iso, sign;
  int sparse;  // 0: dense; 1: the tiled layout of volume::DenseField (8^3 tiles, only leaves stored)
} Grid;

// The raw value of sample (i, j, k): DenseField::sample, both layouts.
float raw_at(__global const float* v, const Grid* g, int i, int j, int k) {
  if (!g->sparse) return v[i + g->nx * (j + g->ny * k)];
  const int tx = (g->nx + 7) / 8, ty = (g->ny + 7) / 8, tz = (g->nz + 7) / 8;
  const ulong tiles = (ulong)tx * ty * tz;
  const ulong t = (ulong)(i / 8) + (ulong)tx * ((ulong)(j / 8) + (ulong)ty * (ulong)(k / 8));
  const int slot = as_int(v[t]);
  if (slot < 0) return v[tiles + t];
  return v[2 * tiles + (ulong)slot * 512 + (ulong)(i % 8 + 8 * (j % 8 + 8 * (k % 8)))];
}

float signed_at(__global const float* v, const Grid* g, int i, int j, int k) {
  const float x = raw_at(v, g, i, j, k);
  return isfinite(x) ? g->sign * (x - g->iso) : -1.0f;
}

// The cell of index point p, clamped into the domain: its corners' signed values and p's
// position in it (0..1 per axis).
typedef struct {
  float s000, s100, s010, s110, s001, s101, s011, s111;
  float3 f;
} Cell;

__attribute__((always_inline)) Cell cell_at(__global const float* v, const Grid* g, float3 p) {
  const float3 hi = (float3)(g->nx - 1, g->ny - 1, g->nz - 1);
  const float3 q = clamp(p, (float3)(0.0f), hi);
  const int3 c = min(convert_int3(floor(q)), (int3)(g->nx - 2, g->ny - 2, g->nz - 2));
  Cell k;
  k.f = q - convert_float3(c);
  k.s000 = signed_at(v, g, c.x, c.y, c.z), k.s100 = signed_at(v, g, c.x + 1, c.y, c.z);
  k.s010 = signed_at(v, g, c.x, c.y + 1, c.z), k.s110 = signed_at(v, g, c.x + 1, c.y + 1, c.z);
  k.s001 = signed_at(v, g, c.x, c.y, c.z + 1), k.s101 = signed_at(v, g, c.x + 1, c.y, c.z + 1);
  k.s011 = signed_at(v, g, c.x, c.y + 1, c.z + 1);
  k.s111 = signed_at(v, g, c.x + 1, c.y + 1, c.z + 1);
  return k;
}

// The trilinear signed field at index point p and its index-space gradient (of the trilinear
// interpolant): DenseField::field with a gradient.
float field_grad_at(__global const float* v, const Grid* g, float3 p, float3* grad) {
  const Cell k = cell_at(v, g, p);
  const float3 f = k.f;
  const float x00 = k.s000 + (k.s100 - k.s000) * f.x, x10 = k.s010 + (k.s110 - k.s010) * f.x;
  const float x01 = k.s001 + (k.s101 - k.s001) * f.x, x11 = k.s011 + (k.s111 - k.s011) * f.x;
  const float y0 = x00 + (x10 - x00) * f.y, y1 = x01 + (x11 - x01) * f.y;
  const float dx00 = k.s100 - k.s000, dx10 = k.s110 - k.s010;
  const float dx01 = k.s101 - k.s001, dx11 = k.s111 - k.s011;
  const float dx0 = dx00 + (dx10 - dx00) * f.y, dx1 = dx01 + (dx11 - dx01) * f.y;
  const float dy0 = x10 - x00, dy1 = x11 - x01;
  *grad = (float3)(dx0 + (dx1 - dx0) * f.z, dy0 + (dy1 - dy0) * f.z, y1 - y0);
  return y0 + (y1 - y0) * f.z;
}

// The trilinear signed field at index point p, clamped into the domain (DenseField::field):
// field_grad_at's value without its gradient (the march's hot path: PoCL does not inline
// field_grad_at, so a wrapper would pay for the gradient too).
__attribute__((always_inline)) float field_at(__global const float* v, const Grid* g, float3 p) {
  const Cell k = cell_at(v, g, p);
  const float3 f = k.f;
  const float x00 = k.s000 + (k.s100 - k.s000) * f.x, x10 = k.s010 + (k.s110 - k.s010) * f.x;
  const float x01 = k.s001 + (k.s101 - k.s001) * f.x, x11 = k.s011 + (k.s111 - k.s011) * f.x;
  const float y0 = x00 + (x10 - x00) * f.y, y1 = x01 + (x11 - x01) * f.y;
  return y0 + (y1 - y0) * f.z;
}

// Central (one-sided at the border) difference at sample c.
float3 sample_gradient(__global const float* v, const Grid* g, int3 c) {
  const int3 n = (int3)(g->nx, g->ny, g->nz);
  float3 r;
  const int xh = min(c.x + 1, n.x - 1), xl = max(c.x - 1, 0);
  const int yh = min(c.y + 1, n.y - 1), yl = max(c.y - 1, 0);
  const int zh = min(c.z + 1, n.z - 1), zl = max(c.z - 1, 0);
  r.x = xh == xl ? 0.0f : (raw_at(v, g, xh, c.y, c.z) - raw_at(v, g, xl, c.y, c.z)) / (xh - xl);
  r.y = yh == yl ? 0.0f : (raw_at(v, g, c.x, yh, c.z) - raw_at(v, g, c.x, yl, c.z)) / (yh - yl);
  r.z = zh == zl ? 0.0f : (raw_at(v, g, c.x, c.y, zh) - raw_at(v, g, c.x, c.y, zl)) / (zh - zl);
  return r;
}

// Gradients at the samples, interpolated trilinearly (DenseField::normal, before the transform).
float3 gradient_at(__global const float* v, const Grid* g, float3 p) {
  const float3 hi = (float3)(g->nx - 1, g->ny - 1, g->nz - 1);
  const float3 q = clamp(p, (float3)(0.0f), hi);
  const int3 c0 = convert_int3(floor(q));
  const float3 f = q - convert_float3(c0);
  float3 r = (float3)(0.0f);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const float w = (i ? f.x : 1 - f.x) * (j ? f.y : 1 - f.y) * (k ? f.z : 1 - f.z);
        if (w == 0.0f) continue;
        const int3 c = min(c0 + (int3)(i, j, k), (int3)(g->nx - 1, g->ny - 1, g->nz - 1));
        r += w * sample_gradient(v, g, c);
      }
  return r;
}

float3 affine(__constant const float* m, float3 p) {
  return (float3)(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
                  m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                  m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]);
}
float3 linear3(__constant const float* m, int stride, float3 p) {
  return (float3)(m[0] * p.x + m[1] * p.y + m[2] * p.z,
                  m[stride] * p.x + m[stride + 1] * p.y + m[stride + 2] * p.z,
                  m[2 * stride] * p.x + m[2 * stride + 1] * p.y + m[2 * stride + 2] * p.z);
}

