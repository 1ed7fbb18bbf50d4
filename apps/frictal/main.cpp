// frictal — command-line front end. Talks to the user; the library only returns results/errors.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>

#include <fmt/core.h>

#include "command.hpp"

namespace frictal::cli {

std::vector<CommandInfo>& command_registry() {
  static std::vector<CommandInfo> registry;
  return registry;
}

bool register_command(CommandInfo info) {
  command_registry().push_back(std::move(info));
  return true;
}

}  // namespace frictal::cli

int main(int argc, char** argv) {
  using namespace frictal::cli;
  CLI::App app{"frictal — static friction between rigid rough surfaces from their topography.\n"
               "Angles are in degrees and lengths in metres at this interface unless an option says otherwise."};
  app.set_version_flag("--version", "frictal 0.1.0");
  app.require_subcommand(1);
  auto& reg = command_registry();
  std::stable_sort(reg.begin(), reg.end(),
                   [](const CommandInfo& a, const CommandInfo& b) { return a.order < b.order; });
  std::vector<std::pair<CLI::App*, std::function<int()>>> runners;
  for (auto& info : reg) {
    CLI::App* sub = app.add_subcommand(info.name, info.description);
    runners.emplace_back(sub, info.setup(*sub));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "frictal: {}\nRun 'frictal --help' or 'frictal <command> --help' for usage.\n", e.what());
    return 2;
  }
  try {
    for (auto& [sub, run] : runners) {
      if (sub->parsed()) return run();
    }
  } catch (const UsageError& e) {
    fmt::print(stderr, "frictal: {}\n", e.what());
    return exit_code(e.code);
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "frictal: out of memory (input or parameters too large)\n");
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "frictal: internal error: {}\n", e.what());
    return 3;
  }
  return 2;
}
