#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ao/ao.h"
#include "ao/formulas.h"
#include "ao/griffin_exact.h"
#include "ao/raycast.h"
#include "core/error.h"
#include "curvature/derived.h"

namespace isocurv::ao {

namespace {

std::string number(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", x);
  return text;
}

void require_size(const std::string& name, std::size_t size, std::size_t nv) {
  if (size != nv)
    throw Error("AO: the curvature field's " + name + " array has " + std::to_string(size) +
                " entries for " + std::to_string(nv) + " vertices");
}

/// The 98th percentile of |H| over the finite, reliable vertices (Prantl's "curvature extreme").
double default_href(const curvature::CurvatureField& field) {
  std::vector<double> a;
  a.reserve(field.H.size());
  for (std::size_t i = 0; i < field.H.size(); ++i)
    if (std::isfinite(field.H[i]) && (field.unreliable.empty() || !field.unreliable[i]))
      a.push_back(std::abs(double(field.H[i])));
  if (a.empty()) return 0;
  const std::size_t k = std::min(a.size() - 1, std::size_t(0.98 * double(a.size() - 1) + 0.5));
  std::nth_element(a.begin(), a.begin() + std::ptrdiff_t(k), a.end());
  return a[k];
}

}  // namespace

void compute(const Mesh& mesh, curvature::CurvatureField& field,
             const curvature::VolumeSource& source, const Options& options) {
  const std::size_t nv = mesh.vertex_count();
  const double rho = options.radius;
  if (!(rho > 0) || !std::isfinite(rho))
    throw Error("AO: the radius (--ao-scale) must be positive and finite");
  std::vector<std::pair<std::string, std::string>> meta = {{"ao", method_name(options.method)},
                                                           {"ao_radius", number(rho)}};
  std::vector<float> ao(nv, 1.0f);
  auto finite = [](double a, double b) { return std::isfinite(a) && std::isfinite(b); };
  switch (options.method) {
    case Method::griffin:
    case Method::griffin_exact:
    case Method::hattori:
      require_size("k1", field.k1.size(), nv);
      require_size("k2", field.k2.size(), nv);
      for (std::size_t i = 0; i < nv; ++i) {
        const double k1 = field.k1[i], k2 = field.k2[i];
        if (!finite(k1, k2)) continue;
        ao[i] = float(options.method == Method::griffin ? curvature::ambient_occlusion(k1, k2, rho)
                      : options.method == Method::griffin_exact
                          ? griffin_exact(k1, k2, rho)
                          : hattori(k1, k2, rho, options.hattori_half));
      }
      if (options.method == Method::hattori)
        meta.emplace_back("ao_hattori", options.hattori_half ? "half" : "printed");
      break;
    case Method::prantl: {
      require_size("H", field.H.size(), nv);
      // At least 1 / (4 rho): a nearly flat surface's noise is not stretched to full contrast.
      const double href =
          options.prantl_href > 0 ? options.prantl_href : std::max(default_href(field), 0.25 / rho);
      for (std::size_t i = 0; i < nv; ++i) {
        const double H = field.H[i];
        if (!std::isfinite(H)) continue;
        ao[i] = float(href > 0 ? prantl(H, href, options.prantl_a) : options.prantl_a);
      }
      meta.emplace_back("ao_href", number(href));
      meta.emplace_back("ao_prantl_a", number(options.prantl_a));
      break;
    }
    case Method::raycast:
    case Method::raycast_cos: {
      if (!source.volume)
        throw Error(std::string("AO ") + method_name(options.method) +
                    " needs the volume the mesh was extracted from (it casts rays through it), "
                    "not a mesh file");
      require_size("Normals", field.normals.size(), nv);
      RaycastOptions ro;
      ro.radius = rho;
      ro.strata = options.strata;
      ro.cosine = options.method == Method::raycast_cos;
      ao = raycast(*source.volume, source.isovalue, mesh.positions, field.normals, ro);
      meta.emplace_back("ao_rays", std::to_string(options.strata * options.strata));
      break;
    }
  }
  field.ao = std::move(ao);
  auto& md = field.metadata;
  auto ours = [](const std::pair<std::string, std::string>& kv) {
    return kv.first == "ao" || (kv.first.rfind("ao_", 0) == 0 && kv.first != "ao_scale");
  };
  md.erase(std::remove_if(md.begin(), md.end(), ours), md.end());
  md.insert(md.end(), meta.begin(), meta.end());
}

}  // namespace isocurv::ao
