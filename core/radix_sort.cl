// Stable LSD radix sort of (key, value) uint pairs, `bits` (1..MAX_RADIX_BITS) a pass, over P
// contiguous chunks: per-chunk digit histograms stored digit-major (hist[d * P + c]), an exclusive
// scan of them, then a sequential stable scatter per chunk. Deterministic: the result depends
// only on the input.

// MAX_RADIX_BITS: the widest digit, defined by the build options (core/cl_radix_sort.cpp).

__kernel void radix_histogram(__global const uint* keys, uint n, uint chunk, uint shift, uint bits, uint p,
                              __global uint* hist) {
  uint c = get_global_id(0);
  if (c >= p) return;
  uint radix = 1u << bits, mask = radix - 1u;
  uint count[1 << MAX_RADIX_BITS];
  for (uint d = 0; d < radix; ++d) count[d] = 0;
  uint begin = c * chunk, end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) count[(keys[i] >> shift) & mask]++;
  for (uint d = 0; d < radix; ++d) hist[d * p + c] = count[d];
}

__kernel void radix_scatter(__global const uint* keys, __global const uint* values, uint n, uint chunk,
                            uint shift, uint bits, uint p, __global const uint* offsets,
                            __global uint* keys_out, __global uint* values_out) {
  uint c = get_global_id(0);
  if (c >= p) return;
  uint radix = 1u << bits, mask = radix - 1u;
  uint offset[1 << MAX_RADIX_BITS];
  for (uint d = 0; d < radix; ++d) offset[d] = offsets[d * p + c];
  uint begin = c * chunk, end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) {
    uint k = keys[i];
    uint dst = offset[(k >> shift) & mask]++;
    keys_out[dst] = k;
    values_out[dst] = values[i];
  }
}
