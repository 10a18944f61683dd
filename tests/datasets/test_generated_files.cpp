// The .vdb files written at build time into <build>/datasets/ exist, are small, and load.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <openvdb/io/File.h>

#include <filesystem>

#include "datasets/field.h"
#include "datasets/sample.h"
#include "datasets/write_vdb.h"

using namespace isocurv;
using namespace isocurv::datasets;

namespace {

struct Loaded {
  openvdb::FloatGrid::Ptr grid;
  openvdb::MetaMap::Ptr file_meta;
};

Loaded load(const std::string& path) {
  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  Loaded l;
  l.file_meta = file.getMetadata();
  const auto grids = file.getGrids();
  file.close();
  EXPECT_EQ(grids->size(), 1u) << path;
  l.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
  return l;
}

// The grid holds the field's values at the voxels' world positions, and the metadata describes it.
void check(const Field& f, const Loaded& l, const std::string& path) {
  ASSERT_TRUE(l.grid) << path << " holds no float grid";
  const bool below = f.inside() == volume::Inside::Below;
  EXPECT_EQ(l.grid->getName(), below ? "levelset" : "density") << path;
  EXPECT_EQ(l.grid->getGridClass() == openvdb::GRID_LEVEL_SET, below) << path;
  for (const openvdb::MetaMap* m : {static_cast<const openvdb::MetaMap*>(l.grid.get()),
                                    static_cast<const openvdb::MetaMap*>(l.file_meta.get())}) {
    EXPECT_EQ(m->metaValue<double>("isovalue"), f.isovalue()) << path;
    EXPECT_EQ(m->metaValue<std::string>("inside"), below ? "below" : "above") << path;
    EXPECT_EQ(m->metaValue<std::string>("field"), f.name()) << path;
  }
  const openvdb::CoordBBox bbox = l.grid->evalActiveVoxelBoundingBox();
  EXPECT_EQ(bbox.min(), openvdb::Coord(0, 0, 0)) << path;
  auto acc = l.grid->getConstAccessor();
  for (const openvdb::Coord ijk : {bbox.min(), bbox.max(), openvdb::Coord((bbox.min().asVec3i() + bbox.max().asVec3i()) / 2), openvdb::Coord(1, 2, 3)}) {
    const openvdb::Vec3d w = l.grid->transform().indexToWorld(ijk);
    EXPECT_EQ(acc.getValue(ijk), static_cast<float>(f.value(Eigen::Vector3d(w.x(), w.y(), w.z())))) << path << ijk;
  }
}

}  // namespace

TEST(GeneratedFiles, EveryFieldWasWrittenAtBuildTime) {
  const std::filesystem::path dir = std::filesystem::path(isocurv::test_paths::build_dir()) / "datasets";
  for (const auto& name : field_names()) {
    const std::string path = (dir / (name + ".vdb")).string();
    ASSERT_TRUE(std::filesystem::exists(path)) << path << " missing: the isocurv_datasets_vdb target writes it";
    EXPECT_LT(std::filesystem::file_size(path), 2u << 20) << path;
    check(*make_field(name), load(path), path);
  }
}

TEST(GeneratedFiles, WriteVdbRoundTrip) {
  auto f = make_field("sphere");
  const volume::Volume v = sample(*f, 12);
  const std::string path = (std::filesystem::temp_directory_path() / "isocurv_test_sphere.vdb").string();
  write_vdb(*f, v, path);
  const Loaded l = load(path);
  check(*f, l, path);
  EXPECT_EQ(l.grid->activeVoxelCount(), v.grid->activeVoxelCount());
  EXPECT_EQ(l.grid->transform(), v.grid->transform());
  std::filesystem::remove(path);
}
