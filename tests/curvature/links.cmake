set(_links isocurv_curvature)
