// isocurv info VOLUME: what the volume holds and a suggested isovalue.
#include <iostream>

#include "app/commands.h"
#include "app/volume_options.h"
#include "volume/load.h"
#include "volume/summary.h"

namespace isocurv::app {

void register_info(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Describe a volume: dimensions, spacing, value range, histogram, suggested isovalue");
  cmd->footer("Example: isocurv info head.nrrd --json\n"
              "         isocurv info scan.raw --dims 256 256 128 --type uint16 --spacing 0.5 0.5 1");
  static std::string path;
  static bool json = false;
  static VolumeOptions vopts;
  cmd->add_option("VOLUME", path, "Volume file (.vdb .nrrd .nhdr .mhd .mha .nii .nii.gz .vti .vtk .vol .raw .raw.gz)")->required();
  cmd->add_flag("--json", json, "Print a JSON object instead of text");
  add_volume_options(*cmd, vopts);
  cmd->callback([] {
    volume::Volume v = volume::load(path, to_load_options(vopts));
    if (json)
      std::cout << volume::summary_json(v).dump(2) << "\n";
    else
      std::cout << volume::summary_text(v);
  });
}

}  // namespace isocurv::app
