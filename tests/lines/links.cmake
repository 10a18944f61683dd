# test_lines: the lines stage, the curvature it needs (reference and OpenCL), the mesher and the
# volume's gradient normals (the CT-like test), VTK's XML parser (SVG).
set(_links isocurv_lines isocurv_curvature isocurv_mc isocurv_volume ${VTK_LIBRARIES})
