#include "datasets/write_vdb.h"

#include <openvdb/io/File.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace isocurv::datasets {

void write_vdb(const Field& field, const volume::Volume& v, const std::string& path) {
  openvdb::initialize();
  if (!v.grid) throw Error(path, "no grid to write");
  openvdb::MetaMap meta;
  meta.insertMeta("isovalue", openvdb::DoubleMetadata(field.isovalue()));
  meta.insertMeta("inside", openvdb::StringMetadata(field.inside() == volume::Inside::Below ? "below" : "above"));
  meta.insertMeta("field", openvdb::StringMetadata(field.name()));
  meta.insertMeta("description", openvdb::StringMetadata(field.info().description));

  // Write a shallow copy (tree shared, metadata copied) so the caller's grid is left as it was.
  openvdb::FloatGrid::Ptr grid = v.grid->copy();
  for (auto it = meta.beginMeta(); it != meta.endMeta(); ++it) grid->insertMeta(it->first, *it->second);
  grid->setSaveFloatAsHalf(false);  // full float precision, stated explicitly in the grid metadata

  try {
    write_atomically(path, [&](const std::string& tmp) {
      openvdb::io::File file(tmp);
      file.write(openvdb::GridCPtrVec{grid}, meta);
      file.close();
    });
  } catch (const openvdb::Exception& e) {
    throw Error(path, std::string("cannot write .vdb: ") + e.what());
  }
}

void write_vdb_grids(const std::vector<NamedGrid>& grids, const std::string& path) {
  openvdb::initialize();
  openvdb::GridCPtrVec out;
  for (const NamedGrid& g : grids) {
    if (!g.field || !g.volume || !g.volume->grid) throw Error(path, "no grid to write");
    openvdb::FloatGrid::Ptr grid = g.volume->grid->copy();
    grid->setName(g.name);
    grid->insertMeta("isovalue", openvdb::DoubleMetadata(g.field->isovalue()));
    grid->insertMeta("inside", openvdb::StringMetadata(
                                   g.field->inside() == volume::Inside::Below ? "below" : "above"));
    grid->insertMeta("field", openvdb::StringMetadata(g.field->name()));
    grid->insertMeta("description", openvdb::StringMetadata(g.field->info().description));
    grid->insertMeta("time", openvdb::DoubleMetadata(g.time));
    grid->setSaveFloatAsHalf(false);
    out.push_back(grid);
  }
  try {
    write_atomically(path, [&](const std::string& tmp) {
      openvdb::io::File file(tmp);
      file.write(out);
      file.close();
    });
  } catch (const openvdb::Exception& e) {
    throw Error(path, std::string("cannot write .vdb: ") + e.what());
  }
}

}  // namespace isocurv::datasets
