// PNG plots through gnuplot (pngcairo terminal): the script is written beside the
// plot so a user can tweak and re-run it.
#pragma once
#include <string>

namespace curio::host {

// Writes `script` to `script_path` and runs gnuplot on it. Returns false with a message
// (gnuplot missing, script error) in *error.
// Atomic (atomic_file.hpp): the script is written by write_file_atomically, and every
// `set output '<path>'` line (quoted as gnuplot_quote does) is run with a temporary path
// beside <path>, renamed to <path> once gnuplot has succeeded; a kill leaves the old plot or
// the new one, and a failed run leaves the old one. The saved script names the real path.
// A plot gnuplot could not finish (it exits 0 on a full disk) is refused, not renamed: every
// output must exist, be non-empty and, for a PNG, end with its IEND chunk.
// *not_installed (optional) tells the one failure a caller may take as a warning: no gnuplot
// on this machine (its plots are then missing, and its data and scripts still written).
bool run_gnuplot(const std::string& script_path, const std::string& script, std::string* error,
                 bool* not_installed = nullptr);

// Quotes a path for a gnuplot string literal.
std::string gnuplot_quote(const std::string& s);

}  // namespace curio::host
