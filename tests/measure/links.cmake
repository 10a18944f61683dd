# test_measure: measure::object_measures on meshes built by hand.
set(_links isocurv_measure)
