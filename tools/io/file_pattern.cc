// File patterns with {frame} / {view} placeholders and frame ranges.
#include "tools/io/file_pattern.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <limits>
#include <system_error>

namespace meshvid {
namespace {

namespace fs = std::filesystem;

/// One piece of a pattern's file name: literal text, or a placeholder.
struct PatternPiece {
  enum Kind { kLiteral, kFrame, kView } kind = kLiteral;
  std::string literal;
  int width = 0;  ///< placeholder's zero-padded width, 0 = none
};

/// Splits a pattern into its directory (may be empty) and file name parts.
std::pair<std::string, std::string> SplitDirectory(const std::string& pattern) {
  const std::size_t slash = pattern.find_last_of('/');
  if (slash == std::string::npos) return {"", pattern};
  return {pattern.substr(0, slash), pattern.substr(slash + 1)};
}

/// Parses the pieces of `name`; `pattern` is the whole pattern, for messages.
StatusOr<std::vector<PatternPiece>> ParsePieces(const std::string& name,
                                                const std::string& pattern) {
  std::vector<PatternPiece> pieces;
  std::size_t i = 0;
  while (i < name.size()) {
    if (name[i] == '}') {
      return InvalidArgumentError("pattern '" + pattern + "': '}' without a matching '{'");
    }
    if (name[i] != '{') {
      if (pieces.empty() || pieces.back().kind != PatternPiece::kLiteral) pieces.emplace_back();
      pieces.back().literal += name[i++];
      continue;
    }
    const std::size_t close = name.find('}', i);
    if (close == std::string::npos) {
      return InvalidArgumentError("pattern '" + pattern + "': '{' without a closing '}'");
    }
    const std::string body = name.substr(i + 1, close - i - 1);
    const std::size_t colon = body.find(':');
    const std::string key = body.substr(0, colon);
    PatternPiece piece;
    if (key == "frame") {
      piece.kind = PatternPiece::kFrame;
    } else if (key == "view") {
      piece.kind = PatternPiece::kView;
    } else {
      return InvalidArgumentError("pattern '" + pattern + "': unknown placeholder '{" + body +
                                  "}' (expected {frame}, {view}, or a width like {frame:04})");
    }
    if (colon != std::string::npos) {
      const std::string spec = body.substr(colon + 1);
      int width = 0;
      const bool digits_only =
          spec.size() >= 2 && spec.find_first_not_of("0123456789") == std::string::npos;
      if (digits_only) {
        std::from_chars(spec.data() + 1, spec.data() + spec.size(), width);
      }
      if (!digits_only || spec[0] != '0' || width < 1 || width > 18) {
        return InvalidArgumentError("pattern '" + pattern + "': bad width in '{" + body +
                                    "}' (write a zero-padded width like {" + key + ":04})");
      }
      piece.width = width;
    }
    for (const PatternPiece& other : pieces) {
      if (other.kind == piece.kind) {
        return InvalidArgumentError("pattern '" + pattern + "': {" + key +
                                    "} appears more than once");
      }
    }
    pieces.push_back(piece);
    i = close + 1;
  }
  return pieces;
}

/// Formats `number` zero-padded to `width` digits.
std::string Pad(int number, int width) {
  std::string digits = std::to_string(number);
  if (static_cast<int>(digits.size()) < width) {
    digits.insert(0, static_cast<std::size_t>(width) - digits.size(), '0');
  }
  return digits;
}

/// Parses a non-negative decimal integer that is the whole of `text`.
bool ParseNonNegative(std::string_view text, int* value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string_view::npos) {
    return false;
  }
  const auto result = std::from_chars(text.data(), text.data() + text.size(), *value);
  return result.ec == std::errc() && result.ptr == text.data() + text.size();
}

/// Matches `name` against `pieces` from piece `k` and character `pos` on, recording the
/// placeholder numbers. Backtracks over the digit count of unpadded placeholders.
bool MatchFrom(const std::vector<PatternPiece>& pieces, std::size_t k, const std::string& name,
               std::size_t pos, int* frame, int* view) {
  if (k == pieces.size()) return pos == name.size();
  const PatternPiece& piece = pieces[k];
  if (piece.kind == PatternPiece::kLiteral) {
    if (name.compare(pos, piece.literal.size(), piece.literal) != 0) return false;
    return MatchFrom(pieces, k + 1, name, pos + piece.literal.size(), frame, view);
  }
  std::size_t end = pos;
  while (end < name.size() && name[end] >= '0' && name[end] <= '9') ++end;
  for (std::size_t len = end - pos; len >= 1; --len) {
    const std::string_view digits(name.data() + pos, len);
    // With a width: exactly that many digits, or more only when the number needs them.
    if (piece.width > 0) {
      const bool exact = static_cast<int>(len) == piece.width;
      const bool wider = static_cast<int>(len) > piece.width && digits[0] != '0';
      if (!exact && !wider) continue;
    }
    int number = 0;
    if (!ParseNonNegative(digits, &number)) continue;
    int* slot = piece.kind == PatternPiece::kFrame ? frame : view;
    *slot = number;
    if (MatchFrom(pieces, k + 1, name, pos + len, frame, view)) return true;
  }
  return false;
}

}  // namespace

