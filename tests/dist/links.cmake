# test_dist checks the pieces in-process (isocurv_dist, the mesher) and runs the real isocurv under
# mpirun, reading the .pvtp back through VTK's vtkXMLPPolyDataReader.
set(_links isocurv_all nlohmann_json::nlohmann_json VTK::IOParallelXML)
if(TARGET isocurv_app_test_deps)
  list(APPEND _links isocurv_app_test_deps)
endif()
