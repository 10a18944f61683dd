#pragma once
// Griffin et al.'s exact curvature AO over (k1, k2) (section 3.7, eq. 10-12; SEEDS-SPEC.md G-AO2):
// the integral their diagonal polynomial (curvature/derived.h) was fitted from.
// Tested in tests/ao/test_ao.cpp.

namespace isocurv::ao {

/// AO = 1 - (1/2pi) int_0^2pi max(0, z(A(phi)))^p dphi, A(phi) = -(a1 cos^2 phi + a2 sin^2 phi),
/// (a1, a2) = rho (k1, k2), z = horizon_height (ao/formulas.h), p = 1 (unweighted, eq. 10) or 2
/// (cosine-weighted). How it is computed: A is monotone in sin^2 phi on [0, pi/2] and the
/// integrand has that quarter's symmetry, so the concave azimuths (A > 0) form one interval whose
/// end is known in closed form, sin^2 phi0 = a1 / (a1 - a2) on saddles; 24-point Gauss-Legendre
/// over that interval alone integrates a smooth function (no max(0, .) kink inside), to about
/// 1e-9 of the exact integral. Exactly 1 where no azimuth is concave (planes, convex points);
/// 1 - z(-a) (resp. 1 - z^2) on the concave umbilic diagonal a1 = a2 = a. Non-finite input: 1.
double griffin_exact_integral(double a1, double a2, bool cosine = false);

/// Griffin's exact AO at principal curvatures (k1, k2) (outward normals: concave negative) and
/// hemisphere radius rho (world units): griffin_exact_integral(rho k1, rho k2).
double griffin_exact(double k1, double k2, double rho);

}  // namespace isocurv::ao
