# test_measure: measure::object_measures on meshes built by hand, and on volumes through the
# device mesher and the default (volume) curvature estimator.
set(_links isocurv_measure isocurv_mc)
