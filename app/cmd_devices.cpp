// isocurv devices: the OpenCL devices and which one is the default.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/commands.h"
#include "core/cl_device.h"

namespace isocurv::app {

void register_devices(CLI::App& app) {
  auto* cmd = app.add_subcommand("devices", "List OpenCL devices (the index is what --device takes)");
  cmd->footer(
      "Example: isocurv devices --json\n"
      "Besides these, every compute command takes --device reference (the C++ references,\n"
      "no OpenCL).");
  static bool json = false;
  cmd->add_flag("--json", json, "Print a JSON array");
  cmd->callback([] {
    std::vector<DeviceInfo> devices;
    int def = -1;
    const char* env = std::getenv("ISOCURV_DEVICE");
    const bool reference =
        env && std::string(env) == "reference";  // then no OpenCL device is the default
    try {
      devices = list_devices();
      if (!reference) def = Device::default_device().info().index;
    } catch (const NoOpenCL& e) {
      throw Error(std::string(e.what()) +
                  "; without one, the compute commands run with --device reference (slow)");
    }
    if (json) {
      nlohmann::json out = nlohmann::json::array();
      for (auto& d : devices)
        out.push_back({{"index", d.index}, {"platform", d.platform}, {"name", d.name}, {"type", d.type},
                       {"version", d.version}, {"global_memory", d.global_memory},
                       {"compute_units", d.compute_units}, {"default", d.index == def}});
      std::cout << out.dump(2) << "\n";
      return;
    }
    for (auto& d : devices)
      std::printf("%c %d  %-4s %s (%s; %s; %u compute units, %.1f GiB)\n", d.index == def ? '*' : ' ',
                  d.index, d.type.c_str(), d.name.c_str(), d.platform.c_str(), d.version.c_str(),
                  d.compute_units, d.global_memory / 1073741824.0);
    if (reference) std::printf("  (ISOCURV_DEVICE=reference: the default is the C++ reference)\n");
    std::printf(
        "(* = default; choose another with --device N or ISOCURV_DEVICE=N; --device reference\n"
        " runs the C++ references instead of OpenCL: slow, single-threaded, always available)\n");
  });
}

}  // namespace isocurv::app
