// Subcommands of the `meshvid` executable. Each cmd_*.cc file adds one subcommand to the app;
// its callback stores the process exit code in *exit_code (0 ok, 1 failure, 2 usage). main()
// exits 3 when an exception escapes a command (an internal error: tools/cli/internal_error.h).
#ifndef MESHVID_TOOLS_CLI_COMMANDS_H_
#define MESHVID_TOOLS_CLI_COMMANDS_H_

#include <CLI/CLI.hpp>

namespace meshvid::cli {

/// Where `args` (a refused `meshvid encode` command line's leftovers) hold a flag that became a
/// --tune key, the line saying so ("--node-spacing is now --tune node_spacing=VALUE"); empty
/// otherwise.
std::string FormerTuningFlagHint(const std::vector<std::string>& args);

void AddSimulateCommand(CLI::App& app, int* exit_code);
void AddEvalCommand(CLI::App& app, int* exit_code);
void AddInfoCommand(CLI::App& app, int* exit_code);
void AddDecodeCommand(CLI::App& app, int* exit_code);
void AddEncodeCommand(CLI::App& app, int* exit_code);
void AddBenchCommand(CLI::App& app, int* exit_code);
void AddFuseCommand(CLI::App& app, int* exit_code);
void AddExportCommand(CLI::App& app, int* exit_code);
void AddRenderCommand(CLI::App& app, int* exit_code);
void AddConcatCommand(CLI::App& app, int* exit_code);
void AddCutCommand(CLI::App& app, int* exit_code);
void AddTranscodeCommand(CLI::App& app, int* exit_code);
void AddEditCommand(CLI::App& app, int* exit_code);

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_COMMANDS_H_
