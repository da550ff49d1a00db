// The last line of defence of the `meshvid` executable: an exception that escapes a command
// (a bug) is reported as an internal error with its own exit code instead of aborting.
#ifndef MESHVID_TOOLS_CLI_INTERNAL_ERROR_H_
#define MESHVID_TOOLS_CLI_INTERNAL_ERROR_H_

#include <cstdio>
#include <exception>

namespace meshvid::cli {

/// Exit code of a command that failed through an uncaught exception (see commands.h).
inline constexpr int kExitInternalError = 3;

/// Returns body(); if it throws, prints "meshvid: internal error: WHAT" on stderr (WHAT is
/// the exception's what(), or "unknown exception" for one not derived from std::exception)
/// and returns kExitInternalError.
template <typename Body>
int RunCatchingInternalErrors(Body&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshvid: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "meshvid: internal error: unknown exception\n");
  }
  std::fflush(stderr);
  return kExitInternalError;
}

}  // namespace meshvid::cli

#endif  // MESHVID_TOOLS_CLI_INTERNAL_ERROR_H_
