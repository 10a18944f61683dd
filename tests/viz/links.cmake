set(_links isocurv_viz)
# test_explorer_view runs the real isocurv executable (`view --time-series --script`): build it
# first (isocurv_app_test_deps is made by tests/app/links.cmake, which runs before this folder's).
if(TARGET isocurv_app_test_deps)
  list(APPEND _links isocurv_app_test_deps)
endif()
