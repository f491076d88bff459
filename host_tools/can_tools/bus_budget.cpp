#include "host_tools/can_tools/bus_budget.hpp"

#include <cstdio>
#include <string>

#include "firmware/app/controller_types.hpp"
#include "firmware/explore/config.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/canopen.hpp"
#include "firmware/protocol/cia402.hpp"
#include "firmware/protocol/isotp.hpp"

namespace curio::tools {

using hal::CanFrame;
using namespace protocol;

namespace {

constexpr uint32_t kEndBits = 13;  // CRC delimiter, ACK slot + delimiter, EOF 7, intermission 3
constexpr uint32_t kPeriodMs = app::kControlPeriodMs;

}  // namespace

FrameBits worst_case_bits(const CanFrame& f) {
  const uint32_t data = 8u * f.len;
  if (!f.fd()) {
    // SOF, id, RTR, IDE, r0, DLC, data, CRC 15: stuffed; g = 34 or 54 without the data.
    const uint32_t g = f.extended() ? 54 : 34;
    const uint32_t payload = f.remote() ? 0 : data;
    return {g + payload + kEndBits + (g + payload - 1) / 4, 0};
  }
  // SOF .. BRS; then ESI, DLC, data; stuff count, CRC and its fixed stuff bits.
  const uint32_t arbitration = f.extended() ? 36 : 17;
  const uint32_t before_crc = 1 + 4 + data;
  const uint32_t crc = f.len <= 16 ? 17 : 21;
  const uint32_t fixed_stuff = f.len <= 16 ? 6 : 7;
  const uint32_t nominal = arbitration + (arbitration - 1) / 4 + kEndBits;
  const uint32_t fast = before_crc + (before_crc + 3) / 4 + 4 + crc + fixed_stuff;
  if ((f.flags & hal::kFlagBrs) == 0) return {nominal + fast, 0};
  return {nominal, fast};
}

TrafficBits traffic_bits(const std::vector<CanFrame>& frames) {
  TrafficBits t;
  t.frames = frames.size();
  for (const CanFrame& f : frames) {
    const FrameBits b = worst_case_bits(f);
    t.nominal_bits += b.nominal;
    t.data_bits += b.data;
  }
  return t;
}

double bus_seconds(const std::vector<CanFrame>& frames, double nominal_bps, double data_bps) {
  const TrafficBits t = traffic_bits(frames);
  return static_cast<double>(t.nominal_bits) / nominal_bps +
         static_cast<double>(t.data_bits) / data_bps;
}

std::vector<CanFrame> control_period_frames() {
  std::vector<CanFrame> out;
  for (uint8_t j = 0; j < kJointNodes; ++j) {
    out.push_back(encode_joint_command(
        {static_cast<uint8_t>(kFirstJointNode + j), cia402::kCwEnableOperation, 0}));
  }
  out.push_back(encode_sync(1));
  for (uint8_t j = 0; j < kJointNodes; ++j)
    out.push_back(encode_joint_feedback({static_cast<uint8_t>(kFirstJointNode + j), 0, 0}));
  return out;
}

std::vector<CanFrame> episode_frames(CanProfile profile, bool with_image) {
  std::vector<CanFrame> out;
  SdoMessage start{SdoKind::kDownloadRequest, kCameraNode, od::kEpisodeControl,
                   od::kEpisodeStartSub, 0, 4};
  out.push_back(encode_sdo(start));
  start.kind = SdoKind::kDownloadResponse;
  out.push_back(encode_sdo(start));
  const std::vector<CanFrame> period = control_period_frames();
  for (int t = 0; t < kStepsPerEpisode; ++t) out.insert(out.end(), period.begin(), period.end());
  const uint32_t heartbeats =
      kStepsPerEpisode * kPeriodMs / app::ControllerConfig{}.heartbeat_producer_ms;
  for (uint32_t k = 0; k < heartbeats; ++k) {
    for (uint8_t n = 0; n < kJointNodes; ++n)
      out.push_back(encode_heartbeat({static_cast<uint8_t>(kFirstJointNode + n),
                                      NmtState::kOperational}));
    out.push_back(encode_heartbeat({kCameraNode, NmtState::kOperational}));
  }
  out.push_back(encode_camera_capture({0}));
  CanFrame truth[kGroundTruthClassicFrames];
  const size_t n = encode_ground_truth(GroundTruth{}, profile, truth);
  out.insert(out.end(), truth, truth + n);
  if (!with_image) return out;
  // The camera frame: the camera's sender and the controller's receiver, frame by frame.
  static uint8_t image[kCameraImageBytes];
  static uint8_t received[kCameraImageBytes];
  IsoTpSender tx(camera_link_for_camera(profile));
  IsoTpReceiver rx(camera_link_for_controller(profile), received, sizeof received);
  tx.start(image, sizeof image, 0);
  for (size_t guard = 0; guard < 4 * kCameraImageBytes; ++guard) {
    IsoTpReply r;
    const IsoTpStatus s = tx.poll(0, &r);
    if (r.valid) {
      out.push_back(r.frame);
      IsoTpReply fc;
      rx.on_frame(r.frame, 0, &fc);
      if (fc.valid) {
        out.push_back(fc.frame);
        tx.on_frame(fc.frame, 0);
      }
    }
    if (s != IsoTpStatus::kInProgress) break;
  }
  return out;
}

namespace {

std::string rate_text(double bps) {
  char buf[32];
  if (bps >= 1e6)
    std::snprintf(buf, sizeof buf, "%gM", bps / 1e6);
  else
    std::snprintf(buf, sizeof buf, "%gk", bps / 1e3);
  return buf;
}

// One row: frames, worst-case bits, time, share of `window_s` and whether it fits.
void print_row(const char* rate, const char* profile, const char* what,
               const std::vector<CanFrame>& frames, double nominal_bps, double data_bps,
               double window_s) {
  const TrafficBits t = traffic_bits(frames);
  const double s = bus_seconds(frames, nominal_bps, data_bps);
  const bool fits = s <= window_s;
  std::printf("%-11s %-8s %-30s %6zu %9llu %10.2f %7.1f%%  %s\n", rate, profile, what, t.frames,
              static_cast<unsigned long long>(t.nominal_bits + t.data_bits), s * 1e3,
              100.0 * s / window_s, fits ? "yes" : "NO");
}

}  // namespace

void print_budget(const std::vector<double>& nominal_bps, double data_bps) {
  constexpr double kPeriodS = kPeriodMs * 1e-3;
  constexpr double kEpisodeS = kStepsPerEpisode * kPeriodS;
  std::printf(
      "Worst-case bus time of Curio's arm protocol (stuff bits included; frames back to back).\n"
      "A period fits in %.0f ms; an episode fits in its %d periods (%.0f ms). EFR goal spaces\n"
      "need only the ground truth; learned ones (beta-VAE) also the 12,288-byte camera frame.\n\n",
      kPeriodS * 1e3, kStepsPerEpisode, kEpisodeS * 1e3);
  std::printf("%-11s %-8s %-30s %6s %9s %10s %8s  %s\n", "bitrate", "profile", "traffic",
              "frames", "bits", "ms", "of time", "fits");
  for (const double b : nominal_bps) {
    const double d = data_bps > 0 ? data_bps : b;
    const std::string rate = b == d ? rate_text(b) : rate_text(b) + "/" + rate_text(d);
    for (const CanProfile p : {CanProfile::kFd, CanProfile::kClassic}) {
      const char* name = to_string(p);
      print_row(rate.c_str(), name, "control period", control_period_frames(), b, d, kPeriodS);
      print_row(rate.c_str(), name, "episode, ground truth (EFR)", episode_frames(p, false), b, d,
                kEpisodeS);
      print_row(rate.c_str(), name, "episode with camera frame", episode_frames(p, true), b, d,
                kEpisodeS);
    }
  }
}

}  // namespace curio::tools
