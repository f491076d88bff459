#include "host_tools/can_tools/mock_arm.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/cia402.hpp"

namespace curio::hal::tools {
namespace {

using namespace curio::protocol;

constexpr int kPeriods = 50;
constexpr uint64_t kTimeoutUs = 2'000'000;

std::vector<uint8_t> pattern_image() {
  std::vector<uint8_t> img(kCameraImageBytes);
  for (size_t i = 0; i < img.size(); ++i) img[i] = static_cast<uint8_t>(i * 7);
  return img;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(p * static_cast<double>(v.size() - 1))];
}

}  // namespace

int run_mock_arm(CanBus& bus, uint64_t idle_timeout_us) {
  int32_t target[kJointNodes] = {};
  const auto image = pattern_image();
  IsoTpSender camera(camera_link_for_camera(profile_for(bus.carries_fd())));
  CanFrame in[64];
  std::vector<CanFrame> out;
  for (;;) {
    out.clear();
    size_t n = 0;
    // Block until a frame or the camera's next deadline (STmin, flow-control timeout):
    // never spin, a spinning process starves its peer on UML's single CPU.
    uint64_t now = camera.busy() ? bus.now_us() : 0;  // the clock is a syscall in UML
    const uint64_t next = camera.next_event_us();
    const uint64_t wait = !camera.busy() ? idle_timeout_us : (next > now ? next - now : 0);
    if (bus.receive_wait(in, 64, &n, wait) != CanStatus::kOk) {
      n = 0;
      if (!camera.busy()) return 0;
    }
    now = bus.now_us();  // one reading per batch
    for (size_t i = 0; i < n; ++i) {
      const CanFrame& f = in[i];
      JointCommand jc;
      CameraCapture cc;
      uint8_t counter = 0;
      if (decode_joint_command(f, &jc) == CodecStatus::kOk) {
        target[jc.node - kFirstJointNode] = jc.target_counts;
      } else if (decode_sync(f, &counter) == CodecStatus::kOk) {
        for (uint8_t j = 0; j < kJointNodes; ++j) {
          const auto sw =
              static_cast<uint16_t>(cia402::statusword_for(cia402::DriveState::kOperationEnabled) |
                                    cia402::kSwFollowingTarget);
          out.push_back(
              encode_joint_feedback({static_cast<uint8_t>(kFirstJointNode + j), sw, target[j]}));
        }
      } else if (decode_camera_capture(f, &cc) == CodecStatus::kOk) {
        camera.start(image.data(), image.size(), now);
      } else {
        camera.on_frame(f, now);
      }
    }
    // Everything the camera may send now goes out in one batch.
    for (;;) {
      IsoTpReply r;
      const IsoTpStatus s = camera.poll(now, &r);
      if (r.valid) out.push_back(r.frame);
      if (!r.valid || s != IsoTpStatus::kInProgress) break;
    }
    if (hal::send_all(bus, out.data(), out.size(), now + kTimeoutUs) != CanStatus::kOk) return 1;
  }
}

EpisodeBenchResult run_episode_bench(CanBus& bus, int episodes) {
  EpisodeBenchResult r;
  std::vector<double> cycles, images;
  std::vector<uint8_t> buffer(kIsoTpMaxMessage);
  const auto expect = pattern_image();
  const uint64_t start = bus.now_us();
  uint64_t frames = 0, reads = 0;
  CanFrame in[64];
  for (int e = 0; e < episodes; ++e) {
    // The clock is read once per period, as a controller needs it for the TX deadline (each
    // reading is a syscall inside UML); the period is timed per episode.
    const uint64_t episode_t0 = bus.now_us();
    for (int t = 0; t < kPeriods; ++t) {
      CanFrame batch[kJointNodes + 1];
      for (uint8_t j = 0; j < kJointNodes; ++j) {
        int32_t counts = 0;
        angle_to_counts(0.01 * (t + j), &counts);
        batch[j] = encode_joint_command(
            {static_cast<uint8_t>(kFirstJointNode + j), cia402::kCwEnableOperation, counts});
      }
      batch[kJointNodes] = encode_sync(static_cast<uint8_t>(t % kSyncCounterMax + 1));
      const uint64_t t0 = bus.now_us();
      if (bus.send_batch(batch, kJointNodes + 1, t0 + kTimeoutUs, nullptr) != CanStatus::kOk)
        return r;
      int got = 0;
      while (got < kJointNodes) {
        size_t n = 0;
        ++reads;
        if (bus.receive_wait(in, 64, &n, kTimeoutUs) != CanStatus::kOk) {
          std::fprintf(stderr, "episode bench: no TPDO (episode %d, period %d)\n", e, t);
          return r;
        }
        for (size_t i = 0; i < n; ++i) {
          JointFeedback fb;
          if (decode_joint_feedback(in[i], &fb) == CodecStatus::kOk) ++got;
        }
      }
      frames += 2 * kJointNodes + 1;
    }
    cycles.push_back(static_cast<double>(bus.now_us() - episode_t0) / kPeriods);
    IsoTpReceiver rx(camera_link_for_controller(profile_for(bus.carries_fd())), buffer.data(),
                     buffer.size());
    const uint64_t t0 = bus.now_us();
    if (bus.send(encode_camera_capture({static_cast<uint32_t>(e)}), t0 + kTimeoutUs) !=
        CanStatus::kOk)
      return r;
    frames += 1;
    IsoTpStatus s = IsoTpStatus::kIdle;
    while (s != IsoTpStatus::kComplete) {
      size_t n = 0;
      if (bus.receive_wait(in, 64, &n, kTimeoutUs) != CanStatus::kOk) {
        std::fprintf(stderr, "episode bench: image stalled (episode %d)\n", e);
        return r;
      }
      const uint64_t now = bus.now_us();  // one reading per batch
      for (size_t i = 0; i < n && s != IsoTpStatus::kComplete; ++i) {
        IsoTpReply fc;
        s = rx.on_frame(in[i], now, &fc);
        if (s == IsoTpStatus::kIgnored) continue;
        ++frames;
        if (fc.valid) {
          bus.send(fc.frame, now + kTimeoutUs);
          ++frames;
        }
        if (s != IsoTpStatus::kInProgress && s != IsoTpStatus::kComplete) {
          std::fprintf(stderr, "episode bench: image failed: %s\n", to_string(s));
          return r;
        }
      }
    }
    images.push_back(static_cast<double>(bus.now_us() - t0));
    if (!std::equal(expect.begin(), expect.end(), rx.data())) return r;
  }
  r.episodes = episodes;
  double sum = 0;
  for (double c : cycles) sum += c;
  r.cycle_mean_us = sum / static_cast<double>(cycles.size());
  r.cycle_worst_us = percentile(cycles, 1.0);
  r.image_median_us = percentile(images, 0.5);
  r.episodes_per_s = episodes / (static_cast<double>(bus.now_us() - start) * 1e-6);
  r.frames_per_episode = frames / static_cast<uint64_t>(episodes);
  r.reads_per_cycle = static_cast<double>(reads) / (static_cast<double>(cycles.size()) * kPeriods);
  r.ok = true;
  return r;
}

}  // namespace curio::hal::tools
