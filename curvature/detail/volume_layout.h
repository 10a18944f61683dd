/* The volume estimator's host/kernel layout, one C header for both sides (Cycles' node_types.h):
 * included by the host (curvature/detail/volume_passes.cpp, which static_asserts the sizes and
 * offsets below) and prepended to the kernels' source (curvature/volume_kernels.cl), so that the
 * brick layout and the parameter block cannot drift apart. Plain C99 / OpenCL C: no C++ here.
 * The estimator's tuning constants (tolerances, Newton steps, shrinkage fit) stay defined once in
 * C++ (curvature/volume_estimate.h, curvature/tolerances.h), shared with the double-precision
 * reference, and reach the kernels as build options. */
#ifndef ISOCURV_CURVATURE_DETAIL_VOLUME_LAYOUT_H
#define ISOCURV_CURVATURE_DETAIL_VOLUME_LAYOUT_H

/* Samples travel in bricks of 8^3 voxels, x fastest (volume/prefilter.h's BrickSet). */
#define VOLUME_BRICK_EDGE 8
#define BRICK_VOXELS 512
/* Rows of 8 voxels along an axis per brick: smooth_axis's work items per brick. */
#define BRICK_ROWS 64
/* The quartic B-spline's taps per axis (volume/spline_jet.h). */
#define SPLINE_TAPS 5
/* pad_bricks' blocks: a brick's 8 voxels per axis plus the taps' reach around any cell in it
 * (floor(q) - 2 .. floor(q) + 3, volume::spline_weights). */
#define PAD_BEFORE 2
#define PADDED (VOLUME_BRICK_EDGE + PAD_BEFORE + 3)
#define PADDED_VOXELS (PADDED * PADDED * PADDED)

/* volume_curvature's parameters for one evaluation (one scale), in __constant memory: the
 * index-space frame and the per-call scalars. */
typedef struct {
  /* The world -> index matrix B, row-major. */
  float b[9];
  /* The world position of a fixed anchor voxel (the brick holding the volume's first voxel), so
   * that a vertex's position rounds the same whatever vertices share the call. */
  float origin[3];
  /* The maps of the distinct index-space derivatives of orders 2 and 3 to world space:
   * h[e] = sum_f m2[e][f] d_f over the 6 second derivatives (PAIR_ORDERS order), t[e] likewise
   * over the 10 third ones (TRIPLE_ORDERS). */
  float m2[6][6];
  float m3[10][10];
  /* The region's first voxel less the anchor (whole numbers). */
  float first[3];
  float isovalue;
  /* -1 where inside is above the isovalue (normals point down the gradient), else 1. */
  float sign;
  /* Ambient occlusion radius, world units. */
  float ao_scale;
  /* 1: VolumePoint::surface (Newton steps to the smoothed isosurface, shrinkage undone). */
  int surface;
  /* surface: the Newton steps' largest move, world units. */
  float max_shift;
  /* sigma^2, world units squared. */
  float sigma2;
} VolumeParams;

#endif
