#include "app/volume_options.h"

namespace isocurv::app {

void add_volume_options(CLI::App& cmd, VolumeOptions& o) {
  cmd.add_option("--grid", o.grid, ".vdb: grid name (default: the first float grid)")->group("Volume");
  cmd.add_option("--inside", o.inside,
                 "Which side of the isovalue is the object: above (densities, CT; the default) or "
                 "below (level sets, the default for VDB level sets). Normals point out of the object.")
      ->check(CLI::IsMember({"above", "below"}))->group("Volume");
  cmd.add_option("--dims", o.dims, ".raw: X Y Z voxel counts (X fastest; wins over the file name)")
      ->expected(3)
      ->group("Volume");
  cmd.add_option("--type", o.type, ".raw: voxel type (wins over the file name)")
      ->check(
          CLI::IsMember({"uint8", "int8", "uint16", "int16", "uint32", "int32", "float", "double"}))
      ->group("Volume");
  cmd.add_option("--endian", o.endian,
                 ".raw: byte order (default: the file name's le/be, else little)")
      ->check(CLI::IsMember({"little", "big"}))
      ->group("Volume");
  cmd.add_option("--spacing", o.spacing,
                 "Voxel spacing X Y Z, replacing the file's (any format; raw default 1 1 1)")
      ->expected(3)
      ->group("Volume");
  cmd.add_option("--origin", o.origin,
                 "World position X Y Z of the first voxel, replacing the file's (any format; raw "
                 "default 0 0 0)")
      ->expected(3)
      ->group("Volume");
  cmd.add_option("--level", o.level,
                 "Zarr/OME-NGFF: the multiscale level to read, 0 the finest (default: the finest "
                 "that fits half the machine's memory)")
      ->check(CLI::NonNegativeNumber)
      ->group("Volume");
  cmd.add_option("--time-point", o.time_point, "Zarr/OME-NGFF: the index along the time axis (default 0)")
      ->check(CLI::NonNegativeNumber)
      ->group("Volume");
  cmd.add_option("--channel", o.channel, "Zarr/OME-NGFF: the index along the channel axis (default 0)")
      ->check(CLI::NonNegativeNumber)
      ->group("Volume");
}

std::vector<std::string> VolumeOptions::given() const {
  std::vector<std::string> out;
  if (!grid.empty()) out.push_back("--grid");
  if (!inside.empty()) out.push_back("--inside");
  if (!dims.empty()) out.push_back("--dims");
  if (!type.empty()) out.push_back("--type");
  if (!endian.empty()) out.push_back("--endian");
  if (!spacing.empty()) out.push_back("--spacing");
  if (!origin.empty()) out.push_back("--origin");
  if (level) out.push_back("--level");
  if (time_point) out.push_back("--time-point");
  if (channel) out.push_back("--channel");
  return out;
}

volume::LoadOptions to_load_options(const VolumeOptions& o) {
  volume::LoadOptions l;
  l.grid = o.grid;
  if (o.inside == "above") l.inside = volume::Inside::Above;
  if (o.inside == "below") l.inside = volume::Inside::Below;
  if (o.dims.size() == 3) l.raw.dims = {o.dims[0], o.dims[1], o.dims[2]};
  l.raw.type = o.type;
  if (!o.endian.empty()) l.raw.big_endian = o.endian == "big";
  if (o.spacing.size() == 3)
    l.spacing = std::array<double, 3>{o.spacing[0], o.spacing[1], o.spacing[2]};
  if (o.origin.size() == 3) l.origin = std::array<double, 3>{o.origin[0], o.origin[1], o.origin[2]};
  l.level = o.level;
  l.time_point = o.time_point;
  l.channel = o.channel;
  return l;
}

}  // namespace isocurv::app
