# test_volume writes Zarr stores with the same compressors the reader uses (test_zarr.cpp).
set(_links isocurv_volume ${ISOCURV_ZSTD_LIBRARY} ${ISOCURV_BLOSC_LIBRARY})
