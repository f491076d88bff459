// libFuzzer target: the files the host tools read back, on arbitrary bytes and on valid files
// with damage. Oracles beyond "no crash, no UB":
//   - a curio-lab run record (host_tools/lab/run_record_format.hpp) that decodes re-encodes to
//     a record that decodes to the same arrays;
//   - a valid record with any one byte changed never decodes (its CRC, its structure or its
//     identity catches it): a damaged record is never read as a result;
//   - a bus history (bus_counters.json, host_tools/controller/bus_history.hpp) that loads has
//     fault kinds adding up to its total and at least one process; one that does not load
//     leaves the history empty.
#include <fuzzer/FuzzedDataProvider.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "host_tools/controller/bus_history.hpp"
#include "host_tools/lab/run_record_format.hpp"
#include "tests/fuzz/fuzz_check.hpp"

using namespace curio;

namespace {

const std::string kName = "MGE-EFR_sigma0.05_seed3";

void record_bytes(const std::vector<uint8_t>& bytes) {
  std::string error;
  const auto r = lab::decode_run_record(bytes, 3, kName, &error);
  if (!r) {
    check(!error.empty());
    return;
  }
  const auto again = lab::decode_run_record(lab::encode_run_record(3, kName, *r), 3, kName, &error);
  check(again.has_value());
  check(again->checkpoints == r->checkpoints && again->grasps == r->grasps &&
        again->final_ball.size() == r->final_ball.size() &&
        again->module_names == r->module_names && again->error == r->error);
}

void damaged_record(FuzzedDataProvider& in) {
  lab::RunResult r;
  const int n = in.ConsumeIntegralInRange<int>(0, 8);
  for (int i = 0; i < n; ++i) {
    r.checkpoints.push_back(in.ConsumeIntegral<int>());
    r.ratio.push_back(in.ConsumeFloatingPoint<double>());
    r.grasps.push_back(in.ConsumeIntegral<int>());
    r.final_ball.push_back({in.ConsumeFloatingPoint<float>(), in.ConsumeFloatingPoint<float>()});
  }
  r.module_names.push_back(in.ConsumeRandomLengthString(16));
  r.error = in.ConsumeRandomLengthString(16);
  std::vector<uint8_t> bytes = lab::encode_run_record(3, kName, r);
  std::string error;
  check(lab::decode_run_record(bytes, 3, kName, &error).has_value());
  const size_t at = in.ConsumeIntegralInRange<size_t>(0, bytes.size() - 1);
  const auto flip = in.ConsumeIntegralInRange<uint8_t>(1, 255);
  bytes[at] ^= flip;
  check(!lab::decode_run_record(bytes, 3, kName, &error).has_value());
}

void bus_history(const std::vector<uint8_t>& bytes) {
  static const std::string path = "/tmp/curio_fuzz_bus_history_" + std::to_string(getpid());
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  app::host::BusHistory h;
  std::string error;
  if (app::host::load_bus_history(path, &h, &error)) {
    uint64_t kinds = 0;
    for (const uint64_t f : h.faults) kinds += f;
    check(kinds == h.fault_total);
    check(h.processes >= 1);
  } else {
    check(h.fault_total == 0 && h.processes == 0 && !error.empty());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0:
      record_bytes(in.ConsumeRemainingBytes<uint8_t>());
      break;
    case 1:
      damaged_record(in);
      break;
    default:
      bus_history(in.ConsumeRemainingBytes<uint8_t>());
      break;
  }
  return 0;
}
