// Marching cubes with vertex fusion (after Griffin et al. 2012, section 3.4).
// Input: bricks of 9x9x9 signed samples (> 0 inside), z fastest (sample z + 9 y + 81 x, as in a
// VDB leaf), and each brick's index-space origin. A brick holds 8x8x8 cells, cell z + 8 y + 64 x;
// a row is the 8 cells along z at one (x, y). One work item per brick walks its cells in order: on
// a CPU device that keeps the samples in cache, reuses each sample row across the cells that
// share it, and pays no per-cell work-item cost; a row of empty cells costs one 8-byte test.
// Mirrors mc/case_table.h (corner/edge numbering), mc/edge_key.h (keys, hash) and mc/frame.h
// (edge_fraction), which the C++ reference uses.
//
// Each crossed cube edge gets one vertex, from the cell that owns it: the cell whose lower corner
// is the edge's lower end (or, for edges on the frame's upper faces, the last cell below them).
// Steps: mc_classify (cases; triangles, vertices and seam vertices per brick), scans, mc_seams
// (the vertices other bricks will look up, with a hash of their edge's identity), radix sort by
// hash, mc_table, mc_emit (positions and triangles). A cell finds the vertex of an edge owned in
// its own brick directly (mc_emit records the brick's vertices in a map before it writes
// triangles), and one owned by a brick above from the same map: before its walk, each brick
// records the seam vertices on the faces it shares with the bricks above, found as runs of the
// sorted hashes (the hash numbers a block's lower faces as a few runs) and placed by their edge
// keys. The output has no duplicate and no unreferenced vertex by construction.

// APRON, BRICK_SAMPLES and McEmitParams come from mc/detail/mc_layout.h, prepended by the host.

__constant int corner_offset[8] = {0, APRON * APRON, APRON * APRON + APRON, APRON, 1, APRON * APRON + 1,
                                   APRON * APRON + APRON + 1, APRON + 1};
__constant int corner_x[8] = {0, 1, 1, 0, 0, 1, 1, 0};
__constant int corner_y[8] = {0, 0, 1, 1, 0, 0, 1, 1};
__constant int corner_z[8] = {0, 0, 0, 0, 1, 1, 1, 1};
__constant int edge_low[12] = {0, 1, 3, 0, 4, 5, 7, 4, 0, 1, 3, 2};
__constant int edge_axis[12] = {0, 1, 0, 1, 0, 1, 0, 1, 2, 2, 2, 2};
__constant int axis_step[3] = {APRON * APRON, APRON, 1};

// Bit e set when the cell at g owns edge e: the edge's lower end is the cell's lower corner,
// except along an axis where the cell is the frame's last, whose upper face it owns too.
inline uint owned_edges(int4 g, int4 cell_max) {
  if (g.x != cell_max.x && g.y != cell_max.y && g.z != cell_max.z) return 0x109u;  // edges 0, 3, 8
  int mx = g.x == cell_max.x, my = g.y == cell_max.y, mz = g.z == cell_max.z;
  uint mask = 0;
  for (int e = 0; e < 12; ++e) {
    int lo = edge_low[e];
    if ((!corner_x[lo] || mx) && (!corner_y[lo] || my) && (!corner_z[lo] || mz)) mask |= 1u << e;
  }
  return mask;
}

// Index of the lowest set bit of m (m != 0).
inline uint lowest_bit(uint m) { return 31u - clz(m & (~m + 1u)); }

// Bit z set for each cell of a row (8 case bytes, cell z at byte z) that has triangles, i.e. whose
// case is neither 0 nor 255 (not all of its bits equal).
inline uint row_cells(__global const uchar* row_cases) {
#ifdef __ENDIAN_LITTLE__
  ulong r = *(__global const ulong*)row_cases;  // 8-byte aligned: rows start at multiples of 8
  ulong t = (r ^ (r << 1)) & 0xfefefefefefefefeUL;  // byte z nonzero iff cell z has triangles
  ulong nonzero = (((t & 0x7f7f7f7f7f7f7f7fUL) + 0x7f7f7f7f7f7f7f7fUL) | t) & 0x8080808080808080UL;
  return (uint)(((nonzero >> 7) * 0x0102040810204080UL) >> 56);  // byte z's flag to bit z
#else
  uint cells = 0;
  for (int z = 0; z < 8; ++z) cells |= (uint)(row_cases[z] != 0 && row_cases[z] != 255) << z;
  return cells;
#endif
}

