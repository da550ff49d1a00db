// meshvid: codec and file format for captured dynamic 3D surfaces.
#include <CLI/CLI.hpp>

#include "tools/cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "meshvid: codec and file format for captured dynamic 3D surfaces.\n"
      "Turns a multi-view capture (K range meshes per frame) into one compact .mvid file and\n"
      "back, and measures the result against ground truth."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "meshvid 0.1.0");
  int exit_code = 0;
  meshvid::cli::AddSimulateCommand(app, &exit_code);
  meshvid::cli::AddEvalCommand(app, &exit_code);
  meshvid::cli::AddInfoCommand(app, &exit_code);
  meshvid::cli::AddEncodeCommand(app, &exit_code);
  meshvid::cli::AddBenchCommand(app, &exit_code);
  meshvid::cli::AddDecodeCommand(app, &exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  return exit_code;
}
