// Marching cubes with vertex fusion (Griffin et al. 2012, section 3.4).
// Input: bricks of 9x9x9 signed samples (> 0 inside), x fastest, and each brick's index-space
// origin. A brick holds 8x8x8 cells; global id = brick * 512 + cell, cell = x + 8 y + 64 z.
// Mirrors mc/case_table.h (corner/edge numbering), mc/edge_key.h (keys, hash) and mc/frame.h
// (edge_fraction), which the C++ reference uses.

#define APRON 9
#define BRICK_SAMPLES 729

__constant int corner_offset[8] = {0, 1, 1 + APRON, APRON, APRON * APRON, 1 + APRON * APRON,
                                   1 + APRON + APRON * APRON, APRON + APRON * APRON};
__constant int corner_x[8] = {0, 1, 1, 0, 0, 1, 1, 0};
__constant int corner_y[8] = {0, 0, 1, 1, 0, 0, 1, 1};
__constant int corner_z[8] = {0, 0, 0, 0, 1, 1, 1, 1};
__constant int edge_low[12] = {0, 1, 3, 0, 4, 5, 7, 4, 0, 1, 3, 2};
__constant int edge_axis[12] = {0, 1, 0, 1, 0, 1, 0, 1, 2, 2, 2, 2};
__constant int axis_step[3] = {1, APRON, APRON * APRON};

inline int cell_case(__global const float* s) {
  int index = 0;
  for (int c = 0; c < 8; ++c)
    if (s[corner_offset[c]] > 0.0f) index |= 1 << c;
  return index;
}

// True when the cell's lower corner lies in [cell_min, cell_max].
inline bool cell_valid(int4 g, int4 cell_min, int4 cell_max) {
  return g.x >= cell_min.x && g.y >= cell_min.y && g.z >= cell_min.z &&
         g.x <= cell_max.x && g.y <= cell_max.y && g.z <= cell_max.z;
}

inline int4 cell_coord(__global const int4* origins, uint gid, __global const float** s,
                       __global const float* samples) {
  uint b = gid >> 9, c = gid & 511u;
  int x = c & 7, y = (c >> 3) & 7, z = c >> 6;
  *s = samples + (size_t)b * BRICK_SAMPLES + x + APRON * y + APRON * APRON * z;
  int4 o = origins[b];
  return (int4)(o.x + x, o.y + y, o.z + z, 0);
}

// Triangles per cell (0 outside the frame's cells).
__kernel void mc_classify(__global const float* samples, __global const int4* origins, uint ncells,
                          int4 cell_min, int4 cell_max, __global const uchar* tri_count,
                          __global uint* counts) {
  uint gid = get_global_id(0);
  if (gid >= ncells) return;
  __global const float* s;
  int4 g = cell_coord(origins, gid, &s, samples);
  counts[gid] = cell_valid(g, cell_min, cell_max) ? tri_count[cell_case(s)] : 0u;
}

inline ulong edge_key(uint x, uint y, uint z, uint axis) {
  return ((ulong)x << 42) | ((ulong)y << 22) | ((ulong)z << 2) | (ulong)axis;
}

inline uint edge_hash(ulong key, uint mask) {
  key ^= key >> 33;
  key *= 0xff51afd7ed558ccdUL;
  key ^= key >> 33;
  key *= 0xc4ceb9fe1a85ec53UL;
  key ^= key >> 33;
  return (uint)key & mask;
}

