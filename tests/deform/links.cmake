# test_deform: the deformers, the prepared curvature topology, the analytic ellipsoid oracle.
set(_links isocurv_deform isocurv_curvature isocurv_datasets)
