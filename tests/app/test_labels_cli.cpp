// --labels, --label and --split on extract, curvature, run, render and measure: one closed
// surface per label of a label map, Label arrays on points and cells, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <set>

#include "io/mesh_file.h"
#include "tests/app/cli.h"

namespace isocurv::test {
namespace {

using json = nlohmann::json;
constexpr int kN = 48;

/// Writes a kN^3 NRRD of `type` ("uint8", "float") to dir/name.nrrd holding f(x, y, z).
std::string write_nrrd(const TempDir& dir, const std::string& name, const std::string& type,
                       const std::function<double(int, int, int)>& f) {
  std::string data;
  for (int z = 0; z < kN; ++z)
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const double v = f(x, y, z);
        if (type == "uint8") {
          data.push_back(static_cast<char>(static_cast<std::uint8_t>(v)));
        } else {
          const float g = static_cast<float>(v);
          data.append(reinterpret_cast<const char*>(&g), sizeof g);
        }
      }
  const std::string path = dir / (name + ".nrrd");
  write_file(path, "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: " + std::to_string(kN) + " " +
                       std::to_string(kN) + " " + std::to_string(kN) + "\nencoding: raw\nendian: little\n\n" + data);
  return path;
}

/// Three touching labels: two balls of radius 10 side by side (the overlap goes to label 1) and a
/// ball below them (label 5 where neither is).
int three_labels(int x, int y, int z) {
  auto in = [&](double cx, double cy, double cz, double r) {
    return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) < r * r;
  };
  if (in(16, 24, 26, 10)) return 1;
  if (in(32, 24, 26, 10)) return 2;
  if (in(24, 24, 11, 8)) return 5;
  return 0;
}

json run_json(const std::vector<std::string>& args) {
  const auto r = run_isocurv(args, 120);
  EXPECT_TRUE(r.ok()) << r.describe();
  return parse_json(r.out, args.front() + " --json");
}

/// The vertices of extract --labels' mesh of `map`.
std::size_t labelled_mesh_vertices(const std::string& map) {
  const json e = run_json({"extract", map, "--labels", "-o", map + ".all.vtp", "--json"});
  return e["vertices"].get<std::size_t>();
}

TEST(CliLabels, EachLabelIsClosedAndMeasuresAsTheSameObjectAlone) {
  TempDir dir("labels");
  const std::string map = write_nrrd(dir, "map", "uint8", [](int x, int y, int z) { return three_labels(x, y, z); });
  const json m = run_json({"measure", map, "--labels", "--json"});
  ASSERT_EQ(m["labels"].size(), 3u) << m.dump();
  const int values[] = {1, 2, 5};
  for (int k = 0; k < 3; ++k) {
    const json& l = m["labels"][k];
    EXPECT_EQ(l["label"], values[k]);
    EXPECT_EQ(l["components"], 1);
    EXPECT_TRUE(l["closed"].get<bool>()) << l.dump();
    EXPECT_EQ(l["euler_characteristic"], 2);
    // The same object alone, as a 0/1 mask measured without --labels: the indicator is that
    // mask (cropped, which changes no value the mesher or the estimator reads).
    const int value = values[k];
    const std::string alone = write_nrrd(dir, "alone" + std::to_string(value), "uint8",
                                         [&](int x, int y, int z) { return three_labels(x, y, z) == value ? 1 : 0; });
    const json a = run_json({"measure", alone, "--json"});
    ASSERT_EQ(a["objects"].size(), 1u) << a.dump();
    const json& o = a["objects"][0];
    for (const char* q : {"area", "volume", "integral_H", "integral_K"})
      EXPECT_NEAR(l[q].get<double>(), o[q].get<double>(), 1e-4 * std::abs(o[q].get<double>()) + 1e-9)
          << "label " << value << ": " << q;
  }
  // Labels 1 and 2 touch along a plane: both surfaces pass through it, so together they are
  // larger than the union's single surface.
  const std::string union_ = write_nrrd(dir, "union", "uint8", [](int x, int y, int z) { return three_labels(x, y, z) ? 1 : 0; });
  const json u = run_json({"measure", union_, "--json"});
  EXPECT_GT(m["total"]["area"].get<double>(), 1.1 * u["total"]["area"].get<double>());
  EXPECT_NEAR(m["total"]["volume"].get<double>(), u["total"]["volume"].get<double>(),
              0.01 * u["total"]["volume"].get<double>());
}

