set(_links isocurv_mc)
