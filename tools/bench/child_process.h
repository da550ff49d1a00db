// Running a step of the benchmark as a child process, measured the way `/usr/bin/time -v`
// does: wall time, CPU time and peak resident memory (wait4's rusage).
#ifndef MESHVID_TOOLS_BENCH_CHILD_PROCESS_H_
#define MESHVID_TOOLS_BENCH_CHILD_PROCESS_H_

#include <string>
#include <vector>

#include "format/status.h"

namespace meshvid {

/// What a finished child process returned and cost.
struct ChildRun {
  int exit_code = -1;       ///< the exit status, or -1 if a signal ended it
  int signal = 0;           ///< the signal that ended it, or 0
  double wall_seconds = 0;  ///< from spawn to exit
  double cpu_seconds = 0;   ///< user + system time of the child
  double peak_rss_mb = 0;   ///< ru_maxrss in MB (10^6 bytes); see RunChild
  std::string log_path;     ///< where its stdout and stderr went
  bool ok() const { return exit_code == 0; }
};

/// Runs `argv` (argv[0] is the executable's path, not searched in PATH unless it has no '/')
/// with stdin from /dev/null and stdout and stderr written to `log_path` (truncated;
/// "" discards them), waits for it and measures it. The peak memory is the kernel's
/// ru_maxrss of the child, which on Linux also counts the parent's resident memory at the
/// spawn (exec keeps the larger high-water mark): keep the parent small. Fails only if the
/// process cannot be started; a child that exits non-zero is a ChildRun with that code.
StatusOr<ChildRun> RunChild(const std::vector<std::string>& argv, const std::string& log_path);

/// The last `max_lines` non-empty lines of a text file (for failure messages), joined with
/// "; ", or "" if it cannot be read.
std::string LogTail(const std::string& path, int max_lines = 3);

/// `argv` as one shell-quoted command line, for reports ("meshvid encode 'a b.json' ...").
std::string ShellQuoteCommand(const std::vector<std::string>& argv);

/// The absolute path of `program` if it is an executable file in PATH (or a path to one),
/// else "".
std::string FindProgram(const std::string& program);

}  // namespace meshvid

#endif  // MESHVID_TOOLS_BENCH_CHILD_PROCESS_H_
