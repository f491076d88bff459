#include "host_tools/common/gnuplot.hpp"

#include <cstdlib>
#include <fstream>

namespace curio::host {

std::string gnuplot_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "''";
    else out += c;
  }
  return out + "'";
}

bool run_gnuplot(const std::string& script_path, const std::string& script, std::string* error) {
  {
    std::ofstream f(script_path);
    if (!f) {
      *error = "cannot write " + script_path;
      return false;
    }
    f << script;
  }
  const std::string cmd = "gnuplot " + gnuplot_quote(script_path) + " 2>&1";
  std::string output;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    *error = "cannot start gnuplot (install gnuplot-nox)";
    return false;
  }
  char buf[512];
  while (fgets(buf, sizeof buf, p)) output += buf;
  const int rc = pclose(p);
  if (rc != 0) {
    *error = "gnuplot failed on " + script_path + (output.empty() ? "" : ": " + output);
    return false;
  }
  return true;
}

}  // namespace curio::host
