#include "host_tools/common/gnuplot.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/wait.h>
#include <utility>
#include <vector>

#include "host_tools/common/atomic_file.hpp"

namespace curio::host {
namespace {

// The path of a line "set output '<quoted>'" (gnuplot_quote's quoting), or false.
bool output_path(const std::string& line, std::string* path) {
  static const std::string kPrefix = "set output '";
  if (line.compare(0, kPrefix.size(), kPrefix) != 0) return false;
  std::string out;
  for (size_t i = kPrefix.size(); i < line.size(); ++i) {
    if (line[i] != '\'') {
      out += line[i];
      continue;
    }
    if (i + 1 < line.size() && line[i + 1] == '\'') {
      out += '\'';
      ++i;
      continue;
    }
    if (line.find_first_not_of(" \t", i + 1) != std::string::npos) return false;
    *path = out;
    return true;
  }
  return false;
}

// gnuplot exits 0 when it cannot write its output (a full disk): a plot is taken only whole.
// "" when `tmp` is a whole plot for `path`, else why not. A PNG ends with its IEND chunk.
std::string incomplete_plot(const std::string& tmp, const std::string& path) {
  std::FILE* f = std::fopen(tmp.c_str(), "rb");
  if (!f) return "gnuplot wrote no " + path + " (" + std::strerror(errno) + ")";
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  unsigned char tail[12] = {};
  const bool png = path.size() > 4 && path.compare(path.size() - 4, 4, ".png") == 0;
  bool whole = size > 0;
  if (png && size >= 12) {
    std::fseek(f, size - 12, SEEK_SET);
    static const unsigned char kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    whole = std::fread(tail, 1, 12, f) == 12 && std::memcmp(tail, kIend, 12) == 0;
  } else if (png) {
    whole = false;
  }
  std::fclose(f);
  if (whole) return "";
  return "gnuplot left " + path + " incomplete (" + std::to_string(size) +
         " bytes, no PNG end; is the disk full?)";
}

}  // namespace

std::string gnuplot_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else
      out += c;
  }
  return out + "'";
}

bool run_gnuplot(const std::string& script_path, const std::string& script, std::string* error,
                 bool* not_installed) {
  if (not_installed) *not_installed = false;
  if (!write_file_atomically(script_path, script, error)) return false;
  // The script gnuplot runs: the same, its outputs redirected to temporary files.
  std::vector<std::pair<std::string, std::string>> outputs;  // (temporary, final)
  std::string run_script;
  size_t pos = 0;
  while (pos < script.size()) {
    size_t end = script.find('\n', pos);
    if (end == std::string::npos) end = script.size();
    const std::string line = script.substr(pos, end - pos);
    std::string path;
    if (output_path(line, &path)) {
      outputs.emplace_back(temp_path_for(path), path);
      run_script += "set output " + gnuplot_quote(outputs.back().first);
    } else {
      run_script += line;
    }
    if (end < script.size()) run_script += '\n';
    pos = end + 1;
  }
  const std::string run_path = temp_path_for(script_path);
  if (!write_file_atomically(run_path, run_script, error)) return false;
  // gnuplot closes its outputs when it exits, so the renames below see whole files.
  // The shell's quoting, not gnuplot's: an apostrophe in the path ("bob's runs") is '\''.
  std::string quoted = "'";
  for (char c : run_path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const std::string cmd = "gnuplot " + quoted + "' 2>&1";
  std::string output;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    remove_temp(run_path);
    *error = "cannot start gnuplot (" + std::string(std::strerror(errno)) + ")";
    return false;
  }
  char buf[512];
  while (fgets(buf, sizeof buf, p)) output += buf;
  const int rc = pclose(p);
  remove_temp(run_path);
  if (WIFEXITED(rc) && WEXITSTATUS(rc) == 127) {  // the shell found no gnuplot
    for (const auto& o : outputs) remove_temp(o.first);
    if (not_installed) *not_installed = true;
    *error = "no plot " + script_path + ": gnuplot is not installed (install gnuplot-nox)";
    return false;
  }
  if (rc != 0) {
    for (const auto& o : outputs) remove_temp(o.first);
    for (size_t at = output.find(run_path); at != std::string::npos;  // name the kept script
         at = output.find(run_path, at + script_path.size()))
      output.replace(at, run_path.size(), script_path);
    *error = "gnuplot failed on " + script_path + (output.empty() ? "" : ": " + output);
    return false;
  }
  for (const auto& [tmp, path] : outputs) {
    if (const std::string why = incomplete_plot(tmp, path); !why.empty()) {
      for (const auto& o : outputs) remove_temp(o.first);
      *error = "cannot write " + path + ": " + why;
      return false;
    }
  }
  for (const auto& [tmp, path] : outputs)
    if (!commit_temp(tmp, path, error)) return false;
  return true;
}

}  // namespace curio::host