// A row's 8 case bytes as one number, cell z's case in byte z (bits 8 z .. 8 z + 7).
inline ulong row_cases(__global const uchar* bytes) {
#ifdef __ENDIAN_LITTLE__
  return *(__global const ulong*)bytes;  // 8-byte aligned: rows start at multiples of 8
#else
  ulong r = 0;
  for (int z = 0; z < 8; ++z) r |= (ulong)bytes[z] << (8 * z);
  return r;
#endif
}

// Bit z set when bit k of byte z of r is set (corner k of cell z, for a row's cases).
inline uint byte_bits(ulong r, int k) {
  return (uint)((((r >> k) & 0x0101010101010101UL) * 0x0102040810204080UL) >> 56);
}

// Byte z of the result holds bit z of m (bits 0-7), each nibble spread by one multiplication
// (the partial products land on distinct bits, so nothing carries).
inline ulong spread8(uint m) {
  return (ulong)((m & 15u) * 0x204081u & 0x01010101u) | (ulong)(((m >> 4) & 15u) * 0x204081u & 0x01010101u) << 32;
}

// The cells of brick b's 8^3 that lie in [cell_min, cell_max]: local ranges lo..hi per axis.
inline void brick_range(int4 o, int4 cell_min, int4 cell_max, int4* lo, int4* hi) {
  *lo = max((int4)(0), cell_min - o);
  *hi = min((int4)(7), cell_max - o);
}

// The edges a cell of another brick uses, by where the cell lies: seam_table[(x == 0) |
// (y == 0) << 1 | (z == 0) << 2] (local coordinates) has bit e set when edge e's lower end is 0
// along an axis across the edge (the cells there lie one brick down).
__constant ushort seam_table[8] = {0x0, 0x588, 0x311, 0x799, 0xf, 0x58f, 0x31f, 0x79f};

