// One run's result as a file (CBOR: every float and double exactly, NaN included): what a
// campaign task leaves per run, and all the report needs to rebuild that run's share of
// summary.json, the CSVs and the plots in a merge. The spec is not stored: the merge takes it
// from the campaign (expand_runs) by the run's index; exploits are summarised in the verdicts.
// The fields are stored as CBOR bytes with their CRC-32 (firmware/journal/crc32.hpp) beside
// them: a record changed on disk, even to valid content, reads as damaged, never as a result.
#pragma once
#include <cstddef>
#include <optional>
#include <string>

#include "host_tools/experiment/run.hpp"

namespace curio::lab {

// Written to a temporary file and renamed, so a killed task leaves no half record.
bool write_run_record(const std::string& path, size_t index, const RunResult& result,
                      std::string* error);

// The record at `path` for run `index` of the campaign, whose spec is `spec`; nullopt with
// *error when the file is missing, unreadable, damaged (CRC), or names another run.
std::optional<RunResult> read_run_record(const std::string& path, size_t index, const RunSpec& spec,
                                         std::string* error);

}  // namespace curio::lab
