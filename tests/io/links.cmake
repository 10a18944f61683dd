set(_links isocurv_io)
