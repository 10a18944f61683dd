// Marching cubes with vertex fusion (after Griffin et al. 2012, section 3.4).
// Input: bricks of 9x9x9 signed samples (> 0 inside), x fastest, and each brick's index-space
// origin. A brick holds 8x8x8 cells; global id = brick * 512 + cell, cell = x + 8 y + 64 z.
// Mirrors mc/case_table.h (corner/edge numbering), mc/edge_key.h (keys, hash) and mc/frame.h
// (edge_fraction), which the C++ reference uses.
//
// Each crossed cube edge is emitted once, by the cell that owns it: the cell whose lower corner is
// the edge's lower end (or, for edges on the frame's upper faces, the last cell below them). The
// vertices carry a hash of their edge's identity and are radix sorted by it; each triangle corner
// then finds its vertex by a binary search for the hash and a walk over equal hashes comparing
// edge identities. The output has no duplicate and no unreferenced vertex by construction.

#define APRON 9
#define BRICK_SAMPLES 729

__constant int corner_offset[8] = {0, 1, 1 + APRON, APRON, APRON * APRON, 1 + APRON * APRON,
                                   1 + APRON + APRON * APRON, APRON + APRON * APRON};
__constant int corner_x[8] = {0, 1, 1, 0, 0, 1, 1, 0};
__constant int corner_y[8] = {0, 0, 1, 1, 0, 0, 1, 1};
__constant int corner_z[8] = {0, 0, 0, 0, 1, 1, 1, 1};
__constant int edge_low[12] = {0, 1, 3, 0, 4, 5, 7, 4, 0, 1, 3, 2};
__constant int edge_high[12] = {1, 2, 2, 3, 5, 6, 6, 7, 4, 5, 7, 6};
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

// Bit e set when cube edge e joins an inside corner to an outside one.
inline uint crossed_edges(int index) {
  uint mask = 0;
  for (int e = 0; e < 12; ++e)
    mask |= (uint)(((index >> edge_low[e]) ^ (index >> edge_high[e])) & 1) << e;
  return mask;
}

// Bit e set when this cell owns edge e: the edge's lower end is the cell's lower corner, except
// along an axis where the cell is the frame's last, whose upper face it owns too.
inline uint owned_edges(int4 g, int4 cell_max) {
  int mx = g.x == cell_max.x, my = g.y == cell_max.y, mz = g.z == cell_max.z;
  uint mask = 0;
  for (int e = 0; e < 12; ++e) {
    int lo = edge_low[e];
    if ((!corner_x[lo] || mx) && (!corner_y[lo] || my) && (!corner_z[lo] || mz)) mask |= 1u << e;
  }
  return mask;
}

// Per cell: triangles, and the crossed edges it owns (0 outside the frame's cells).
__kernel void mc_classify(__global const float* samples, __global const int4* origins, uint ncells,
                          int4 cell_min, int4 cell_max, __global const uchar* tri_count,
                          __global uint* tri_counts, __global uint* vertex_counts) {
  uint gid = get_global_id(0);
  if (gid >= ncells) return;
  __global const float* s;
  int4 g = cell_coord(origins, gid, &s, samples);
  uint ntri = 0, nvert = 0;
  if (cell_valid(g, cell_min, cell_max)) {
    int index = cell_case(s);
    ntri = tri_count[index];
    if (ntri) nvert = popcount(crossed_edges(index) & owned_edges(g, cell_max));
  }
  tri_counts[gid] = ntri;
  vertex_counts[gid] = nvert;
}

inline ulong edge_key(uint x, uint y, uint z, uint axis) {
  return ((ulong)x << 42) | ((ulong)y << 22) | ((ulong)z << 2) | (ulong)axis;
}

// 32-bit hash of an edge (key coordinates x, y, z and axis), spatially coherent: 8^3-voxel
// blocks in order, 1536 edge slots each, wrapping past 2^32 (over 2.8 million blocks), then
// masked. Sorting by it keeps neighbouring edges together, so lookups stay in cache.
inline uint edge_hash(uint x, uint y, uint z, uint axis, uint2 blocks, uint mask) {
  uint block = (x >> 3) + blocks.x * ((y >> 3) + blocks.y * (z >> 3));
  uint slot = (((z & 7u) << 6) | ((y & 7u) << 3) | (x & 7u)) * 3u + axis;
  return (block * 1536u + slot) & mask;
}

// Key and hash of cube edge e of the cell at g.
inline ulong cell_edge(int4 g, int e, int4 key_origin, uint2 blocks, uint mask, uint* hash) {
  int lo = edge_low[e];
  uint x = (uint)(g.x + corner_x[lo] - key_origin.x), y = (uint)(g.y + corner_y[lo] - key_origin.y),
       z = (uint)(g.z + corner_z[lo] - key_origin.z), axis = (uint)edge_axis[e];
  *hash = edge_hash(x, y, z, axis, blocks, mask);
  return edge_key(x, y, z, axis);
}

