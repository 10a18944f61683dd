// isocurv info VOLUME: what the volume holds and a suggested isovalue.
#include <iostream>

#include "app/commands.h"
#include "app/volume_options.h"
#include "volume/load.h"
#include "volume/summary.h"
#include "volume/zarr.h"

namespace isocurv::app {

void register_info(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Describe a volume: dimensions, spacing, value range, histogram, suggested isovalue");
  cmd->footer("Example: isocurv info head.nrrd --json\n"
              "         isocurv info scan.raw --dims 256 256 128 --type uint16 --spacing 0.5 0.5 1\n"
              "         isocurv info cells.ome.zarr --level 1 --channel 0");
  static std::string path;
  static bool json = false;
  static VolumeOptions vopts;
  cmd->add_option("VOLUME", path, "Volume file (.vdb .nrrd .nhdr .mhd .mha .nii .nii.gz .vti .vtk .vol .raw .raw.gz) or Zarr store folder")->required();
  cmd->add_flag("--json", json, "Print a JSON object instead of text");
  add_volume_options(*cmd, vopts);
  cmd->callback([] {
    const volume::LoadOptions lo = to_load_options(vopts);
    volume::Volume v = volume::load(path, lo);
    // A Zarr store also shows its levels, chunks and codecs (docs/big-volumes.md).
    const bool zarr = volume::is_zarr_store(path);
    volume::ZarrInfo zinfo;
    if (zarr) zinfo = volume::describe_zarr(path);
    if (json) {
      nlohmann::json j = volume::summary_json(v);
      if (zarr) j["zarr"] = volume::zarr_summary_json(zinfo, volume::choose_zarr_level(zinfo, lo));
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << volume::summary_text(v);
      if (zarr) std::cout << volume::zarr_summary_text(zinfo, volume::choose_zarr_level(zinfo, lo));
    }
  });
}

}  // namespace isocurv::app
