# test_ao: the AO methods, with the mesher, the curvature reference, the analytic fields, the
# volume-gradient normals and the curvature tests' analytic meshes.
set(_links isocurv_ao isocurv_mc isocurv_curvature isocurv_datasets isocurv_volume)
list(APPEND _srcs ${PROJECT_SOURCE_DIR}/tests/curvature/test_meshes.cpp)