// Per brick: every cell's case into cases[512 b ..] (0 for cells outside the frame and for rows
// with no triangles, whatever their case); the brick's
// triangles, vertices (owned crossed edges) and seam vertices (those other bricks use); and for
// each row of cells (x, y) the number of the brick's vertices before it, into row_ranks[64 b ..].
// crossed[case]: bit e set when edge e joins an inside corner to an outside one.
__kernel void mc_classify(__global const float* samples, __global const int4* origins, uint nbricks,
                          int4 cell_min, int4 cell_max, __global const uchar* tri_count,
                          __global const ushort* crossed, __global uchar* cases, __global ushort* row_ranks,
                          __global uint* brick_triangles, __global uint* brick_vertices,
                          __global uint* brick_seams) {
  uint b = get_global_id(0);
  if (b >= nbricks) return;
  __global const float* s = samples + (size_t)b * BRICK_SAMPLES;
  __global uchar* out = cases + (size_t)b * 512;
  __global ushort* ranks = row_ranks + (size_t)b * 64;
  int4 o = origins[b];
  o.w = 0;
  int4 lo, hi;
  brick_range(o, cell_min, cell_max, &lo, &hi);
  // Inside bits of each sample row (x, y), row y + 9 x: bit z set when sample z is inside.
  uint rows[APRON * APRON];
  for (int r = 0; r < APRON * APRON; ++r) {
    uint m = 0;
    for (int z = 0; z < APRON; ++z) m |= (uint)(s[APRON * r + z] > 0.0f) << z;
    rows[r] = m;
  }
  __global ulong* out8 = (__global ulong*)out;
  uint ntri = 0, nvert = 0, nseam = 0;
  uint zmask = ((2u << hi.z) - 1u) & ~((1u << lo.z) - 1u);  // bits lo.z .. hi.z
  ulong zbytes = spread8(zmask) * 0xffUL;                  // bytes lo.z .. hi.z all ones
  bool zlast = cell_max.z - o.z <= 7;  // the frame's last cells along z lie in this brick
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y) {
      ranks[y + 8 * x] = (ushort)nvert;
      out8[y + 8 * x] = 0;
      if (x < lo.x || x > hi.x || y < lo.y || y > hi.y) continue;
      // Corners 0, 4 on sample row a (z and z + 1); 3, 7 on bb; 1, 5 on c; 2, 6 on d.
      uint a = rows[y + APRON * x], bb = rows[y + 1 + APRON * x];
      uint c = rows[y + APRON * (x + 1)], d = rows[y + 1 + APRON * (x + 1)];
      if (a == bb && a == c && a == d && (a == 0u || a == 0x1ffu)) continue;  // a row of empty cells
      // The row's 8 cases at once, byte z = cell z's case (corner bit k of every byte together).
      ulong row = spread8(a) | spread8(c) << 1 | spread8(d) << 2 | spread8(bb) << 3 | spread8(a >> 1) << 4 |
                  spread8(c >> 1) << 5 | spread8(d >> 1) << 6 | spread8(bb >> 1) << 7;
      row &= zbytes;
      out8[y + 8 * x] = row;
      for (int z = 0; z < 8; ++z) ntri += tri_count[(row >> (8 * z)) & 0xffu];
      if (!zlast && o.x + x != cell_max.x && o.y + y != cell_max.y) {
        // No cell of the row is the frame's last: each owns the edges at its corner 0, the x edge
        // (a against c), the y edge (a against bb) and the z edge (a against a shifted), and
        // which of them are seam edges depends on the row and on z == 0 (seam_table).
        uint ex = (a ^ c) & zmask, ey = (a ^ bb) & zmask, ez = (a ^ (a >> 1)) & zmask;
        nvert += popcount(ex) + popcount(ey) + popcount(ez);
        nseam += popcount(ex & (y == 0 ? 0xffu : 1u)) + popcount(ey & (x == 0 ? 0xffu : 1u)) +
                 (x == 0 || y == 0 ? popcount(ez) : 0u);
        continue;
      }
      for (int z = lo.z; z <= hi.z; ++z) {
        uint index = out[z + 8 * y + 64 * x];
        uint owned = crossed[index] & owned_edges(o + (int4)(x, y, z, 0), cell_max);
        nvert += popcount(owned);
        nseam += popcount(owned & seam_table[(x == 0) | (y == 0) << 1 | (z == 0) << 2]);
      }
    }
  brick_triangles[b] = ntri;
  brick_vertices[b] = nvert;
  brick_seams[b] = nseam;
}

inline ulong edge_key(uint x, uint y, uint z, uint axis) {
  return ((ulong)x << 42) | ((ulong)y << 22) | ((ulong)z << 2) | (ulong)axis;
}

// Order of point (x, y, z) (each 0..7) in its 8^3 block, the lower faces' points first: face
// x = 0 is [0, 64), face y = 0 [56, 120), face z = 0 [49, 57) and [113, 169) (mc/edge_key.h).
inline uint block_point(uint x, uint y, uint z) {
  if (x == 0) return y == 0 ? 56 + z : z == 0 ? 48 + y : (y - 1) * 7 + (z - 1);
  if (y == 0) return z == 0 ? 112 + x : 64 + (x - 1) * 7 + (z - 1);
  if (z == 0) return 120 + (x - 1) * 7 + (y - 1);
  return 169 + ((x - 1) * 7 + (y - 1)) * 7 + (z - 1);
}

// Number of hash block (bx, by, bz): z fastest, blocks = (blocks a column, columns a layer).
inline uint hash_block(uint bx, uint by, uint bz, uint2 blocks) { return bz + blocks.x * (by + blocks.y * bx); }

// 32-bit hash of an edge starting at hash coordinates (x, y, z) (index space from a brick-aligned
// origin) along `axis`, spatially coherent: the bricks' 8^3 blocks in order, z fastest like the
// bricks (blocks = (blocks a column, columns a layer)), 1536 edge slots each (block_point order,
// so each lower face is one or two runs of hashes), wrapping past 2^32 (over 2.8 million blocks),
// then masked.
inline uint edge_hash(uint x, uint y, uint z, uint axis, uint2 blocks, uint mask) {
  uint block = hash_block(x >> 3, y >> 3, z >> 3, blocks);
  return (block * 1536u + block_point(x & 7u, y & 7u, z & 7u) * 3u + axis) & mask;
}

