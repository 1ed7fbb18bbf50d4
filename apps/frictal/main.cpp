// frictal — command-line front end. Talks to the user; the library only returns results/errors.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "command.hpp"
#include "common.hpp"
#include "frictal/settings.hpp"
#include "frictal/version.hpp"

namespace frictal::cli {

std::vector<CommandInfo>& command_registry() {
  static std::vector<CommandInfo> registry;
  return registry;
}

bool register_command(CommandInfo info) {
  command_registry().push_back(std::move(info));
  return true;
}

namespace {

CLI::App* find_sub(CLI::App* app, const std::string& name) {
  for (CLI::App* s : app->get_subcommands([](CLI::App*) { return true; }))
    if (s->get_name() == name) return s;
  return nullptr;
}

std::string path_of(const std::vector<CLI::App*>& chain) {
  std::string s = "frictal";
  for (std::size_t i = 1; i < chain.size(); ++i) s += " " + chain[i]->get_name();
  return s;
}

bool is_number(const std::string& a) {
  char* end = nullptr;
  std::strtod(a.c_str(), &end);
  return end && *end == '\0' && end != a.c_str();
}

/// Before CLI11 parses: finds the first word that names no command, subcommand or option and
/// says so, with the nearest known word ("unknown command 'stat'; did you mean 'stats'?").
/// Returns "" when every word is known (CLI11 then reports anything else).
std::string diagnose(CLI::App& app, int argc, char** argv) {
  std::vector<CLI::App*> chain{&app};
  std::size_t positionals_used = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    CLI::App* cur = chain.back();
    if (a == "--") break;
    if (a.size() > 1 && a[0] == '-' && !is_number(a)) {
      const std::string name = a.substr(0, a.find('='));
      const CLI::Option* found = nullptr;
      std::vector<std::string> known;
      // Options of the command and, through fallthrough, of its parents.
      for (std::size_t k = chain.size(); k-- > 0;) {
        for (const CLI::Option* o : chain[k]->get_options()) {
          for (const std::string& l : o->get_lnames()) {
            known.push_back("--" + l);
            if (name == "--" + l && !found) found = o;
          }
          for (const std::string& sn : o->get_snames()) {
            known.push_back("-" + sn);
            if (name.size() >= 2 && name[1] != '-' && name.substr(0, 2) == "-" + sn && !found) found = o;
          }
        }
        if (!chain[k]->get_fallthrough()) break;
      }
      if (!found) {
        std::string msg = fmt::format("unknown option '{}' for '{}'", name, path_of(chain));
        if (std::string n = frictal::nearest_word(name, known); !n.empty())
          msg += fmt::format("; did you mean '{}'?", n);
        return msg + fmt::format("\nRun '{} --help' for its options.", path_of(chain));
      }
      const bool short_with_value = name.size() > 2 && name[1] != '-';
      const int items = found->get_items_expected_max();  // 0 for flags
      if (a.find('=') == std::string::npos && !short_with_value && items > 0) i += items < 100 ? items : 1;
      continue;
    }
    if (CLI::App* sub = find_sub(cur, a)) {
      chain.push_back(sub);
      positionals_used = 0;
      continue;
    }
    // A word: a positional argument if the command takes one more, else unknown.
    std::size_t positionals = 0;
    for (const CLI::Option* o : cur->get_options()) positionals += o->get_positional() ? 1 : 0;
    if (positionals_used < positionals) {
      ++positionals_used;
      continue;
    }
    std::vector<std::string> names;
    for (CLI::App* s : cur->get_subcommands([](CLI::App*) { return true; })) names.push_back(s->get_name());
    if (names.empty()) return "";  // CLI11 reports the extra argument
    const bool top = chain.size() == 1;
    // A file where a command takes its surfaces by option (`frictal tilt FILE`): name the option.
    std::error_code ec;
    if (!top && std::filesystem::is_regular_file(a, ec)) {
      for (const CLI::Option* o : cur->get_options())
        if (o->check_lname("lower"))
          return fmt::format(
              "'{}' is a file, and '{}' takes its surfaces by option: --lower {} [--upper FILE] (or a generator: {})",
              a, path_of(chain), a, [&] {
                std::string l;
                for (const std::string& n : names) l += (l.empty() ? "" : ", ") + n;
                return l;
              }());
    }
    std::string msg =
        fmt::format("unknown {} '{}'{}", top ? "command" : "subcommand", a, top ? "" : " for '" + path_of(chain) + "'");
    if (std::string n = frictal::nearest_word(a, names); !n.empty()) msg += fmt::format("; did you mean '{}'?", n);
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    return msg + fmt::format("\n{}: {}", top ? "Commands" : "Expected one of", list);
  }
  // A command that needs a subcommand (a generator, a study action) and got none.
  CLI::App* last = chain.back();
  bool help = false;
  for (int i = 1; i < argc; ++i)
    help = help || std::string(argv[i]).rfind("--help", 0) == 0 || std::string(argv[i]) == "-h" ||
           std::string(argv[i]) == "--version";
  if (!help && last->get_require_subcommand_min() > 0) {
    std::string list;
    for (CLI::App* s : last->get_subcommands([](CLI::App*) { return true; }))
      list += (list.empty() ? "" : ", ") + s->get_name();
    return fmt::format("'{}' needs a {}: {}", path_of(chain), chain.size() == 1 ? "command" : "subcommand", list);
  }
  return "";
}

}  // namespace

}  // namespace frictal::cli

int main(int argc, char** argv) {
  using namespace frictal::cli;
  CLI::App app{
      "frictal — static friction between rigid rough surfaces from their topography.\n"
      "Angles are in degrees and lengths in metres at this interface unless an option says otherwise."};
  app.set_version_flag("--version", frictal::version_line());
  app.require_subcommand(1);
  auto& reg = command_registry();
  std::stable_sort(reg.begin(), reg.end(),
                   [](const CommandInfo& a, const CommandInfo& b) { return a.order < b.order; });
  std::vector<std::pair<CLI::App*, std::function<int()>>> runners;
  for (auto& info : reg) {
    CLI::App* sub = app.add_subcommand(info.name, info.description);
    runners.emplace_back(sub, info.setup(*sub));
  }
  if (std::string problem = diagnose(app, argc, argv); !problem.empty()) {
    fmt::print(stderr, "frictal: {}\n", problem);
    return 2;
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
    fmt::print(stderr, "frictal: {}\n", stdin_name(e.what()));
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
