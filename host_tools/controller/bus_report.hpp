// What curio-controller tells about a finished run over the bus: the line of rates and faults
// (print_bus_run), and the result files (write_bus_report): curio-lab's files for a campaign of
// this one run (host_tools/experiment/report.hpp), plus what the bus did to it, in
// summary.json "bus" (faults, replays, capture retries, node reboots over every process of the
// run, and whether the results are those of an undisturbed run) and a note in summary.md.
#pragma once
#include "host_tools/controller/bus_run_types.hpp"
#include "host_tools/controller/wall_clock_pacer.hpp"
#include "host_tools/experiment/campaign_config.hpp"

namespace curio::app::host {

// One line on stderr: episodes (replayed from the journal among them), wall time, rates and
// frames per episode of this process, the faults.
void print_bus_run(const BusRunResult& result);

// Writes the result files into campaign.out_dir and prints the ratio, where the files are, the
// bus note when the bus misbehaved, and the controllable-feature verdict. Returns the exit
// status: 0; 1 when a file cannot be written; 3 when written but marked (a fault may have
// changed the results).
// `periods` (optional): the wall-clock control periods' figures (summary.json
// "control_periods", control_periods.csv / .png).
int write_bus_report(lab::CampaignConfig campaign, const BusRunResult& result,
                     const WallClockPacer* periods = nullptr, const RealtimeSettings& realtime = {});

}  // namespace curio::app::host