// Key and hash of cube edge e of the cell at g.
inline ulong cell_edge(int4 g, int e, int4 key_origin, int4 hash_origin, uint2 blocks, uint mask, uint* hash) {
  int lo = edge_low[e];
  int4 c = g + (int4)(corner_x[lo], corner_y[lo], corner_z[lo], 0);
  uint axis = (uint)edge_axis[e];
  int4 h = c - hash_origin, k = c - key_origin;
  *hash = edge_hash((uint)h.x, (uint)h.y, (uint)h.z, axis, blocks, mask);
  return edge_key((uint)k.x, (uint)k.y, (uint)k.z, axis);
}

// Per brick, from seam_offsets[b] on: the seam vertices (seam_table), cell by cell in edge order,
// as (hash, own index j) pairs for the sort, with their vertex number (vertex_offsets[b] plus the
// rank among the brick's vertices, the numbering mc_emit gives) and edge key. Only the rows on
// the brick's lower faces (x = 0 or y = 0) and the first cell of every other row hold seam
// vertices.
__kernel void mc_seams(__global const int4* origins, uint nbricks, int4 cell_max, int4 key_origin,
                       int4 hash_origin, uint2 blocks, uint hash_mask, __global const ushort* crossed,
                       __global const uchar* cases, __global const ushort* row_ranks,
                       __global const uint* vertex_offsets, __global const uint* seam_offsets,
                       __global uint* hashes, __global uint* order, __global uint* seam_vertex,
                       __global ulong* seam_keys) {
  uint b = get_global_id(0);
  if (b >= nbricks) return;
  __global const uchar* bc = cases + (size_t)b * 512;
  __global const ushort* ranks = row_ranks + (size_t)b * 64;
  int4 o = origins[b];
  o.w = 0;
  uint first = vertex_offsets[b], j = seam_offsets[b];
  int4 ob = (o - hash_origin) >> 3, kc = o - key_origin;  // the brick's hash block; key of its origin
  uint block_hash = hash_block((uint)ob.x, (uint)ob.y, (uint)ob.z, blocks) * 1536u;
  bool zlast = cell_max.z - o.z <= 7;  // the frame's last cells along z lie in this brick
  for (int row = 0; row < 64; ++row) {
    int y = row & 7, x = row >> 3;
    // Every cell of a row on a lower face (x = 0 or y = 0), else only the first (z = 0).
    uint first_case = bc[8 * row];
    uint cells = x == 0 || y == 0 ? row_cells(bc + 8 * row) : (uint)(first_case != 0u && first_case != 255u);
    if (!cells) continue;
    uint v = first + ranks[row];
    if (!zlast && o.x + x != cell_max.x && o.y + y != cell_max.y) {
      // No cell of the row is the frame's last: each owns its x, y and z edges at corner 0 (as in
      // mc_classify), crossed where corner 0's bit differs from corner 1's, 3's or 4's, and the
      // seam ones among them depend on the row and on z == 0 (seam_table). Vertex numbers count
      // the row's owned crossed edges before each.
      ulong r = row_cases(bc + 8 * row);
      uint c0 = byte_bits(r, 0), ex = c0 ^ byte_bits(r, 1), ey = c0 ^ byte_bits(r, 3), ez = c0 ^ byte_bits(r, 4);
      uint sx = ex & (y == 0 ? 0xffu : 1u), sy = ey & (x == 0 ? 0xffu : 1u), sz = x == 0 || y == 0 ? ez : 0u;
      for (uint rest = sx | sy | sz; rest; rest &= rest - 1u) {
        int z = (int)lowest_bit(rest);
        uint below = (1u << z) - 1u;
        uint w = v + popcount(ex & below) + popcount(ey & below) + popcount(ez & below);
        uint h = block_hash + block_point((uint)x, (uint)y, (uint)z) * 3u;
        ulong key = edge_key((uint)(kc.x + x), (uint)(kc.y + y), (uint)(kc.z + z), 0u);
        uint in_x = (ex >> z) & 1u, in_y = (ey >> z) & 1u;
        if ((sx >> z) & 1u) {
          hashes[j] = h & hash_mask;
          order[j] = j;
          seam_vertex[j] = w;
          seam_keys[j++] = key;
        }
        if ((sy >> z) & 1u) {
          hashes[j] = (h + 1u) & hash_mask;
          order[j] = j;
          seam_vertex[j] = w + in_x;
          seam_keys[j++] = key | 1u;
        }
        if ((sz >> z) & 1u) {
          hashes[j] = (h + 2u) & hash_mask;
          order[j] = j;
          seam_vertex[j] = w + in_x + in_y;
          seam_keys[j++] = key | 2u;
        }
      }
      continue;
    }
    for (; cells; cells &= cells - 1u) {
      int z = (int)lowest_bit(cells);
      uint index = bc[8 * row + z];
      int4 g = o + (int4)(x, y, z, 0);
      uint owned = crossed[index] & owned_edges(g, cell_max);
      for (uint seam = owned & seam_table[(x == 0) | (y == 0) << 1 | (z == 0) << 2]; seam; seam &= seam - 1u) {
        uint e = lowest_bit(seam);
        uint h;
        seam_keys[j] = cell_edge(g, (int)e, key_origin, hash_origin, blocks, hash_mask, &h);
        hashes[j] = h;
        order[j] = j;
        seam_vertex[j] = v + popcount(owned & ((1u << e) - 1u));
        ++j;
      }
      v += popcount(owned);
    }
  }
}

