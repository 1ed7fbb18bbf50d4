// frictal CLI — subcommand registry. Each subcommand lives in its own file and registers itself
// with a static FRICTAL_COMMAND(...) so that adding one touches no other file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "frictal/result.hpp"

namespace frictal::cli {

/// An error for the user: printed as "frictal: <message>"; main() turns its code into the exit
/// status through exit_code() (errors of the command line itself are invalid input: exit 2).
struct UsageError : std::runtime_error {
  explicit UsageError(const std::string& message, ErrorCode error_code = ErrorCode::InvalidInput)
      : std::runtime_error(message), code(error_code) {}
  ErrorCode code;
};

/// Throws a library error as a UsageError with its message and code (exit status from exit_code).
[[noreturn]] inline void fail(const Error& e) { throw UsageError(e.message, e.code); }

/// The CLI's one table from error codes to exit statuses (docs/ARCHITECTURE.md, "Errors"):
/// invalid input, I/O and not-available errors exit 2, an unstable simulation 1, internal 3.
inline int exit_code(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidInput: return 2;
    case ErrorCode::Io: return 2;
    case ErrorCode::NotAvailable: return 2;
    case ErrorCode::Unstable: return 1;
    case ErrorCode::Internal: return 3;
  }
  return 3;
}

/// Sets up a subcommand on the app; the returned callback runs it and returns the exit code.
using CommandSetup = std::function<std::function<int()>(CLI::App&)>;

struct CommandInfo {
  std::string name;
  std::string description;
  CommandSetup setup;
  int order = 100;  ///< position in --help
};

std::vector<CommandInfo>& command_registry();
bool register_command(CommandInfo info);

}  // namespace frictal::cli

#define FRICTAL_CONCAT2(a, b) a##b
#define FRICTAL_CONCAT(a, b) FRICTAL_CONCAT2(a, b)
#define FRICTAL_COMMAND(...)                                        \
  static const bool FRICTAL_CONCAT(frictal_registered_, __LINE__) = \
      ::frictal::cli::register_command(::frictal::cli::CommandInfo __VA_ARGS__)
