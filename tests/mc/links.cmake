set(_links isocurv_mc VTK::FiltersCore VTK::CommonDataModel VTK::FiltersGeneral)