// The lookup table, from the sorted (hash, seam j) pairs: hashes[j], vertices[j] and keys[j] (the
// hashes apart, so a bucket's scan reads one or two cache lines), and starts[b] = first j whose
// hash's top bits (hash >> shift) are >= b, for b in [0, nbuckets]. One work item per j in
// [0, n]; every entry is written once.
__kernel void mc_table(__global const uint* sorted_hashes, __global const uint* sorted_order,
                       __global const uint* seam_vertex, __global const ulong* seam_keys, uint n, uint shift,
                       uint nbuckets, __global uint* hashes, __global uint* vertices, __global ulong* keys,
                       __global uint* starts) {
  uint j = get_global_id(0);
  if (j > n) return;
  long cur = (long)nbuckets;
  if (j < n) {
    uint h = sorted_hashes[j], u = sorted_order[j];
    hashes[j] = h;
    vertices[j] = seam_vertex[u];
    keys[j] = seam_keys[u];
    cur = (long)(h >> shift);
  }
  long prev = j > 0 ? (long)(sorted_hashes[j - 1] >> shift) : -1;
  for (long b = prev + 1; b <= cur; ++b) starts[b] = j;
}

// Slot of cube edge e of the cell at local (0,0,0) in a brick's vertex map: 3 * (lower end's
// x + 9 y + 81 z) + axis. A cell's slot adds 3 * (x + 9 y + 81 z).
__constant int edge_slot[12] = {0, 3 * 1 + 1, 3 * 9 + 0, 1, 3 * 81 + 0, 3 * 82 + 1,
                                3 * 90 + 0, 3 * 81 + 1, 2, 3 * 1 + 2, 3 * 9 + 2, 3 * 10 + 2};

// Records in the vertex map `own` of the brick at o the seam vertices with (masked) hashes in
// [a, b): every table entry there whose edge lies in the brick's 9^3 lattice (keys compared, so
// entries of other edges, from collisions, are passed over). The first entry is found in the
// bucket of a's top bits: scanned when short (the usual dozen entries), binary-searched when long
// (collisions, a narrowed hash).
inline void record_run(uint a, ulong b, int4 o, int4 key_origin, __global const uint* hashes,
                       __global const uint* vertices, __global const ulong* keys, uint n,
                       __global const uint* starts, uint shift, uint first, uint* own) {
  uint bucket = a >> shift;
  uint j = starts[bucket], len = starts[bucket + 1] - j;
  while (len > 16) {  // halve to a short range that holds the lower bound of a
    uint half_len = len >> 1;
    if (hashes[j + half_len] < a) {
      j += half_len + 1;
      len -= half_len + 1;
    } else {
      len = half_len;
    }
  }
  for (uint end = j + len; j < end && hashes[j] < a;) ++j;
  int4 d = key_origin - o;
  for (; j < n && hashes[j] < b; ++j) {
    ulong key = keys[j];
    int axis = (int)(key & 3u);
    int4 l = (int4)((int)(key >> 42), (int)(key >> 22) & 0xfffff, (int)(key >> 2) & 0xfffff, 0) + d;
    int along = axis == 0 ? l.x : axis == 1 ? l.y : l.z;
    if ((uint)l.x <= 8u && (uint)l.y <= 8u && (uint)l.z <= 8u && along < 8)
      own[3 * (l.x + APRON * l.y + APRON * APRON * l.z) + axis] = vertices[j] - first;
  }
}

