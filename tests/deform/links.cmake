# test_deform: the deformers, the prepared curvature topology, the analytic ellipsoid oracle and
# the mesher for its independently meshed ellipsoid.
set(_links isocurv_deform isocurv_curvature isocurv_datasets isocurv_mc)
