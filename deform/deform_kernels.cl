// Deformers writing vertex positions in place on the device (deform/*.h). Positions and normals
// are packed float x, y, z (12 bytes a vertex). Every kernel ignores ids >= vertex_count.

// out = M p with M a 3 x 4 row-major affine matrix (m[0..3] the first row).
__kernel void affine_positions(__global const float* rest, const uint vertex_count,
                               __constant const float* m, __global float* out) {
  const uint i = get_global_id(0);
  if (i >= vertex_count) return;
  const float x = rest[3 * i], y = rest[3 * i + 1], z = rest[3 * i + 2];
  for (int r = 0; r < 3; ++r)
    out[3 * i + r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3];
}

// The smooth noise field of noise_displace.h: the mean of WAVES plane waves
// sin(frequency * dir_k . p + phase_k); waves holds (dir_k, phase_k) as float4.
float smooth_noise(const float3 p, __constant const float4* waves, const int wave_count,
                   const float frequency) {
  float sum = 0.0f;
  for (int k = 0; k < wave_count; ++k) {
    const float4 w = waves[k];
    sum += sin(frequency * (w.x * p.x + w.y * p.y + w.z * p.z) + w.w);
  }
  return sum / (float)wave_count;
}

// out = p + amplitude * noise(p) * n, n the rest normal.
__kernel void noise_displace(__global const float* rest, __global const float* normals,
                             const uint vertex_count, __constant const float4* waves,
                             const int wave_count, const float frequency, const float amplitude,
                             __global float* out) {
  const uint i = get_global_id(0);
  if (i >= vertex_count) return;
  const float3 p = (float3)(rest[3 * i], rest[3 * i + 1], rest[3 * i + 2]);
  const float3 n = (float3)(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
  const float3 q = p + (amplitude * smooth_noise(p, waves, wave_count, frequency)) * n;
  out[3 * i] = q.x;
  out[3 * i + 1] = q.y;
  out[3 * i + 2] = q.z;
}

// Linear blend skinning: out = sum_j weight_j (M_{bone_j} p), four (bone, weight) pairs a vertex
// (unused pairs have weight 0), M the bones' 3 x 4 row-major matrices, summed in slot order.
__kernel void skin_positions(__global const float* rest, __global const uint4* bones,
                             __global const float4* weights, const uint vertex_count,
                             __global const float* matrices, __global float* out) {
  const uint i = get_global_id(0);
  if (i >= vertex_count) return;
  const float x = rest[3 * i], y = rest[3 * i + 1], z = rest[3 * i + 2];
  const uint b[4] = {bones[i].x, bones[i].y, bones[i].z, bones[i].w};
  const float4 w4 = weights[i];
  const float w[4] = {w4.x, w4.y, w4.z, w4.w};
  float acc[3] = {0.0f, 0.0f, 0.0f};
  for (int j = 0; j < 4; ++j) {
    if (w[j] == 0.0f) continue;
    __global const float* m = matrices + 12 * b[j];
    for (int r = 0; r < 3; ++r)
      acc[r] += w[j] * (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]);
  }
  out[3 * i] = acc[0];
  out[3 * i + 1] = acc[1];
  out[3 * i + 2] = acc[2];
}
