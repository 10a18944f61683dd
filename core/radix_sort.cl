// Stable LSD radix sort of (key, value) uint pairs, 11 bits a pass (three for 32-bit keys), over P contiguous chunks:
// per-chunk digit histograms stored digit-major (hist[d * P + c]), an exclusive scan of them, then
// a sequential stable scatter per chunk. Deterministic: the result depends only on the input.

#define RADIX_BITS 11  // core/cl_radix_sort.cpp kRadixBits, keep equal
#define RADIX (1 << RADIX_BITS)

__kernel void radix_histogram(__global const uint* keys, uint n, uint chunk, uint shift, uint p,
                              __global uint* hist) {
  uint c = get_global_id(0);
  if (c >= p) return;
  uint count[RADIX];
  for (int d = 0; d < RADIX; ++d) count[d] = 0;
  uint begin = c * chunk, end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) count[(keys[i] >> shift) & (RADIX - 1u)]++;
  for (int d = 0; d < RADIX; ++d) hist[d * p + c] = count[d];
}

__kernel void radix_scatter(__global const uint* keys, __global const uint* values, uint n, uint chunk,
                            uint shift, uint p, __global const uint* offsets,
                            __global uint* keys_out, __global uint* values_out) {
  uint c = get_global_id(0);
  if (c >= p) return;
  uint offset[RADIX];
  for (int d = 0; d < RADIX; ++d) offset[d] = offsets[d * p + c];
  uint begin = c * chunk, end = min(begin + chunk, n);
  for (uint i = begin; i < end; ++i) {
    uint k = keys[i];
    uint dst = offset[(k >> shift) & (RADIX - 1u)]++;
    keys_out[dst] = k;
    values_out[dst] = values[i];
  }
}
