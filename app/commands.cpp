#include "app/commands.h"

#include <cmath>
#include <cstdlib>

#include <string>
#include <utility>

namespace isocurv::app {

namespace {

/// Each command's page under docs/, the last line of its --help ("Docs: docs/PAGE.md").
/// tests/docs/run_examples.py checks that every command has one and that the page exists.
const std::pair<const char*, const char*> kDocPages[] = {
    {"info", "volumes.md"},       {"extract", "extraction.md"}, {"check", "extraction.md"},
    {"curvature", "curvature.md"}, {"run", "curvature.md"},      {"compare", "curvature.md"},
    {"features", "features.md"},  {"render", "pictures.md"},    {"view", "pictures.md"},
    {"lines", "lines.md"},        {"deform", "time-series.md"}, {"screen", "screen.md"},
    {"devices", "install.md"},    {"measure", "measure.md"},
};

}  // namespace

int& command_exit_status() {
  static int status = 0;
  return status;
}

OnRanks on_ranks(const std::string& command) {
  // extract and curvature divide one volume (a .pvtp or --gather); run, check and features divide
  // its extraction and finish on rank 0; lines on one input would run once per rank.
  for (const char* divided : {"extract", "curvature", "run", "check", "features"})
    if (command == divided) return OnRanks::divided;
  if (command == "lines") return OnRanks::batches;
  return OnRanks::refused;
}

void register_commands(CLI::App& app) {
  register_info(app);
  register_extract(app);
  register_curvature(app);
  register_features(app);
  register_run(app);
  register_render(app);
  register_lines(app);
  register_deform(app);
  register_screen(app);
  register_view(app);
  register_check(app);
  register_compare(app);
  register_measure(app);
  register_devices(app);
  for (const auto& [name, page] : kDocPages) {
    CLI::App* cmd = app.get_subcommand(name);  // throws for a name no command has
    cmd->footer(cmd->get_footer() + "\nDocs: docs/" + page);
  }
  require_finite_numbers(app);
}

void require_finite_numbers(CLI::App& app) {
  // CLI11's ranges compare, and every comparison with NaN is false: "nan" passed them all.
  static const CLI::Validator finite(
      [](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end != text.c_str() && !std::isfinite(v)) return "must be a finite number, not " + text;
        return std::string();
      },
      "");
  for (CLI::Option* o : app.get_options())
    if (o->get_type_name().find("FLOAT") != std::string::npos) o->check(finite);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) require_finite_numbers(*sub);
}

}  // namespace isocurv::app
