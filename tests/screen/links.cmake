# test_screen: the screen stage, analytic fields sampled into volumes, the mesher (mesh vs volume)
# and the volume's gradient normals (the ray caster's normals against them).
set(_links isocurv_screen isocurv_datasets isocurv_mc isocurv_curvature isocurv_volume ${VTK_LIBRARIES})
