// isocurv: the command line. Each subcommand lives in its own cmd_*.cpp and only composes stages.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "core/error.h"
#include "core/huge_pages.h"

int main(int argc, char** argv) {
  isocurv::retain_freed_memory();  // the explorer re-extracts on every slider move
  CLI::App app{"isocurv: isosurfaces and their curvature from volumes (OpenVDB, OpenCL, VTK)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "isocurv 0.1.0");
  isocurv::app::register_commands(app);
  // Name a mistyped command (CLI11 would only say that a subcommand is required).
  const auto known = app.get_subcommands([&](const CLI::App* c) { return argc > 1 && c->check_name(argv[1]); });
  if (argc > 1 && argv[1][0] != '-' && known.empty()) {
    std::fprintf(stderr, "isocurv: unknown command '%s' (commands: info extract curvature run render view check devices; "
                         "see isocurv --help)\n", argv[1]);
    return 1;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const isocurv::Error& e) {
    std::fprintf(stderr, "isocurv: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "isocurv: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