// One vertex per owned crossed edge, from vertex_offsets[gid] on, in edge order: its world
// position, edge key and hash, and its own index (the sort's value).
__kernel void mc_generate(__global const float* samples, __global const int4* origins, uint ncells,
                          int4 cell_max, int4 key_origin,
                          __global const uint* vertex_offsets, uint nvertices, float min_fraction,
                          float16 world, uint2 blocks, uint hash_mask,
                          __global float* positions, __global ulong* keys,
                          __global uint* hashes, __global uint* order) {
  uint gid = get_global_id(0);
  if (gid >= ncells) return;
  uint v = vertex_offsets[gid];
  if ((gid + 1 < ncells ? vertex_offsets[gid + 1] : nvertices) == v) return;
  __global const float* s;
  int4 g = cell_coord(origins, gid, &s, samples);
  uint edges = crossed_edges(cell_case(s)) & owned_edges(g, cell_max);
  for (int e = 0; e < 12; ++e) {
    if (!(edges & (1u << e))) continue;
    int lo = edge_low[e], axis = edge_axis[e];
    float s0 = s[corner_offset[lo]], s1 = s[corner_offset[lo] + axis_step[axis]];
    float t = s0 / (s0 - s1);
    t = fmin(fmax(t, min_fraction), 1.0f - min_fraction);
    float px = (float)(g.x + corner_x[lo]) + (axis == 0 ? t : 0.0f);
    float py = (float)(g.y + corner_y[lo]) + (axis == 1 ? t : 0.0f);
    float pz = (float)(g.z + corner_z[lo]) + (axis == 2 ? t : 0.0f);
    positions[3 * v + 0] = world.s0 * px + world.s1 * py + world.s2 * pz + world.s3;
    positions[3 * v + 1] = world.s4 * px + world.s5 * py + world.s6 * pz + world.s7;
    positions[3 * v + 2] = world.s8 * px + world.s9 * py + world.sa * pz + world.sb;
    uint h;
    keys[v] = cell_edge(g, e, key_origin, blocks, hash_mask, &h);
    hashes[v] = h;
    order[v] = v;
    ++v;
  }
}

// The lookup table, from the sorted (hash, vertex) pairs: entries[j] = (hash, vertex, key) side by
// side (one cache line per probe), and starts[b] = first j whose hash's top bits (hash >> shift)
// are >= b, for b in [0, nbuckets]. One work item per j in [0, n]; every entry is written once.
__kernel void mc_table(__global const uint* sorted_hashes, __global const uint* sorted_order,
                       __global const ulong* keys, uint n, uint shift, uint nbuckets,
                       __global uint4* entries, __global uint* starts) {
  uint j = get_global_id(0);
  if (j > n) return;
  long cur = (long)nbuckets;
  if (j < n) {
    uint h = sorted_hashes[j], u = sorted_order[j];
    ulong key = keys[u];
    entries[j] = (uint4)(h, u, (uint)key, (uint)(key >> 32));
    cur = (long)(h >> shift);
  }
  long prev = j > 0 ? (long)(sorted_hashes[j - 1] >> shift) : -1;
  for (long b = prev + 1; b <= cur; ++b) starts[b] = j;
}

// The vertex of edge `key` (hash h): a binary search for the first entry with hash h (within the
// bucket of h's top bits), then a walk over the entries of equal hash comparing edge keys, which
// resolves collisions. ~0 only if the edge's owner was not processed (a bug).
inline uint find_vertex(ulong key, uint h, __global const uint4* entries, uint n,
                        __global const uint* starts, uint shift) {
  uint b = h >> shift;
  uint lo = starts[b], len = starts[b + 1] - lo;
  while (len > 0) {  // lower bound of h in [lo, lo + len), without branches on the data
    uint step = len >> 1, mid = lo + step;
    bool less = entries[mid].x < h;
    lo = less ? mid + 1 : lo;
    len = less ? len - step - 1 : step;
  }
  uint klo = (uint)key, khi = (uint)(key >> 32);
  for (uint j = lo; j < n; ++j) {
    uint4 t = entries[j];
    if (t.x != h) break;
    if (t.z == klo && t.w == khi) return t.y;
  }
  return 0xffffffffu;
}

// The index kernel, per cell: the vertex of each crossed edge, then every triangle corner's.
// Edges the cell owns are its own vertices (in edge order from its offset); the others are looked
// up once each by their hash (find_vertex).
__kernel void mc_index(__global const float* samples, __global const int4* origins, uint ncells,
                       int4 cell_max, int4 key_origin, uint2 blocks, uint hash_mask,
                       __global const char* tri_edges,
                       __global const uint* tri_offsets, uint ntriangles, __global const uint* vertex_offsets,
                       __global const uint4* entries, uint n, __global const uint* starts, uint shift,
                       __global uint* triangles) {
  uint gid = get_global_id(0);
  if (gid >= ncells) return;
  uint first = tri_offsets[gid];
  uint ntri = (gid + 1 < ncells ? tri_offsets[gid + 1] : ntriangles) - first;
  if (ntri == 0) return;
  __global const float* s;
  int4 g = cell_coord(origins, gid, &s, samples);
  int index = cell_case(s);
  uint crossed = crossed_edges(index), owned = crossed & owned_edges(g, cell_max);
  uint vertex[12];
  uint v = vertex_offsets[gid];
  for (int e = 0; e < 12; ++e) {
    if (!(crossed & (1u << e))) continue;
    if (owned & (1u << e)) {
      vertex[e] = v++;
    } else {
      uint h;
      ulong key = cell_edge(g, e, key_origin, blocks, hash_mask, &h);
      vertex[e] = find_vertex(key, h, entries, n, starts, shift);
    }
  }
  __global uint* out = triangles + 3 * (size_t)first;
  for (int k = 0; k < 3 * (int)ntri; ++k) out[k] = vertex[tri_edges[index * 16 + k]];
}
