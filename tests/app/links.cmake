# test_app runs the real isocurv executable (located at run time through ISOCURV_BUILD_DIR) on the
# bundled .vdb datasets, and reads its output back in-process (io::read_mesh).
set(_links isocurv_all isocurv_datasets_files nlohmann_json::nlohmann_json)
# Build the executable before test_app: dependencies of an interface library are followed by the
# targets linking it (links.cmake runs before add_executable(test_app), so this is the only hook).
if(TARGET isocurv AND NOT TARGET isocurv_app_test_deps)
  add_library(isocurv_app_test_deps INTERFACE)
  add_dependencies(isocurv_app_test_deps isocurv)
endif()
if(TARGET isocurv_app_test_deps)
  list(APPEND _links isocurv_app_test_deps)
endif()
