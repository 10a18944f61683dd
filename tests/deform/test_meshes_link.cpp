// The curvature tests' mesh builders (icosphere, torus, quadric patch), compiled into this suite.
#include "tests/curvature/test_meshes.cpp"
