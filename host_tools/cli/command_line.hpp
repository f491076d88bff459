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
//   ... add options; give every number its range: ->check(CLI::Range(1, 100000)), or
//       ->check(curio::cli::kNonNegative) / kPositive (an unsigned option takes "-1" as
//       2^64 - 1 otherwise) ...
//   if (const auto code = curio::cli::parse(app, argc, argv)) return *code;  // not CLI11_PARSE
//   if (bad) return curio::cli::usage_error(*sub, "--episodes must be >= 1 (got 0)");
//
// Why not CLI11_PARSE: CLI11 exits with its own codes (104-114 for the different parse errors)
// and prints two lines; scripts that drive Curio test for 2.
//
// It lives in host_tools/cli/, the shared layer every program parses with (curio-sim's commands
// in sim/cli/ included): no program includes another program's folder (docs/architecture.md).
#pragma once
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "host_tools/cli/seed_text.hpp"

namespace curio::cli {

inline constexpr int kRuntimeFailure = 1;
inline constexpr int kUsageError = 2;

// A finite number >= 0, and one > 0 (CLI::NonNegativeNumber and CLI::PositiveNumber say so
// with the 300 digits of DBL_MAX, and let "inf" pass). Checked on the text, before CLI11
// converts it: an unsigned option would otherwise take "-1" as 2^64 - 1.
inline CLI::Validator number_check(bool zero_allowed) {
  return CLI::Validator(
      [zero_allowed](std::string& text) {
        double value = 0.0;
        const bool ok = CLI::detail::lexical_cast(text, value) && std::isfinite(value) &&
                        (zero_allowed ? value >= 0.0 : value > 0.0);
        return ok ? std::string()
                  : "'" + text + "' is not a finite number " + (zero_allowed ? ">= 0" : "> 0");
      },
      zero_allowed ? "NUMBER >= 0" : "NUMBER > 0");
}
inline const CLI::Validator kNonNegative = number_check(true);
inline const CLI::Validator kPositive = number_check(false);

// A seed (--seed, --test-seed): 0 to 2^64 - 1, digits only (host_tools/cli/seed_text.hpp).
// Checked on the text: CLI11 alone reads "-1" as 2^64 - 1 and clamps "18446744073709551616".
inline const CLI::Validator kSeed(
    [](std::string& text) {
      return parse_seed(text) ? std::string()
                              : "'" + text + "' is not a seed (a whole number 0 to 2^64 - 1)";
    },
    "SEED");

// An output folder (--out): not empty (an empty path once meant "the current folder" and
// printed "results in /"). Whether it can be written is found before the work starts
// (host_tools/common/output_folder.hpp), a runtime failure.
inline const CLI::Validator kOutputFolder(
    [](std::string& text) { return text.empty() ? std::string("an empty path") : std::string(); },
    "FOLDER");

// An output file: not empty, not an existing folder, not ending in '/' (the file is written
// beside itself as "<path>.tmp.*" and renamed, which a folder path would turn into litter).
inline const CLI::Validator kOutputFile(
    [](std::string& text) {
      if (text.empty()) return std::string("an empty path");
      std::error_code ec;
      if (text.back() == '/' || std::filesystem::is_directory(text, ec))
        return "'" + text + "' is a folder; name the file to write";
      return std::string();
    },
    "FILE");

// The name a message starts with: the root app's name without its folder ("curio-lab", also
// when CLI11 took it from argv[0]), whichever subcommand `app` is.
inline std::string program_name(const CLI::App& app) {
  const CLI::App* root = &app;
  while (root->get_parent() != nullptr) root = root->get_parent();
  std::string name = root->get_name();
  if (const auto slash = name.rfind('/'); slash != std::string::npos) name.erase(0, slash + 1);
  if (name.empty()) name = "curio";
  return name;
}

// "curio-lab run": the program and the subcommands down to `app`.
inline std::string command_name(const CLI::App& app) {
  if (app.get_parent() == nullptr) return program_name(app);
  return command_name(*app.get_parent()) + " " + app.get_name();
}

// The subcommand the command line selected, deepest first ("run" of "curio-lab run ..."); the
// app itself when none was.
inline const CLI::App& selected_command(const CLI::App& app) {
  const CLI::App* at = &app;
  while (!at->get_subcommands().empty()) at = at->get_subcommands().front();
  return *at;
}

// Prints "<program>: <message> (see <program> [sub] --help)" on stderr, on one line, and
// returns 2.
inline int usage_error(const CLI::App& app, std::string message) {
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::fprintf(stderr, "%s: %s (see %s --help)\n", program_name(app).c_str(), message.c_str(),
               command_name(app).c_str());
  return kUsageError;
}

// Options renamed so that one name has one meaning in every program (README, "Option | Meaning
// | Programs"). The old spelling is a usage error that names the new one. `command` is
// command_name()'s text; old "URL" stands for the bus URL curio-can took as a positional word.
struct RenamedOption {
  const char* command;
  const char* old_name;
  const char* new_name;
};
inline constexpr RenamedOption kRenamedOptions[] = {
    {"curio-sim render", "--out", "--png"},
    {"curio-sim render", "-o", "--png"},
    {"curio-quantize quantize", "--out", "--header"},
    {"curio-encode", "--model", "--weights"},
    {"curio-train train", "--model", "--kind"},
    {"curio-train report", "--model-dir", "--checkpoint"},
    {"curio-train export", "--model-dir", "--checkpoint"},
    {"curio-train unmix", "--from", "--checkpoint"},
    {"curio-can bench", "--window", "--in-flight"},
    {"curio-can bench", "-w", "--in-flight"},
    {"curio-can slcan-bridge", "--window", "--burst"},
    {"curio-can send", "URL", "--bus"},
    {"curio-can dump", "URL", "--bus"},
    {"curio-can echo", "URL", "--bus"},
    {"curio-can bench", "URL", "--bus"},
    {"curio-can mock-arm", "URL", "--bus"},
    {"curio-can episodes", "URL", "--bus"},
};

// "" or the line for an old spelling among `words` (what the parser did not take) of `command`.
inline std::string renamed_option_text(const std::string& command,
                                       const std::vector<std::string>& words) {
  for (const std::string& word : words) {
    const std::string name = word.substr(0, word.find('='));
    for (const RenamedOption& r : kRenamedOptions) {
      if (command != r.command) continue;
      if (std::string(r.old_name) == "URL" && !word.empty() && word[0] != '-')
        return "'" + word + "': the bus is named with " + r.new_name + " URL (" + r.new_name +
               " " + word + ")";
      if (name == r.old_name)
        return name + " is now " + r.new_name + " (one meaning per option name; README)";
    }
  }
  return "";
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
    const CLI::App& at = selected_command(app);
    // CLI11 says only "A subcommand is required" when the first word is not one: name it.
    const auto subcommands = app.get_subcommands([](const CLI::App*) { return true; });
    if (&at == &app && !subcommands.empty() && !app.remaining().empty()) {
      std::string names;
      for (const CLI::App* sub : subcommands)
        names += (names.empty() ? "" : ", ") + sub->get_name();
      const std::string word = app.remaining().front();
      return usage_error(
          app, (word.rfind('-', 0) == 0 ? "unknown option '" : "unknown subcommand '") + word +
                   "' (a subcommand comes first: " + names + ")");
    }
    // CLI11 checks required options before it looks for unknown ones: "evaluate --bogus"
    // would say "--model is required". The unknown option is the first mistake to name.
    const std::vector<std::string> extras = at.remaining();
    // An unknown option of a subcommand is handed back to its parent: look in both.
    std::vector<std::string> unparsed = extras;
    for (const std::string& w : app.remaining()) unparsed.push_back(w);
    if (const std::string renamed = renamed_option_text(command_name(at), unparsed);
        !renamed.empty())
      return usage_error(at, renamed);
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr && !extras.empty()) {
      return usage_error(at, "The following argument was not expected: " + extras.front());
    }
    return usage_error(at, e.what());
  }
  return std::nullopt;
}

}  // namespace curio::cli
