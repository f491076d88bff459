// One command-line convention for Curio's programs (README, "Command-line convention").
//
// Exit codes:
//   0    success, and --help
//   1    a runtime failure (a file that cannot be written, a bus that does not answer, ...)
//   2    a usage error: unknown option, missing or malformed value, number out of range,
//        options that contradict each other. One line on stderr names the option and ends
//        with a --help hint; nothing has been written.
//   130  interrupted by SIGINT (Ctrl-C), 143 by SIGTERM (128 + the signal)
//
// API:
//   CLI::App app{"curio-x: ..."};
//   ... add options ...
//   if (const auto code = curio::cli::parse(app, argc, argv)) return *code;   // replaces CLI11_PARSE
//   if (bad) return curio::cli::usage_error(app, "--episodes must be >= 1 (got 0)");
//
// Why not CLI11_PARSE: CLI11 exits with its own codes (104-114 for the different parse errors)
// and prints two lines; scripts that drive Curio test for 2.
#pragma once
#include <cstdio>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace curio::cli {

inline constexpr int kRuntimeFailure = 1;
inline constexpr int kUsageError = 2;

// The name a message starts with: the root app's name ("curio-lab"), whichever subcommand
// `app` is.
inline std::string program_name(const CLI::App& app) {
  const CLI::App* root = &app;
  while (root->get_parent() != nullptr) root = root->get_parent();
  std::string name = root->get_name();
  if (name.empty()) name = "curio";
  return name;
}

// Prints "<program>: <message> (see <program> [sub] --help)" on stderr and returns 2.
inline int usage_error(const CLI::App& app, const std::string& message) {
  std::string help = program_name(app);
  if (app.get_parent() != nullptr) help += " " + app.get_name();
  std::fprintf(stderr, "%s: %s (see %s --help)\n", program_name(app).c_str(), message.c_str(),
               help.c_str());
  return kUsageError;
}

// Parses the command line. std::nullopt: go on. Otherwise the exit code to return now: 0 after
// printing --help, 2 after a one-line usage error.
inline std::optional<int> parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e.what());
  }
  return std::nullopt;
}

}  // namespace curio::cli
