# test_series runs the real isocurv executable on the bundled animated series (datasets/animated.h)
# and reads its frames and .pvd back in-process.
set(_links isocurv_all isocurv_datasets_files nlohmann_json::nlohmann_json)
if(TARGET isocurv_app_test_deps)  # made by tests/app/links.cmake: builds the executable first
  list(APPEND _links isocurv_app_test_deps)
endif()