TEST(CliLabels, MeshesCarryLabelOnPointsAndCellsAndSplitWritesOneFilePerLabel) {
  TempDir dir("labels");
  const std::string map = write_nrrd(dir, "map", "uint8", [](int x, int y, int z) { return three_labels(x, y, z); });
  const json e = run_json({"extract", map, "--labels", "-o", dir / "all.vtp", "--json"});
  EXPECT_EQ(e["labels"].size(), 3u) << e.dump();
  const io::MeshFile f = io::read_mesh(dir / "all.vtp");
  ASSERT_TRUE(f.field.has_value());
  const auto label = std::find_if(f.field->extra.begin(), f.field->extra.end(),
                                  [](const auto& x) { return x.name == "Label"; });
  ASSERT_NE(label, f.field->extra.end());
  ASSERT_EQ(f.cells.size(), 1u);
  EXPECT_EQ(f.cells[0].name, "Label");
  ASSERT_EQ(f.cells[0].values.size(), f.mesh.triangles.size());
  std::set<int> seen;
  for (std::size_t t = 0; t < f.mesh.triangles.size(); ++t) {
    const int l = f.cells[0].values[t];
    seen.insert(l);
    for (std::uint32_t v : f.mesh.triangles[t]) ASSERT_EQ(label->values[v], float(l)) << "triangle " << t;
  }
  EXPECT_EQ(seen, (std::set<int>{1, 2, 5}));

  // curvature --split with a label the map lacks: a warning naming it, one file per other label.
  const auto r = run_isocurv({"curvature", map, "--label", "5,1,9", "--split", "-o", dir / "split"}, 120);
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_NE(r.err.find("label 9"), std::string::npos) << r.describe();
  for (const char* name : {"label_5.vtp", "label_1.vtp"}) {
    const io::MeshFile one = io::read_mesh(dir / (std::string("split/") + name));
    ASSERT_TRUE(one.field.has_value()) << name;
    EXPECT_EQ(one.field->H.size(), one.mesh.positions.size()) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "split/label_2.vtp"));

  // run and render take --labels too; render colours by the Label array.
  const json run = run_json({"run", map, "--labels", "-o", dir / "run", "--json"});
  EXPECT_EQ(run["labels"].size(), 3u);
  EXPECT_EQ(io::read_mesh(dir / "run/map.vtp").cells.size(), 1u);
  const auto p = run_isocurv({"render", map, "--labels", "--color", "Label", "-o", dir / "l.png"}, 120);
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_GT(png_size(dir / "l.png")[0], 0u);
}

// check understands isocurv's labelled meshes: touching labels' coincident walls are each label's
// own closed surface, not duplicate vertices (it reported PROBLEMS FOUND).
TEST(CliLabels, CheckAcceptsTheWallsOfTouchingLabels) {
  TempDir dir("labels_check");
  const std::string map = write_nrrd(dir, "map", "uint8", [](int x, int y, int z) { return three_labels(x, y, z); });
  const std::string mesh = dir / "labels.vtp";
  ASSERT_TRUE(run_isocurv({"extract", map, "--labels", "-o", mesh, "--quiet"}, 120).ok());
  const auto r = run_isocurv({"check", mesh, "--json"}, 120);
  EXPECT_EQ(r.exit_code, 0) << r.describe();
  const json j = parse_json(r.out, "check --json");
  EXPECT_TRUE(j["labelled"].get<bool>());
  EXPECT_EQ(j["duplicate_vertices"], 0) << j.dump();
  EXPECT_GT(j["label_wall_vertices"].get<int>(), 0) << "labels 1 and 2 touch";
  EXPECT_FALSE(j["problems_found"].get<bool>());
  // The same triangles without their labels (a .ply written by another tool) are judged as any
  // mesh: the coincident vertices are duplicates there.
  const Mesh bare = io::read_mesh(mesh).mesh;
  const std::string plain = dir / "plain.ply";
  io::write_mesh(plain, bare, nullptr);
  const auto p = run_isocurv({"check", plain, "--json"}, 120);
  EXPECT_EQ(p.exit_code, 1) << p.describe();
  EXPECT_GT(parse_json(p.out, "check --json")["duplicate_vertices"].get<int>(), 0);
}

/// The mean of a mesh file's point array `name` (NaN when it lacks it).
double array_mean(const std::string& path, const std::string& name) {
  const io::MeshFile f = io::read_mesh(path);
  if (!f.field) return std::nan("");
  for (const auto& a : f.field->extra)
    if (a.name == name && !a.values.empty()) {
      double sum = 0;
      for (float v : a.values) sum += v;
      return sum / double(a.values.size());
    }
  return std::nan("");
}