// One unfused vertex per triangle corner: position (world), edge key, hash, and its own index
// as the sort value. offsets[gid] = first triangle of the cell.
__kernel void mc_generate(__global const float* samples, __global const int4* origins, uint ncells,
                          int4 cell_min, int4 cell_max, int4 key_origin,
                          __global const uchar* tri_count, __global const char* tri_edges,
                          __global const uint* offsets, float min_fraction,
                          float16 world, uint hash_mask,
                          __global float* positions, __global ulong* keys,
                          __global uint* hashes, __global uint* order) {
  uint gid = get_global_id(0);
  if (gid >= ncells) return;
  __global const float* s;
  int4 g = cell_coord(origins, gid, &s, samples);
  if (!cell_valid(g, cell_min, cell_max)) return;
  int index = cell_case(s);
  int ntri = tri_count[index];
  uint v = offsets[gid] * 3u;
  for (int k = 0; k < 3 * ntri; ++k, ++v) {
    int e = tri_edges[index * 16 + k];
    int lo = edge_low[e], axis = edge_axis[e];
    float s0 = s[corner_offset[lo]], s1 = s[corner_offset[lo] + axis_step[axis]];
    float t = s0 / (s0 - s1);
    t = fmin(fmax(t, min_fraction), 1.0f - min_fraction);
    int ax = g.x + corner_x[lo], ay = g.y + corner_y[lo], az = g.z + corner_z[lo];
    float px = (float)ax + (axis == 0 ? t : 0.0f);
    float py = (float)ay + (axis == 1 ? t : 0.0f);
    float pz = (float)az + (axis == 2 ? t : 0.0f);
    positions[3 * v + 0] = world.s0 * px + world.s1 * py + world.s2 * pz + world.s3;
    positions[3 * v + 1] = world.s4 * px + world.s5 * py + world.s6 * pz + world.s7;
    positions[3 * v + 2] = world.s8 * px + world.s9 * py + world.sa * pz + world.sb;
    ulong key = edge_key((uint)(ax - key_origin.x), (uint)(ay - key_origin.y),
                         (uint)(az - key_origin.z), (uint)axis);
    keys[v] = key;
    hashes[v] = edge_hash(key, hash_mask);
    order[v] = v;
  }
}

// Where each bucket of sorted hashes begins: starts[b] = first j with (sorted_hashes[j] >> shift)
// >= b, for b in [0, nbuckets]. One work item per j in [0, n]; every entry is written once.
__kernel void mc_bucket_starts(__global const uint* sorted_hashes, uint n, uint shift, uint nbuckets,
                               __global uint* starts) {
  uint j = get_global_id(0);
  if (j > n) return;
  long cur = j < n ? (long)(sorted_hashes[j] >> shift) : (long)nbuckets;
  long prev = j > 0 ? (long)(sorted_hashes[j - 1] >> shift) : -1;
  for (long b = prev + 1; b <= cur; ++b) starts[b] = j;
}

// The index kernel: for vertex i, binary search its hash among the sorted hashes (within the
// bucket of its top bits), walk back to the first equal hash, then forward comparing edge keys to
// resolve collisions. The match found first is the smallest vertex index on that edge (the sort is
// stable): its representative.
__kernel void mc_fuse(__global const uint* hashes, __global const ulong* keys,
                      __global const uint* sorted_hashes, __global const uint* sorted_order, uint n,
                      __global const uint* starts, uint shift,
                      __global uint* representative, __global uint* is_first) {
  uint i = get_global_id(0);
  if (i >= n) return;
  uint h = hashes[i];
  uint b = h >> shift;
  int lo = (int)starts[b], hi = (int)starts[b + 1] - 1, j = lo;
  while (lo <= hi) {  // finds some entry equal to h: i's own hash is in this bucket
    int mid = lo + (hi - lo) / 2;
    uint m = sorted_hashes[mid];
    if (m < h) lo = mid + 1;
    else if (m > h) hi = mid - 1;
    else { j = mid; break; }
  }
  while (j > 0 && sorted_hashes[j - 1] == h) --j;
  ulong key = keys[i];
  uint rep = i;
  for (; (uint)j < n && sorted_hashes[j] == h; ++j) {
    uint u = sorted_order[j];
    if (keys[u] == key) { rep = u; break; }
  }
  representative[i] = rep;
  is_first[i] = rep == i ? 1u : 0u;
}

// Compaction: the first vertex of each edge moves to its fused index; every triangle corner gets
// the fused index of its representative.
__kernel void mc_compact(__global const float* positions, __global const ulong* keys,
                         __global const uint* representative, __global const uint* is_first,
                         __global const uint* fused_index, uint n,
                         __global float* out_positions, __global ulong* out_keys, uint write_keys,
                         __global uint* out_triangles) {
  uint i = get_global_id(0);
  if (i >= n) return;
  if (is_first[i]) {
    uint f = fused_index[i];
    out_positions[3 * f + 0] = positions[3 * i + 0];
    out_positions[3 * f + 1] = positions[3 * i + 1];
    out_positions[3 * f + 2] = positions[3 * i + 2];
    if (write_keys) out_keys[f] = keys[i];
  }
  out_triangles[i] = fused_index[representative[i]];
}
