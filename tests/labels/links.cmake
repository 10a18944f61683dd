# test_labels: the labels library, and the C++ mesher (mc::extract_reference) that
# test_label_surfaces.cpp passes to labels::for_each_label_surface as its extraction.
set(_links isocurv_labels isocurv_mc)
