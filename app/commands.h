#pragma once
// Registration of the isocurv subcommands; each register_* is defined in its cmd_*.cpp.
#include <CLI/CLI.hpp>

namespace isocurv::app {

void register_commands(CLI::App& app);  ///< all subcommands below
void register_info(CLI::App& app);      ///< isocurv info VOLUME
void register_devices(CLI::App& app);   ///< isocurv devices

}  // namespace isocurv::app
