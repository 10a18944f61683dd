# test_curvature: the curvature library, the mesher and analytic fields for the marching-cubes
# tests, and VTK for the vtkCurvatures comparison.
set(_links isocurv_curvature isocurv_mc isocurv_datasets ${VTK_LIBRARIES})
