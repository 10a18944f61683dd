# test_features: the features stage, with the mesher, the curvature reference, the analytic
# fields and the curvature tests' analytic meshes.
set(_links isocurv_features isocurv_mc isocurv_curvature isocurv_datasets)
list(APPEND _srcs ${PROJECT_SOURCE_DIR}/tests/curvature/test_meshes.cpp)
