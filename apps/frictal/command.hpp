// frictal CLI — subcommand registry. Each subcommand lives in its own file and registers itself
// with a static FRICTAL_COMMAND(...) so that adding one touches no other file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace frictal::cli {

/// A user-facing error: printed as "frictal: <message>" and exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

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
#define FRICTAL_COMMAND(...) \
  static const bool FRICTAL_CONCAT(frictal_registered_, __LINE__) = \
      ::frictal::cli::register_command(::frictal::cli::CommandInfo __VA_ARGS__)
