#pragma once
// Registration of the isocurv subcommands; each register_* is defined in its cmd_*.cpp.
#include <CLI/CLI.hpp>

#include <string>

namespace isocurv::app {

void register_commands(CLI::App& app);  ///< all subcommands below, then require_finite_numbers
/// Every floating-point option of `app` and its subcommands refuses NaN and infinities (a usage
/// error naming the option), whatever range it also checks.
void require_finite_numbers(CLI::App& app);

/// How a command runs under mpirun with several ranks (docs/distributed.md), the one place that
/// says so (main() and the batches ask here).
enum class OnRanks {
  refused,  ///< every rank would write the same files: refused in one line
  divided,  ///< one volume divided among the ranks, or a batch handed out (extract, curvature, run, check, features)
  batches,  ///< only a batch of inputs handed out; one input is refused (lines)
};
OnRanks on_ranks(const std::string& command);

/// The exit status a command that ran to its end asks for (0 unless set): `check` sets 1 when it
/// reports problems. main() returns it after a successful run.
int& command_exit_status();
void register_info(CLI::App& app);      ///< isocurv info VOLUME
void register_devices(CLI::App& app);   ///< isocurv devices
void register_extract(CLI::App& app);   ///< isocurv extract VOLUME -o MESH
void register_check(CLI::App& app);     ///< isocurv check MESH_OR_VOLUME
void register_curvature(CLI::App& app); ///< isocurv curvature VOLUME_OR_MESH -o MESH
void register_render(CLI::App& app);    ///< isocurv render VOLUME_OR_MESH -o PNG
void register_run(CLI::App& app);       ///< isocurv run VOLUME -o DIR
void register_view(CLI::App& app);      ///< isocurv view VOLUME
void register_features(CLI::App& app);  ///< isocurv features VOLUME_OR_MESH --radius R -o MESH
void register_compare(CLI::App& app);   ///< isocurv compare VOLUME_OR_MESH
void register_measure(CLI::App& app);   ///< isocurv measure VOLUME_OR_MESH
void register_screen(CLI::App& app);    ///< isocurv screen VOLUME_OR_MESH -o PNG
void register_lines(CLI::App& app);     ///< isocurv lines VOLUME_OR_MESH -o VTP|SVG
void register_deform(CLI::App& app);    ///< isocurv deform MESH --deformer D -o DIR

}  // namespace isocurv::app
