# Debian ships FindOpenVDB.cmake in a non-default folder; use it and expose OpenVDB::openvdb.
if(NOT TARGET OpenVDB::openvdb)
  list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB
       /usr/local/lib/cmake/OpenVDB)
  file(GLOB _ovdb_dirs /usr/lib/*/cmake/OpenVDB)
  list(APPEND CMAKE_MODULE_PATH ${_ovdb_dirs})
  find_package(OpenVDB QUIET)
endif()
if(TARGET OpenVDB::openvdb)
  set(OpenVDB_FOUND TRUE)
endif()
