// frictal — error handling without exceptions in the numerics.
//
// Library functions that can fail on user data return Result<T>: either a value or an Error
// whose message names what was wrong (parameter, file, line) and what was expected. The
// library never prints or exits; front ends decide how to report.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace frictal {

/// What kind of failure an Error is. Callers decide on the code, never on the message text
/// (e.g. a study task retries an Unstable run with a smaller step; the CLI maps codes to exit
/// codes in one table, docs/ARCHITECTURE.md).
enum class ErrorCode {
  InvalidInput,  ///< bad parameter, file content or option: the caller must change the input
  Io,            ///< a file could not be opened, read or written (operating system)
  Unstable,      ///< a simulation stopped by its stability guard (a smaller time step may pass)
  NotAvailable,  ///< a feature (task kind, engine, MPI) that this build does not have
  Internal,      ///< a failure that is no fault of the input (out of memory, a lost worker, a bug)
};

/// Lower-case name of a code ("invalid input", "io", "unstable", "not available", "internal").
inline const char* to_string(ErrorCode c) {
  switch (c) {
    case ErrorCode::InvalidInput: return "invalid input";
    case ErrorCode::Io: return "io";
    case ErrorCode::Unstable: return "unstable";
    case ErrorCode::NotAvailable: return "not available";
    case ErrorCode::Internal: return "internal";
  }
  return "internal";
}

struct Error {
  std::string message;
  ErrorCode code = ErrorCode::InvalidInput;
};

/// A warning as a result: a number computed without an error that a reader should not trust as
/// it stands. `code` is one of warning_codes() (warnings.hpp), on which decisions are taken; the
/// message names the file or quantity and the number that triggered it. Every result that
/// carries warnings carries this type.
struct Warning {
  std::string code;
  std::string message;

  Warning() = default;
  /// Constructor rather than aggregate: `emplace_back(code, message)` needs it on compilers
  /// without C++20's parenthesized aggregate initialization (clang 14, the fuzz build).
  Warning(std::string c, std::string m) : code(std::move(c)), message(std::move(m)) {}
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : v_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

/// Result of an operation that returns nothing but can fail.
struct Ok {};
using Status = Result<Ok>;

/// An error with a message naming what was wrong and what was expected; the code defaults to
/// invalid input.
inline Error make_error(std::string message, ErrorCode code = ErrorCode::InvalidInput) {
  return Error{std::move(message), code};
}
inline Error make_error(ErrorCode code, std::string message) { return Error{std::move(message), code}; }
/// The same error with context in front of its message (the code is kept).
inline Error with_prefix(const std::string& prefix, const Error& e) { return Error{prefix + e.message, e.code}; }

}  // namespace frictal
