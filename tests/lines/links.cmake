# test_lines: the lines stage, the curvature reference that feeds it, VTK's XML parser (SVG).
set(_links isocurv_lines isocurv_curvature ${VTK_LIBRARIES})
