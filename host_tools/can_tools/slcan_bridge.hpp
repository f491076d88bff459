// curio-can slcan-bridge: joins an SLCAN byte stream (QEMU's UART chardev socket, a pty, an
// inherited descriptor) to any Curio bus URL, both ways, frame for frame (docs/can.md, "SLCAN").
//   serial → bus: lines are assembled (firmware/protocol/slcan), frames sent on the bus
//   bus → serial: frames become lines, queued in memory and written as the line takes them
// Nothing is dropped by the bridge: the bus side is drained at once into an unbounded queue
// (the UDP bus would drop datagrams if its socket buffer filled), and the serial side is
// written as fast as it accepts, or paced (`--max-fps`, a token bucket of lines with a burst
// of `--burst`) for a consumer without flow control, such as UML's serial line.
#pragma once
#include <cstdint>
#include <string>

#include "firmware/protocol/slcan.hpp"

namespace curio::hal::tools {

struct SlcanBridgeOptions {
  std::string serial;  // unix:PATH (connect), pty (open one, print its path), fd:N
  std::string bus;     // any bus URL (hal/linux/open_bus.hpp)
  protocol::SlcanMode mode = protocol::SlcanMode::kClassic;
  double max_fps = 0.0;           // serial-side pacing, lines per second (0 = as fast as taken)
  unsigned burst = 32;            // burst of the pacing bucket, lines (--burst)
  double connect_timeout_s = 10;  // unix:PATH: keep trying this long (the peer may start later)
  double stats_every_s = 0;       // --status-every (0: statistics only at the end)
};

// Runs until the serial side closes (exit 0), a signal (SIGINT/SIGTERM: exit 130/143) or an
// error (exit 1); prints the link's statistics to stderr at the end.
int run_slcan_bridge(const SlcanBridgeOptions& options);

}  // namespace curio::hal::tools
