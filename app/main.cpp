// isocurv: the command line. Each subcommand lives in its own cmd_*.cpp and only composes stages.
// Exit status: 0 success, 1 bad input or a failure, 2 a usage error (bad or missing arguments).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/suggest.h"
#include "core/error.h"
#include "core/huge_pages.h"
#include "dist/world.h"
#include "io/vtk_errors.h"

namespace {

constexpr int kUsageError = 2;
constexpr int kFailure = 1;

}  // namespace

namespace {

// Under mpirun every rank runs main(): only rank 0 prints errors (they agree on them, dist/world.h).
bool prints_errors() { return isocurv::dist::World::get().rank() == 0; }

int run(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) {
  try {
    isocurv::dist::World::init(argc, argv);
  } catch (const isocurv::Error& e) {
    std::fprintf(stderr, "isocurv: %s\n", isocurv::one_line(e.what()).c_str());
    return kFailure;
  }
  const int status = run(argc, argv);
  isocurv::dist::World::finalize();
  return status;
}

namespace {

int run(int argc, char** argv) {
  isocurv::retain_freed_memory();  // the explorer re-extracts on every slider move
  isocurv::io::silence_vtk_output();  // VTK's messages reach the user only as our one-line errors
  // Named, so that usage lines say "isocurv", not the path it was started by (build/app/isocurv).
  CLI::App app{"isocurv: isosurfaces and their curvature from volumes (OpenVDB, OpenCL, VTK)", "isocurv"};
  app.require_subcommand(0, 1);  // none given is handled below, after CLI11 named any stray option
  app.set_version_flag("--version", "isocurv 0.1.0");
  app.footer(
      "Run isocurv COMMAND --help for a command's options and an example.\n"
      "Exit status: 0 success, 1 bad input or a failure (one line on stderr), 2 a usage error.\n"
      "isocurv without arguments prints this list and exits with status 2.\n"
      "Docs: README.md, and docs/ for one page per task.");
  isocurv::app::register_commands(app);
  if (argc <= 1) {
    std::cout << app.help();
    return kUsageError;
  }
  // Name a mistyped command (CLI11 would only say that a subcommand is required).
  const auto known = app.get_subcommands([&](const CLI::App* c) { return c->check_name(argv[1]); });
  // Under mpirun with several ranks only the commands that share out their work run (on_ranks).
  const isocurv::dist::World& world = isocurv::dist::World::get();
  if (world.size() > 1 && !known.empty()) {
    const std::string name = known.front()->get_name();
    if (isocurv::app::on_ranks(name) == isocurv::app::OnRanks::refused) {
      if (prints_errors())
        std::fprintf(stderr, "isocurv: %s does not run under mpirun with several ranks (docs/distributed.md)\n",
                     name.c_str());
      return kFailure;
    }
  }
  if (argv[1][0] != '-' && known.empty()) {
    std::string names;  // every registered command, so the list cannot fall behind
    for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
      names += (names.empty() ? "" : " ") + c->get_name();
    std::vector<std::string> all;
    for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
      all.push_back(c->get_name());
    const std::string near = isocurv::app::closest_name(argv[1], all);
    const std::string hint = near.empty() ? "" : "did you mean " + near + "? ";
    if (prints_errors())
      std::fprintf(stderr, "isocurv: unknown command '%s' (%scommands: %s; see isocurv --help)\n", argv[1],
                   hint.c_str(), names.c_str());
    return kUsageError;
  }
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) {  // only top-level options: still no command
      std::cout << app.help();
      return kUsageError;
    }
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --help-all, --version: printed on stdout, status 0
  } catch (const CLI::ParseError& e) {
    const std::string where = known.empty() ? "isocurv" : "isocurv " + known.front()->get_name();
    // A mistyped option: name the closest one the command knows.
    const std::string hint =
        dynamic_cast<const CLI::ExtrasError*>(&e)
            ? isocurv::app::option_suggestion(known.empty() ? &app : known.front(), argc, argv)
            : "";
    if (prints_errors())
      std::fprintf(stderr, "isocurv: %s%s (see %s --help)\n", isocurv::one_line(e.what()).c_str(),
                   hint.c_str(), where.c_str());
    return kUsageError;
  } catch (const isocurv::Error& e) {
    if (prints_errors()) std::fprintf(stderr, "isocurv: %s\n", isocurv::one_line(e.what()).c_str());
    return kFailure;
  } catch (const std::exception& e) {
    if (prints_errors()) std::fprintf(stderr, "isocurv: error: %s\n", isocurv::one_line(e.what()).c_str());
    return kFailure;
  }
  return isocurv::app::command_exit_status();
}

}  // namespace
