// meshvid: codec and file format for captured dynamic 3D surfaces.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "meshvid/version.h"
#include "tools/cli/commands.h"
#include "tools/cli/internal_error.h"

namespace {

/// Exit code of a command line that names no known command (see commands.h).
constexpr int kExitUsage = 2;

int Run(int argc, char** argv) {
  CLI::App app{
      "meshvid: codec and file format for captured dynamic 3D surfaces.\n"
      "Turns a multi-view capture (K range meshes per frame) into one compact .mvid file and\n"
      "back, and measures the result against ground truth."};
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 done; 1 the command failed (bad or missing data, an error reading or\n"
      "writing); 2 the command line is wrong (an unknown command or option, a value out of\n"
      "range); 3 an internal error (a bug: please report it).\n");
  app.set_version_flag("--version", "meshvid " MESHVID_VERSION_STRING);
  int exit_code = 0;
  // In the order of the work: capture, encode, look, decode, use, measure.
  meshvid::cli::AddSimulateCommand(app, &exit_code);
  meshvid::cli::AddEncodeCommand(app, &exit_code);
  meshvid::cli::AddInfoCommand(app, &exit_code);
  meshvid::cli::AddDecodeCommand(app, &exit_code);
  meshvid::cli::AddExportCommand(app, &exit_code);
  meshvid::cli::AddRenderCommand(app, &exit_code);
  meshvid::cli::AddEvalCommand(app, &exit_code);
  meshvid::cli::AddFuseCommand(app, &exit_code);
  meshvid::cli::AddConcatCommand(app, &exit_code);
  meshvid::cli::AddCutCommand(app, &exit_code);
  meshvid::cli::AddTranscodeCommand(app, &exit_code);
  meshvid::cli::AddEditCommand(app, &exit_code);
  meshvid::cli::AddBenchCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A first word that is no command: name it (CLI11 would only say one is required).
    const std::vector<std::string> extras = app.remaining();
    if (app.get_subcommands().empty() && !extras.empty() && !extras.front().starts_with('-')) {
      std::string commands;
      // Hidden commands (no group: run by meshvid bench) are not listed.
      for (const CLI::App* command :
           app.get_subcommands([](const CLI::App* c) { return !c->get_group().empty(); })) {
        commands += (commands.empty() ? "" : ", ") + command->get_name();
      }
      std::fprintf(stderr, "meshvid: unknown command '%s' (commands: %s); see meshvid --help\n",
                   extras.front().c_str(), commands.c_str());
      return kExitUsage;
    }
    // --help and --version: CLI11 prints them and exits 0.
    if (e.get_exit_code() == 0) return app.exit(e);
    // Any other bad command line: one line in the tool's own style, and the usage exit code.
    const std::vector<CLI::App*> given = app.get_subcommands();
    const std::string help =
        "meshvid " + (given.empty() ? std::string() : given.front()->get_name() + " ") + "--help";
    std::fprintf(stderr, "meshvid: %s (see %s)\n", e.what(), help.c_str());
    if (!given.empty() && given.front()->get_name() == "encode") {
      const std::string hint = meshvid::cli::FormerTuningFlagHint(given.front()->remaining());
      if (!hint.empty()) std::fprintf(stderr, "meshvid: %s\n", hint.c_str());
    }
    return kExitUsage;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  return meshvid::cli::RunCatchingInternalErrors([&] { return Run(argc, argv); });
}
