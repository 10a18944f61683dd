// Exclusive prefix sum of uint arrays, in three passes over P contiguous chunks:
// per-chunk totals, a serial scan of the P totals, then a sequential scan of each chunk from its
// offset. Sequential runs per work item suit CPU devices; integer sums make it deterministic.

__kernel void scan_chunk_totals(__global const uint* in, uint n, uint chunk, uint p, __global uint* totals) {
  uint c = get_global_id(0);
  if (c >= p) return;
  uint begin = c * chunk, end = min(begin + chunk, n);
  uint sum = 0;
  for (uint i = begin; i < end; ++i) sum += in[i];
  totals[c] = sum;
}

// One work item: exclusive scan of totals[0..p) in place; totals[p] and result[index] receive the
// grand total.
__kernel void scan_totals(__global uint* totals, uint p, __global uint* result, uint index) {
  if (get_global_id(0) != 0) return;
  uint sum = 0;
  for (uint i = 0; i < p; ++i) {
    uint v = totals[i];
    totals[i] = sum;
    sum += v;
  }
  totals[p] = sum;
  result[index] = sum;
}

__kernel void scan_chunks(__global const uint* in, __global uint* out, uint n, uint chunk, uint p,
                          __global const uint* offsets) {
  uint c = get_global_id(0);
  if (c >= p) return;
  uint begin = c * chunk, end = min(begin + chunk, n);
  uint sum = offsets[c];
  for (uint i = begin; i < end; ++i) {
    uint v = in[i];
    out[i] = sum;
    sum += v;
  }
}
