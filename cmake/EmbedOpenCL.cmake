# isocurv_embed_cl(<target> <symbol> <file.cl>): compiles the OpenCL source into <target> as
#   namespace isocurv::kernels { extern const char* const <symbol>; }
# regenerated whenever the .cl file changes, so an installed binary needs no kernel files.
function(isocurv_embed_cl target symbol clfile)
  get_filename_component(abs "${clfile}" ABSOLUTE)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_${symbol}.cpp")
  add_custom_command(OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DIN=${abs} -DOUT=${out} -DSYMBOL=${symbol}
            -P "${PROJECT_SOURCE_DIR}/cmake/embed_file.cmake"
    DEPENDS "${abs}" "${PROJECT_SOURCE_DIR}/cmake/embed_file.cmake"
    COMMENT "Embedding OpenCL kernel ${clfile}")
  target_sources(${target} PRIVATE "${out}")
  # Compiled alone, not in a unity batch (cmake/UnityBuild.cmake): editing a kernel then rebuilds
  # one small file, not a batch of the stage's sources.
  set_source_files_properties("${out}" PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
endfunction()
