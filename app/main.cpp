// isocurv: the command line. Each subcommand lives in its own cmd_*.cpp and only composes stages.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"isocurv: isosurfaces and their curvature from volumes (OpenVDB, OpenCL, VTK)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "isocurv 0.1.0");
  isocurv::app::register_commands(app);
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
