#include "volume/vdb_grid_names.h"

#include <openvdb/openvdb.h>

#include "core/error.h"
#include "core/natural_order.h"
#include "volume/detail/vdb_length_check.h"
#include "volume/file_bytes.h"

namespace isocurv::volume {

std::vector<std::string> vdb_grid_names(const std::string& path) {
  openvdb::initialize();
  detail::check_vdb_lengths(path,
                            file_size(path));  // before OpenVDB allocates from a corrupt length
  std::vector<std::string> names;
  try {
    openvdb::io::File file(path);
    file.open(/*delayLoad=*/false);
    const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
    file.close();
    for (const auto& g : *grids) {
      const std::string type = g->valueType();
      if (type == "float" || type == "double" || type == "half") names.push_back(g->getName());
    }
  } catch (const std::exception& e) {
    throw Error(path, std::string("cannot read the grids of this OpenVDB file: ") + e.what());
  }
  natural_sort(names);
  return names;
}

}  // namespace isocurv::volume
