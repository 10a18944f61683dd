# Unity builds: the build's one speed switch (ISOCURV_UNITY, on by default).
#
# Where a clean build's time went (Ninja's log of a -j2 build on the 2-core development machine,
# 2026-12-07; docs/install.md has the table): a translation unit of ours spent most of its time
# on third-party headers, and not only parsing them: CLI11 (header-only in Debian's 2.1.2) alone
# costs 1.9 s to parse and 3.6 s more at -O3 to compile the inline functions and static objects
# every unit that includes it emits again; OpenVDB's openvdb.h 3.3 s and 1.8 s. A command of the
# executable took 14-26 s, a test file 7.7 s on average. Precompiled headers were measured and
# do not help with GCC: the header of CLI11, JSON, OpenVDB and the OpenCL bindings precompiles to
# 327 MB, and loading it costs what parsing saved (cmd_devices.cpp: 9.9 s without, 10.3 s with;
# the libraries' units got slower on average). Compiling a target's sources in batches does:
# eight of the executable's units took 27 s together against 163 s one by one.
#
# So each target compiles its sources ISOCURV_UNITY_BATCH at a time (CMake's UNITY_BUILD). The
# cost is on the sources: a name in an anonymous namespace, a `static` function, a macro or a
# `using` at file scope is seen by the files after it in the same batch, so such names must be
# unique within a target's folder (the build fails on a clash, it never picks the wrong one).
# -DISOCURV_UNITY=OFF builds file by file (to check that each file includes what it uses).
# Touching one file rebuilds its batch: under a minute for the largest (the executable's).
option(ISOCURV_UNITY "Compile each target's sources in batches (unity build; faster)" ON)
set(ISOCURV_UNITY_BATCH 8 CACHE STRING "Sources per unity batch (ISOCURV_UNITY)")
if(ISOCURV_UNITY)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE ${ISOCURV_UNITY_BATCH})
  # GCC warns when a class in an anonymous namespace is used by one defined outside the main file
  # (meant for headers, where the class would differ per unit); in a batch every source is an
  # included file, so the fixtures of the tests (TEST_F in an anonymous namespace) would warn.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-subobject-linkage)
  endif()
endif()
