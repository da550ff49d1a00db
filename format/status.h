// Status and StatusOr<T>: how every meshvid library function reports failure.
// The libraries never print and never exit; tools turn a Status into text and an exit code.
#ifndef MESHVID_FORMAT_STATUS_H_
#define MESHVID_FORMAT_STATUS_H_

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace meshvid {

/// What kind of failure a Status reports.
enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  ///< the caller passed something unusable (option, range, pattern)
  kNotFound,         ///< a file or item does not exist
  kIoError,          ///< the OS failed to read or write
  kCorrupt,          ///< input data is malformed or truncated
  kUnsupported,      ///< valid input using a feature meshvid does not handle
  kCancelled,        ///< a progress callback asked to stop
  kInternal,         ///< a bug or a failure of a dependency
};

/// Short lower-case name of a code ("invalid argument", "corrupt", ...).
std::string_view StatusCodeName(StatusCode code);

/// The outcome of an operation: ok, or a code with a message a user can act on.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return Status(); }
  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  /// "corrupt: bunny.ply: truncated binary vertex data" style text.
  std::string ToString() const;
  /// Returns a copy whose message is prefixed with `context: `.
  Status WithContext(std::string_view context) const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status InvalidArgumentError(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status NotFoundError(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
inline Status IoError(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
inline Status CorruptError(std::string m) { return {StatusCode::kCorrupt, std::move(m)}; }
inline Status UnsupportedError(std::string m) { return {StatusCode::kUnsupported, std::move(m)}; }
inline Status CancelledError(std::string m) { return {StatusCode::kCancelled, std::move(m)}; }
inline Status InternalError(std::string m) { return {StatusCode::kInternal, std::move(m)}; }

/// A value of type T, or the Status explaining why there is none.
template <typename T>
class [[nodiscard]] StatusOr {
 public:
  StatusOr(const T& value) : value_(value) {}                 // NOLINT: implicit by design
  StatusOr(T&& value) : value_(std::move(value)) {}           // NOLINT
  StatusOr(Status status) : status_(std::move(status)) {      // NOLINT
    if (status_.ok()) status_ = InternalError("StatusOr constructed from an ok Status");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }
  const T& value() const& { return *value_; }
  T& value() & { return *value_; }
  T&& value() && { return std::move(*value_); }
  const T& operator*() const& { return *value_; }
  T& operator*() & { return *value_; }
  T&& operator*() && { return std::move(*value_); }
  const T* operator->() const { return &*value_; }
  T* operator->() { return &*value_; }

 private:
  Status status_;
  std::optional<T> value_;
};

}  // namespace meshvid

#define MESHVID_CONCAT_INNER_(a, b) a##b
#define MESHVID_CONCAT_(a, b) MESHVID_CONCAT_INNER_(a, b)

/// Returns the Status of `expr` from the enclosing function if it is not ok.
#define MESHVID_RETURN_IF_ERROR(expr)              \
  do {                                             \
    ::meshvid::Status meshvid_status_ = (expr);    \
    if (!meshvid_status_.ok()) return meshvid_status_; \
  } while (0)

/// `MESHVID_ASSIGN_OR_RETURN(auto x, F());` declares x from an ok StatusOr or returns its error.
#define MESHVID_ASSIGN_OR_RETURN(lhs, expr) \
  MESHVID_ASSIGN_OR_RETURN_IMPL_(MESHVID_CONCAT_(meshvid_statusor_, __LINE__), lhs, expr)
#define MESHVID_ASSIGN_OR_RETURN_IMPL_(tmp, lhs, expr) \
  auto tmp = (expr);                                   \
  if (!tmp.ok()) return tmp.status();                  \
  lhs = std::move(tmp).value()

#endif  // MESHVID_FORMAT_STATUS_H_
