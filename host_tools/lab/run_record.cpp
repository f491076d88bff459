#include "host_tools/lab/run_record.hpp"

#include <fstream>
#include <iterator>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/experiment/report.hpp"
#include "host_tools/lab/run_record_format.hpp"

namespace curio::lab {

bool write_run_record(const std::string& path, size_t index, const RunResult& r,
                      std::string* error) {
  const std::vector<uint8_t> bytes = encode_run_record(index, run_stem(r.spec), r);
  return host::write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), error);
}

std::optional<RunResult> read_run_record(const std::string& path, size_t index, const RunSpec& spec,
                                         std::string* error) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    *error = "no record " + path;
    return std::nullopt;
  }
  const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(f),
                                   std::istreambuf_iterator<char>()};
  std::string why;
  auto r = decode_run_record(bytes, index, run_stem(spec), &why);
  if (!r) {
    *error = path + (why.rfind("holds", 0) == 0 ? " " : " is ") + why;
    return std::nullopt;
  }
  r->spec = spec;
  return r;
}

}  // namespace curio::lab
