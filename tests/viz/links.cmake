set(_links isocurv_viz)
