// The bus budget of Curio's arm protocol: how many frames, and how many bits on the wire in
// the worst case, one control period and one episode take in each profile (FD, classic), and
// whether they fit the 10 ms period and the episode's 50 periods at a given bitrate
// (`curio-can budget`, docs/can.md "Bus budget").
//
// The frames are made by the protocol's own encoders (arm_messages.hpp, canopen.hpp, the
// camera's ISO-TP sender), so the budget follows the code. Worst-case frame lengths count the
// stuff bits the worst payload can force:
//   classic (ISO 11898-1): g + 8n + 13 + ⌊(g + 8n − 1)/4⌋ bits, g = 34 (11-bit id) or 54
//     (29-bit), the bound of Davis, Burns, Bril & Lukkien (2007); an 8-byte 11-bit frame is
//     135 bits, a 0-byte one 55;
//   CAN FD: the arbitration phase (SOF to BRS: 17 bits, 36 with a 29-bit id) and the end (CRC
//     delimiter, ACK, ACK delimiter, EOF, intermission: 13 bits) at the nominal bitrate; ESI,
//     DLC, data, stuff count (4) and CRC (17 bits up to 16 data bytes, else 21) with its fixed
//     stuff bits (6 or 7) at the data bitrate when the frame switches (BRS), else nominal;
//     dynamic stuff bits bounded by ⌊(a − 1)/4⌋ in the a arbitration bits and ⌈d/4⌉ in the d
//     data-phase bits before the stuff count (together at least the ⌊(a + d − 1)/4⌋ bound:
//     after the first five equal bits, a stuff bit needs four more).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "firmware/protocol/arm_messages.hpp"
#include "hal/can_frame.hpp"

namespace curio::tools {

// Worst-case bits of one frame, by the rate they go at.
struct FrameBits {
  uint32_t nominal = 0;  // at the nominal (arbitration) bitrate
  uint32_t data = 0;     // at the FD data bitrate (0 for classic frames and FD without BRS)
};
FrameBits worst_case_bits(const hal::CanFrame& f);

// Seconds the frames take on the bus back to back (no idle), at the nominal and data bitrates.
double bus_seconds(const std::vector<hal::CanFrame>& frames, double nominal_bps, double data_bps);

struct TrafficBits {
  size_t frames = 0;
  uint64_t nominal_bits = 0;
  uint64_t data_bits = 0;
};
TrafficBits traffic_bits(const std::vector<hal::CanFrame>& frames);

// One control period: 7 RPDO1 targets and the SYNC from the controller, 7 TPDO1 answers.
std::vector<hal::CanFrame> control_period_frames();

// One episode: its start (SDO write 0x2000.1 and the answer), 50 control periods, the eight
// nodes' heartbeats over the 500 ms (one per node per 100 ms, the controller's default 0x1017),
// the capture request, the ground truth and, when `with_image`, the camera frame over ISO-TP
// (first frame, the controller's flow control, consecutive frames).
std::vector<hal::CanFrame> episode_frames(protocol::CanProfile profile, bool with_image);

// The budget table on stdout: for each nominal bitrate and profile, one control period (fits
// when its worst case is at most 10 ms) and one episode without and with the camera frame
// (fits when at most the 50 periods' 500 ms). `data_bps` is the FD data bitrate (the nominal
// one when 0).
void print_budget(const std::vector<double>& nominal_bps, double data_bps);

}  // namespace curio::tools
