// The bytes of a curio-lab run record (run_record.hpp writes and reads them as files): a CBOR
// map {format, version 2, crc32, body}, the body the run's fields as CBOR and crc32 its CRC-32
// (firmware/journal/crc32.hpp). Apart from the files so that a fuzzer (tests/fuzz) can feed it
// any bytes: decoding never throws and never trusts a field it has not checked.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "host_tools/experiment/run.hpp"

namespace curio::lab {

// The record of run `index`, named `name` (run_stem of its spec), holding `r`'s results.
std::vector<uint8_t> encode_run_record(size_t index, const std::string& name, const RunResult& r);

// The results in `bytes` if they are a whole, undamaged record of run `index` named `name`;
// nullopt with *error ("damaged (CRC mismatch)", "holds run 3 ...", "inconsistent ...")
// otherwise. The result's spec is left default: the caller knows it.
std::optional<RunResult> decode_run_record(const std::vector<uint8_t>& bytes, size_t index,
                                           const std::string& name, std::string* error);

}  // namespace curio::lab