// The hashes of the points of block face, line or corner d (dx + 2 dy + 4 dz: the points at 0
// along each axis with d set), in block_point order: up to two runs [begin, end).
__constant uchar face_runs[8][4] = {{0, 0, 0, 0},   {0, 64, 0, 0},  {56, 120, 0, 0}, {56, 64, 0, 0},
                                    {49, 57, 113, 169}, {49, 57, 0, 0}, {56, 57, 113, 120}, {56, 57, 0, 0}};

// Records in `own` the vertices of the edges on the upper faces of the brick at o (hash block
// (bx, by, bz)) that the bricks above own: each is a seam vertex of the block d above (d = dx + 2
// dy + 4 dz), on that block's face, line or corner touching this brick, and so hashes into one of
// face_runs[d]. Blocks above are visited only where the brick's cells reach its upper face.
inline void record_upper_faces(int4 o, int4 cell_max, int4 key_origin, uint3 bb, uint2 blocks, uint mask,
                               __global const uint* hashes, __global const uint* vertices,
                               __global const ulong* keys, uint n, __global const uint* starts, uint shift,
                               uint first, uint* own) {
  int4 reach = (int4)(cell_max.x >= o.x + 7, cell_max.y >= o.y + 7, cell_max.z >= o.z + 7, 0);
  for (int d = 1; d < 8; ++d) {
    int dx = d & 1, dy = (d >> 1) & 1, dz = d >> 2;
    if ((dx && !reach.x) || (dy && !reach.y) || (dz && !reach.z)) continue;
    uint block = hash_block(bb.x + dx, bb.y + dy, bb.z + dz, blocks);
    for (int r = 0; r < 4; r += 2) {
      uint begin = face_runs[d][r], end = face_runs[d][r + 1];
      if (begin == end) break;
      uint lo = block * 1536u + 3u * begin, len = 3u * (end - begin);
      ulong full = (ulong)mask + 1;
      if (len >= full) {  // a hash narrower than the run: every entry (the second run too)
        record_run(0, full, o, key_origin, hashes, vertices, keys, n, starts, shift, first, own);
        break;
      }
      uint a = lo & mask;
      ulong b = (ulong)a + len;
      record_run(a, min(b, full), o, key_origin, hashes, vertices, keys, n, starts, shift, first, own);
      if (b > full) record_run(0, b - full, o, key_origin, hashes, vertices, keys, n, starts, shift, first, own);
    }
  }
}

// Vertex snapping (mc/snap_vertices.h): a vertex at fraction f of its edge, within `snap` of one
// end, is listed for the host with its edge's key, SNAP_UPPER set when it lies near the upper end.
// The list's order depends on the work items' timing; the host sorts it by key.
#define SNAP_UPPER 0x8000000000000000UL
inline void note_snap(float f, float snap, ulong edge, uint vertex, __global uint* count, uint capacity,
                      __global ulong* edges, __global uint* vertices) {
  if (!(f < snap || f > 1.0f - snap)) return;
  uint slot = atomic_inc(count);
  if (slot >= capacity) return;  // cannot happen: one entry a vertex at most
  edges[slot] = edge | (f > 0.5f ? SNAP_UPPER : 0UL);
  vertices[slot] = vertex;
}

