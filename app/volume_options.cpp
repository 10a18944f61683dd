#include "app/volume_options.h"

#include "core/error.h"

namespace isocurv::app {

void add_volume_options(CLI::App& cmd, VolumeOptions& o) {
  cmd.add_option("--grid", o.grid, ".vdb: grid name (default: the first float grid)")->group("Volume");
  cmd.add_option("--inside", o.inside,
                 "Which side of the isovalue is the object: above (densities, CT; the default) or "
                 "below (level sets, the default for VDB level sets). Normals point out of the object.")
      ->check(CLI::IsMember({"above", "below"}))->group("Volume");
  cmd.add_option("--dims", o.dims, ".raw: X Y Z voxel counts (X fastest)")->expected(3)->group("Volume");
  cmd.add_option("--type", o.type, ".raw: voxel type")
      ->check(CLI::IsMember({"uint8", "int8", "uint16", "int16", "uint32", "int32", "float", "double"}))
      ->group("Volume");
  cmd.add_option("--endian", o.endian, ".raw: byte order")->check(CLI::IsMember({"little", "big"}))
      ->capture_default_str()->group("Volume");
  cmd.add_option("--spacing", o.spacing, ".raw: voxel spacing X Y Z")->expected(3)->capture_default_str()->group("Volume");
  cmd.add_option("--origin", o.origin, ".raw: world origin X Y Z")->expected(3)->capture_default_str()->group("Volume");
}

volume::LoadOptions to_load_options(const VolumeOptions& o) {
  volume::LoadOptions l;
  l.grid = o.grid;
  if (o.inside == "above") l.inside = volume::Inside::Above;
  if (o.inside == "below") l.inside = volume::Inside::Below;
  if (o.dims.size() == 3) l.raw.dims = {o.dims[0], o.dims[1], o.dims[2]};
  l.raw.type = o.type;
  l.raw.big_endian = o.endian == "big";
  if (o.spacing.size() == 3) l.raw.spacing = {o.spacing[0], o.spacing[1], o.spacing[2]};
  if (o.origin.size() == 3) l.raw.origin = {o.origin[0], o.origin[1], o.origin[2]};
  return l;
}

}  // namespace isocurv::app
