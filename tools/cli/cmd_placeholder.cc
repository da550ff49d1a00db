#include "tools/cli/commands.h"
namespace meshvid::cli {
void AddSimulateCommand(CLI::App&, int*) {}
void AddEvalCommand(CLI::App&, int*) {}
}  // namespace meshvid::cli
