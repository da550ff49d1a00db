#include "tools/cli/terminal.h"

#include <unistd.h>

#include <cstdio>

namespace meshvid::cli {

int ReportError(const Status& status) {
  std::fprintf(stderr, "meshvid: %s\n", status.ToString().c_str());
  return 1;
}

std::string Count(std::size_t n, std::string_view noun, std::string_view plural) {
  std::string text = std::to_string(n) + " ";
  if (n == 1) return text.append(noun);
  return plural.empty() ? text.append(noun).append("s") : text.append(plural);
}

std::string Kilobytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f kB", bytes / 1000.0);
  return text;
}

ProgressBar::ProgressBar(bool quiet)
    : quiet_(quiet),
      tty_(isatty(STDERR_FILENO) != 0),
      last_draw_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { Finish(); }

ProgressCallback ProgressBar::Callback() {
  return [this](std::string_view stage, long done, long total) {
    Draw(stage, done, total);
    return true;
  };
}

void ProgressBar::Finish() {
  if (drawn_ && tty_) std::fputc('\n', stderr);
  drawn_ = false;
}

void ProgressBar::Message(std::string_view line) {
  if (quiet_) return;
  if (drawn_ && tty_) std::fputs("\r\033[K", stderr);
  drawn_ = false;
  std::fprintf(stderr, "%.*s\n", static_cast<int>(line.size()), line.data());
  if (tty_) last_draw_ = {};  // redraw the bar at the next update
  std::fflush(stderr);
}

void ProgressBar::Draw(std::string_view stage, long done, long total) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  if (stage != stage_) {
    Finish();
    stage_ = std::string(stage);
    stage_start_ = now;
    if (tty_) last_draw_ = {};
  }
  const bool last = total > 0 && done >= total;
  if (tty_) {
    // Redraw a terminal bar at most 10 times a second, and at the end of each stage.
    if (!last && now - last_draw_ < std::chrono::milliseconds(100)) return;
  } else {
    // A log gets one plain line every 5 seconds at most, whatever the stages do (an
    // encode's stages interleave and nest), and nothing for work shorter than that.
    if (now - last_draw_ < std::chrono::seconds(5)) return;
  }
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double fraction = total > 0 ? static_cast<double>(done) / total : 0.0;
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  const double eta = rate > 0 && total > done ? (total - done) / rate : 0.0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r%-12.*s [%s] %ld/%ld  %.1f/s  ETA %.0fs   ",
                 static_cast<int>(stage_.size()), stage_.data(), bar.c_str(), done, total, rate,
                 eta);
    drawn_ = true;
  } else {
    // No rate: stages interleave in a log's 5 s, so a rate since the stage began means little.
    std::fprintf(stderr, "%.*s: %ld/%ld\n", static_cast<int>(stage_.size()), stage_.data(), done,
                 total);
  }
  std::fflush(stderr);
}

}  // namespace meshvid::cli