// lines, features, compare and screen take --labels as extract and curvature do: each label's
// surface and curvature on its own indicator (the same numbers as the label alone as a 0/1
// mask), and screen casts the picked labels together (as the union mask).
TEST(CliLabels, LinesFeaturesCompareAndScreenTakeLabels) {
  TempDir dir("labels");
  const std::string map = write_nrrd(dir, "map", "uint8", [](int x, int y, int z) { return three_labels(x, y, z); });
  const std::string alone = write_nrrd(dir, "alone2", "uint8",
                                       [](int x, int y, int z) { return three_labels(x, y, z) == 2 ? 1 : 0; });
  const std::string both = write_nrrd(dir, "both", "uint8", [](int x, int y, int z) {
    const int l = three_labels(x, y, z);
    return l == 1 || l == 2 ? 1 : 0;
  });
  auto near = [](const json& a, const json& b, const char* what) {
    EXPECT_NEAR(a.get<double>(), b.get<double>(), 1e-4 * std::abs(b.get<double>()) + 1e-9) << what;
  };
  // lines: the label's contours, as long as the mask's.
  const json l = run_json({"lines", map, "--label", "2", "-o", dir / "l.vtp", "--json"});
  const json la = run_json({"lines", alone, "-o", dir / "la.vtp", "--json"});
  ASSERT_GT(la["length"]["contours"].get<double>(), 0.0) << la.dump();
  near(l["length"]["contours"], la["length"]["contours"], "contour length");
  near(l["length"]["suggestive"], la["length"]["suggestive"], "suggestive length");
  // features: the label's neighbourhoods on its own indicator.
  const json f = run_json({"features", map, "--label", "2", "--radius", "3", "-o", dir / "f.vtp", "--json"});
  run_json({"features", alone, "--radius", "3", "-o", dir / "fa.vtp", "--json"});
  EXPECT_EQ(f["features"]["radii"][0]["world"], 3.0) << f.dump();
  for (const char* a : {"H_ii", "Vr", "LBE"}) {
    const double mine = array_mean(dir / "f.vtp", a), theirs = array_mean(dir / "fa.vtp", a);
    ASSERT_TRUE(std::isfinite(theirs)) << a;
    EXPECT_NEAR(mine, theirs, 1e-4 * std::abs(theirs) + 1e-9) << a;
  }
  EXPECT_TRUE(std::isfinite(array_mean(dir / "f.vtp", "Label")));
  // A radius in % is of the map's box diagonal, one radius for every label.
  const json fp = run_json({"features", map, "--labels", "--radius", "5%", "-o", dir / "fp.vtp", "--json"});
  EXPECT_NEAR(fp["features"]["radii"][0]["world"].get<double>(), 0.05 * std::sqrt(3.0) * (kN - 1), 1e-3);
  // compare: every estimator on each label, the rows over all labels.
  const json c = run_json({"compare", map, "--labels", "--json"});
  const json c2 = run_json({"compare", map, "--label", "2", "--json"});
  const json ca = run_json({"compare", alone, "--json"});
  EXPECT_EQ(c["labels"], 3);
  EXPECT_EQ(c["vertices"].get<std::size_t>(), labelled_mesh_vertices(map));
  ASSERT_EQ(c2["estimators"].size(), ca["estimators"].size());
  for (std::size_t i = 0; i < ca["estimators"].size(); ++i) {
    EXPECT_EQ(c2["estimators"][i]["counted"], ca["estimators"][i]["counted"]);
    near(c2["estimators"][i]["H"]["p50"], ca["estimators"][i]["H"]["p50"],
         ca["estimators"][i]["estimator"].get<std::string>().c_str());
  }
  // screen: labels 1 and 2 together, as their union's mask (the cast reads the indicator's
  // cropped box, so the surface's brick box and the framing move by a fraction of a pixel: 0.05%
  // of the pixels); no isovalue in the title.
  const json sc = run_json({"screen", map, "--label", "1,2", "-o", dir / "s.png", "--json"});
  const json sb = run_json({"screen", both, "-o", dir / "sb.png", "--json"});
  EXPECT_NEAR(sc["surface_pixels"].get<double>(), sb["surface_pixels"].get<double>(),
              0.005 * sb["surface_pixels"].get<double>());
  EXPECT_NEAR(sc["median_H"].get<double>(), sb["median_H"].get<double>(),
              0.01 * std::abs(sb["median_H"].get<double>()));
  EXPECT_EQ(sc.value("title", std::string()).find("iso"), std::string::npos) << sc.dump();
}

TEST(CliLabels, RefusesWhatIsNotALabelMap) {
  TempDir dir("labels");
  const std::string map = write_nrrd(dir, "map", "uint8", [](int x, int y, int z) { return three_labels(x, y, z); });
  const std::string floats = write_nrrd(dir, "floats", "float", [](int x, int y, int z) { return three_labels(x, y, z); });
  expect_clean_failure(run_isocurv({"measure", floats, "--labels"}), "integer label map");
  expect_clean_failure(run_isocurv({"measure", dataset("torus"), "--labels"}), "integer label map");
  expect_clean_failure(run_isocurv({"extract", map, "--labels", "--iso", "1", "-o", dir / "x.vtp"}), "--iso");
  expect_clean_failure(run_isocurv({"measure", map, "--label", "7"}), "none of the labels");
  // A list that does not parse, or an empty one (once silently measured without labels), is a
  // usage error (status 2, the fuzzing campaign's finding).
  for (const char* bad : {"1,x", "", "2.5", "3,3"})
    expect_usage_error(run_isocurv({"measure", map, "--label", bad}), "--label");
  expect_clean_failure(run_isocurv({"extract", map, "--split", "-o", dir / "s"}), "--split needs --labels");
  ASSERT_TRUE(run_isocurv({"extract", map, "-o", dir / "plain.vtp", "--quiet"}).ok());
  expect_clean_failure(run_isocurv({"measure", dir / "plain.vtp", "--labels"}), "needs a volume");
  expect_clean_failure(run_isocurv({"curvature", map, map, "--labels", "-o", dir / "batch"}),
                       "one label map at a time");
  EXPECT_FALSE(fs::exists(dir / "x.vtp"));
  EXPECT_FALSE(fs::exists(dir / "s"));
}

}  // namespace
}  // namespace isocurv::test
