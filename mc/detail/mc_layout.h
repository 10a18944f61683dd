/* The marching-cubes kernels' host/kernel layout, one C header for both sides (Cycles'
 * node_types.h): included by mc/detail/mesher_passes.cpp (which static_asserts the sizes and
 * offsets below) and prepended to mc/marching_cubes.cl, so that the brick layout and mc_emit's
 * parameter block cannot drift apart. Plain C99 / OpenCL C: no C++ here; vectors are plain arrays
 * (4-byte aligned on both sides, where OpenCL's int4 would be 16). */
#ifndef ISOCURV_MC_DETAIL_MC_LAYOUT_H
#define ISOCURV_MC_DETAIL_MC_LAYOUT_H

/* A brick's samples: 8 cells per axis plus the apron of the next brick's first plane
 * (mc/bricks.h, kApron and kBrickSamples). */
#define APRON 9
#define BRICK_SAMPLES (APRON * APRON * APRON)

/* mc_emit's scalar parameters, in __constant memory. */
typedef struct {
  /* The frame's last cell (index coordinates; w unused). */
  int cell_max[4];
  /* The index coordinates edge keys count from (mc/edge_key.h). */
  int key_origin[4];
  /* The brick-aligned corner the seam hashes count from, and the hash's blocks along z and y. */
  int hash_origin[4];
  unsigned int hash_blocks[2];
  unsigned int hash_mask;
  /* A vertex's place along its edge, kept within [min_fraction, 1 - min_fraction]. */
  float min_fraction;
  /* The index -> world map, rows of 4 (3 rows used: x' = w0 x + w1 y + w2 z + w3, ...). */
  float world[16];
  unsigned int bricks, triangles, vertices, seams;
  /* The seam table: a hash's bucket is hash >> shift. */
  unsigned int shift;
  /* 1: write each vertex's edge key. */
  unsigned int write_keys;
  /* Options::snap: vertices this near a grid point (fraction of the edge) are listed; 0: none. */
  float snap;
  unsigned int snap_capacity;
} McEmitParams;

#endif