StatusOr<FilePattern> FilePattern::Parse(const std::string& pattern) {
  const auto [directory, name] = SplitDirectory(pattern);
  if (directory.find('{') != std::string::npos || directory.find('}') != std::string::npos) {
    return InvalidArgumentError("pattern '" + pattern +
                                "': placeholders may only appear in the file name, not in "
                                "the directory '" +
                                directory + "'");
  }
  if (name.empty()) {
    return InvalidArgumentError("pattern '" + pattern + "' has no file name");
  }
  MESHVID_ASSIGN_OR_RETURN(std::vector<PatternPiece> pieces, ParsePieces(name, pattern));
  FilePattern result;
  result.pattern_ = pattern;
  for (const PatternPiece& piece : pieces) {
    if (piece.kind == PatternPiece::kFrame) result.frame_width_ = piece.width;
    if (piece.kind == PatternPiece::kView) result.view_width_ = piece.width;
  }
  return result;
}

bool FilePattern::LooksLikePattern(const std::string& text) {
  for (const char* key : {"{frame}", "{frame:", "{view}", "{view:"}) {
    if (text.find(key) != std::string::npos) return true;
  }
  return false;
}

std::string FilePattern::Expand(int frame, int view) const {
  const auto [directory, name] = SplitDirectory(pattern_);
  // Parse() already accepted the pattern, so this cannot fail.
  const StatusOr<std::vector<PatternPiece>> pieces = ParsePieces(name, pattern_);
  std::string result = directory.empty() && pattern_.find('/') == std::string::npos
                           ? std::string()
                           : directory + "/";
  for (const PatternPiece& piece : *pieces) {
    switch (piece.kind) {
      case PatternPiece::kLiteral:
        result += piece.literal;
        break;
      case PatternPiece::kFrame:
        result += Pad(frame, piece.width);
        break;
      case PatternPiece::kView:
        result += Pad(view, piece.width);
        break;
    }
  }
  return result;
}

StatusOr<std::map<std::pair<int, int>, std::string>> FilePattern::Scan() const {
  const auto [directory, name] = SplitDirectory(pattern_);
  const bool has_directory = pattern_.find('/') != std::string::npos;
  const fs::path folder =
      has_directory ? fs::path(directory.empty() ? "/" : directory) : fs::path(".");
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    return NotFoundError("pattern '" + pattern_ + "': folder '" + folder.string() +
                         "' does not exist");
  }
  MESHVID_ASSIGN_OR_RETURN(std::vector<PatternPiece> pieces, ParsePieces(name, pattern_));
  std::map<std::pair<int, int>, std::string> found;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    if (!it->is_regular_file(error)) continue;
    const std::string file = it->path().filename().string();
    int frame = 0;
    int view = 0;
    if (!MatchFrom(pieces, 0, file, 0, &frame, &view)) continue;
    const std::string path = has_directory ? directory + "/" + file : file;
    const auto [slot, inserted] = found.emplace(std::make_pair(frame, view), path);
    if (!inserted) {
      return InvalidArgumentError("pattern '" + pattern_ + "': files '" + slot->second + "' and '" +
                                  path + "' both match frame " + std::to_string(frame) + ", view " +
                                  std::to_string(view));
    }
  }
  if (error) {
    return IoError("pattern '" + pattern_ + "': cannot list folder '" + folder.string() +
                   "': " + error.message());
  }
  return found;
}

StatusOr<std::pair<int, int>> ParseFrameRange(const std::string& text, int frame_count,
                                              std::string* clipped) {
  if (clipped != nullptr) clipped->clear();
  const auto malformed = [&]() {
    return InvalidArgumentError("frame range '" + text +
                                "' is malformed: expected A:B (frames A..B-1), A:, :B or N, "
                                "with non-negative integers");
  };
  int first = 0;
  int last = frame_count;
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) {
    if (!ParseNonNegative(text, &first)) return malformed();
    if (first == std::numeric_limits<int>::max()) return malformed();
    last = first + 1;
  } else {
    const std::string_view left(text.data(), colon);
    const std::string_view right(text.data() + colon + 1, text.size() - colon - 1);
    if (!left.empty() && !ParseNonNegative(left, &first)) return malformed();
    if (!right.empty() && !ParseNonNegative(right, &last)) return malformed();
  }
  const int clamped_first = std::min(first, frame_count);
  const int clamped_last = std::min(last, frame_count);
  if (clamped_first >= clamped_last) {
    return InvalidArgumentError("frame range '" + text + "' selects no frame of the " +
                                std::to_string(frame_count) + " frames (0.." +
                                std::to_string(frame_count - 1) + ")");
  }
  if (clipped != nullptr && last > frame_count) {
    *clipped = "frame range '" + text + "' runs past the last of the " +
               std::to_string(frame_count) + " frames: using " + std::to_string(clamped_first) +
               ":" + std::to_string(clamped_last);
  }
  return std::make_pair(clamped_first, clamped_last);
}

}  // namespace meshvid