// Per brick, the vertices (positions, and edge keys when write_keys) from vertex_offsets[b] on and
// the triangles from triangle_offsets[b] on, with the brick's vertex map `own` (by edge_slot): (0)
// the vertices of the edges on its upper faces that other bricks own, from the seam table
// (record_upper_faces); (1) a walk over the non-empty cells writing each owned crossed edge's
// vertex and recording it in the map; (2) a second walk writing every triangle corner from the map.
__kernel void mc_emit(__global const float* samples, __global const int4* origins,
                      __constant const McEmitParams* params, __global const ushort* case_slots,
                      __global const uchar* tri_count, __global const ushort* crossed, __global const uchar* cases,
                      __global const uint* triangle_offsets, __global const uint* vertex_offsets,
                      __global const uint* table_hashes, __global const uint* table_vertices,
                      __global const ulong* table_keys, __global const uint* starts,
                      __global float* positions, __global uint* triangles, __global ulong* keys,
                      __global uint* snap_count, __global ulong* snap_edges, __global uint* snap_vertices) {
  const McEmitParams pm = *params;
  const uint nbricks = pm.bricks, ntriangles = pm.triangles, nvertices = pm.vertices;
  const uint nseams = pm.seams, shift = pm.shift, hash_mask = pm.hash_mask;
  const uint write_keys = pm.write_keys, snap_capacity = pm.snap_capacity;
  const float min_fraction = pm.min_fraction, snap = pm.snap;
  const int4 cell_max = vload4(0, pm.cell_max), key_origin = vload4(0, pm.key_origin);
  const int4 hash_origin = vload4(0, pm.hash_origin);
  const uint2 blocks = vload2(0, pm.hash_blocks);
  const float16 world = vload16(0, pm.world);
  uint b = get_global_id(0);
  if (b >= nbricks) return;
  __global const float* brick = samples + (size_t)b * BRICK_SAMPLES;
  __global const uchar* bc = cases + (size_t)b * 512;
  int4 o = origins[b];
  o.w = 0;
  uint own[APRON * APRON * APRON * 3];  // vertex numbers relative to the brick's first, `first`
  uint first = vertex_offsets[b];
  int4 ob = (o - hash_origin) >> 3;
  record_upper_faces(o, cell_max, key_origin, (uint3)((uint)ob.x, (uint)ob.y, (uint)ob.z), blocks, hash_mask,
                     table_hashes, table_vertices, table_keys, nseams, starts, shift, first, own);
  // (1) The brick's own vertices, cell by cell in edge order, into positions[first + w]. A cell
  // inside the frame owns just its x, y and z edges at corner 0: it writes all three without
  // branches, each advancing the count only when crossed (the next write overwrites an uncrossed
  // one, and map entries of uncrossed edges are never read); a write past the brick's last vertex
  // is dropped (the next brick's).
  __global float* pos = positions + 3 * (size_t)first;
  uint nv = (b + 1 < nbricks ? vertex_offsets[b + 1] : nvertices) - first;
  uint w = 0;
  float3 ax = (float3)(world.s0, world.s4, world.s8), ay = (float3)(world.s1, world.s5, world.s9),
         az = (float3)(world.s2, world.s6, world.sa), at = (float3)(world.s3, world.s7, world.sb);
  for (int row = 0; row < 64; ++row) {
    int y = row & 7, x = row >> 3;
    for (uint cells = row_cells(bc + 8 * row); cells; cells &= cells - 1u) {
      int z = (int)lowest_bit(cells);
      uint index = bc[8 * row + z];
      int4 g = o + (int4)(x, y, z, 0);
      __global const float* s = brick + z + APRON * y + APRON * APRON * x;
      int base = 3 * (x + APRON * y + APRON * APRON * z);
      uint cross = crossed[index];
      if (!write_keys && g.x != cell_max.x && g.y != cell_max.y && g.z != cell_max.z) {
        float s0 = s[0];
        float3 f = (float3)(s0) / ((float3)(s0) - (float3)(s[APRON * APRON], s[APRON], s[1]));  // one division
        f = fmin(fmax(f, (float3)(min_fraction)), (float3)(1.0f - min_fraction));
        float3 c = convert_float3(g.xyz), p = c + f;  // world map of (x + fx, y, z), ...
        uint wx = w, wy, wz;
        if (w < nv) vstore3(ax * p.x + ay * c.y + az * c.z + at, w, pos);
        own[base] = w;
        w += cross & 1u;
        wy = w;
        if (w < nv) vstore3(ax * c.x + ay * p.y + az * c.z + at, w, pos);
        own[base + 1] = w;
        w += (cross >> 3) & 1u;
        wz = w;
        if (w < nv) vstore3(ax * c.x + ay * c.y + az * p.z + at, w, pos);
        own[base + 2] = w;
        w += (cross >> 8) & 1u;
        if (snap > 0.0f) {  // edges 0, 3 and 8 start at corner 0, along x, y and z
          int4 k = g - key_origin;
          ulong key = edge_key((uint)k.x, (uint)k.y, (uint)k.z, 0u);
          if (cross & 1u) note_snap(f.x, snap, key, first + wx, snap_count, snap_capacity, snap_edges, snap_vertices);
          if (cross & 8u) note_snap(f.y, snap, key | 1u, first + wy, snap_count, snap_capacity, snap_edges, snap_vertices);
          if (cross & 256u) note_snap(f.z, snap, key | 2u, first + wz, snap_count, snap_capacity, snap_edges, snap_vertices);
        }
        continue;
      }
      for (uint rest = cross & owned_edges(g, cell_max); rest; rest &= rest - 1u) {
        int e = (int)lowest_bit(rest);
        int lo = edge_low[e], axis = edge_axis[e];
        float s0 = s[corner_offset[lo]], s1 = s[corner_offset[lo] + axis_step[axis]];
        float f = s0 / (s0 - s1);
        f = fmin(fmax(f, min_fraction), 1.0f - min_fraction);
        float px = (float)(g.x + corner_x[lo]) + (axis == 0 ? f : 0.0f);
        float py = (float)(g.y + corner_y[lo]) + (axis == 1 ? f : 0.0f);
        float pz = (float)(g.z + corner_z[lo]) + (axis == 2 ? f : 0.0f);
        vstore3(ax * px + ay * py + az * pz + at, w, pos);
        if (write_keys || snap > 0.0f) {
          uint h;
          ulong key = cell_edge(g, e, key_origin, hash_origin, blocks, hash_mask, &h);
          if (write_keys) keys[first + w] = key;
          if (snap > 0.0f) note_snap(f, snap, key, first + w, snap_count, snap_capacity, snap_edges, snap_vertices);
        }
        own[base + edge_slot[e]] = w++;
      }
    }
  }
  // (2) The triangles. Cells write their first 6 corners (2 triangles, the most common case)
  // without a loop, when the brick's triangles leave room: a cell with fewer writes padding
  // corners (from map slot 0 of the cell, which may never have been written) where its
  // successor's corners then go.
  __global uint* out = triangles + 3 * (size_t)triangle_offsets[b];
  __global const uint* end = triangles + 3 * (size_t)(b + 1 < nbricks ? triangle_offsets[b + 1] : ntriangles);
  for (int row = 0; row < 64; ++row) {
    for (uint cells = row_cells(bc + 8 * row); cells; cells &= cells - 1u) {
      int z = (int)lowest_bit(cells), y = row & 7, x = row >> 3;
      uint index = bc[8 * row + z];
      int n = 3 * tri_count[index];
      const uint* map = own + 3 * (x + APRON * y + APRON * APRON * z);
      __global const ushort* ts = case_slots + index * 16;
      int k = 0;
      if (out + 6 <= end)
        for (; k < 6; ++k) out[k] = map[ts[k]] + first;
      for (; k < n; ++k) out[k] = map[ts[k]] + first;
      out += n;
    }
  }
}

// case_slots[16 c + k]: the vertex-map slot (edge_slot) of corner k of case c's triangles, 0 past
// the last. One work item per case; run once per Mesher.
__kernel void mc_case_slots(__global const char* tri_edges, __global ushort* case_slots) {
  uint c = get_global_id(0);
  if (c >= 256) return;
  for (int k = 0; k < 16; ++k) {
    int e = tri_edges[16 * c + k];
    case_slots[16 * c + k] = (ushort)(e >= 0 ? edge_slot[e] : 0);
  }
}
