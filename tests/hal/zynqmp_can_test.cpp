// The ZynqMP CAN driver (hal/zynqmp/): its pure part on the host (bit timing, the FIFO's frame
// words in the chip's layout and QEMU's, acceptance filters against hal::filter_matches, the
// error state), and the bus contract every backend passes (bus_contract.cpp) run on the driver
// itself: the contract server image (tests/zynqmp/contract_server_main.cpp) runs under QEMU's
// xlnx-zcu102 and executes each call of a host-side endpoint on CAN0 or CAN1 over UART0
// (tests/zynqmp/contract_rpc.hpp). The image comes from the zynqmp build
// (cmake --preset zynqmp && cmake --build --preset zynqmp); without it the contract skips.
// The board has two controllers, so the contract's third-endpoint case cannot run here (the
// ctest registration leaves it out; docs/deploy.md).
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hal/zynqmp/zynqmp_can_regs.hpp"
#include "tests/hal/bus_contract.hpp"
#include "tests/zynqmp/contract_rpc.hpp"

using namespace curio::hal;
using namespace curio::hal::test;
using namespace curio::hal::zynqmp;
namespace rpc = curio::zynqmp_rpc;

// ------------------------------------------------------------------ the pure part

TEST(ZynqmpCanTiming, ExactBitratesGetTheSamplePointNearest875) {
  CanBitTiming t;
  ASSERT_TRUE(compute_bit_timing(24'000'000, 1'000'000, 875, &t));  // QEMU's clock
  EXPECT_EQ(t.brp, 3);
  EXPECT_EQ(t.tq_per_bit(), 8u);
  EXPECT_EQ(t.sample_point_permille, 875);
  EXPECT_EQ(t.brpr_value(), 2u);
  EXPECT_EQ(t.btr_value(), (6u - 1u) | (1u - 1u) << 4 | (1u - 1u) << 7);
  ASSERT_TRUE(compute_bit_timing(100'000'000, 500'000, 875, &t));  // a ZCU102's CAN_REF_CLK
  EXPECT_EQ(100'000'000u / (t.brp * t.tq_per_bit()), 500'000u);
  EXPECT_EQ(t.sample_point_permille, 875);
  EXPECT_EQ(t.tq_per_bit(),
            8u);  // of the whole divisors (8, 10, 20, 25 quanta) only 8 gives 87.5 %
  EXPECT_FALSE(compute_bit_timing(100'000'000, 10'000, 875, &t)) << "BRP would exceed 256";
  for (uint32_t rate : {20'000u, 50'000u, 125'000u, 250'000u, 500'000u, 1'000'000u}) {
    ASSERT_TRUE(compute_bit_timing(100'000'000, rate, 875, &t)) << rate;
    EXPECT_EQ(uint64_t{100'000'000} % (uint64_t{rate} * t.brp * t.tq_per_bit()), 0u) << rate;
    EXPECT_GE(t.ts1, 1);
    EXPECT_LE(t.ts1, 16);
    EXPECT_GE(t.ts2, 1);
    EXPECT_LE(t.ts2, 8);
    EXPECT_LE(t.sjw, t.ts2);
    EXPECT_NEAR(t.sample_point_permille, 875, 40) << rate;
  }
  // 100 MHz / 800 kbit/s = 125 = 5 × 25: only 25 quanta divide it, and TS1 ≤ 16 caps the
  // sample point at 17/25. Met exactly, with the best point the controller allows.
  ASSERT_TRUE(compute_bit_timing(100'000'000, 800'000, 875, &t));
  EXPECT_EQ(t.tq_per_bit(), 25u);
  EXPECT_EQ(t.sample_point_permille, 680);
}

TEST(ZynqmpCanTiming, UnmeetableBitratesAreRefusedNotRounded) {
  CanBitTiming t;
  t.brp = 77;
  EXPECT_FALSE(compute_bit_timing(24'000'000, 999'999, 875, &t));    // no exact divider
  EXPECT_FALSE(compute_bit_timing(24'000'000, 5'000'000, 875, &t));  // fewer than 8 quanta
  EXPECT_FALSE(compute_bit_timing(24'000'000, 1'000, 875, &t));      // prescaler over 256
  EXPECT_FALSE(compute_bit_timing(24'000'000, 0, 875, &t));
  EXPECT_EQ(t.brp, 77) << "a refusal leaves the output alone";
}

namespace {
CanFrame frame_with(uint32_t id, uint8_t len, bool ext, bool remote = false) {
  CanFrame f = frame_of(id, len, false, ext, static_cast<uint8_t>(id));
  if (remote) {
    f.flags = static_cast<uint8_t>(f.flags | kFlagRemote);
    for (auto& b : f.data) b = 0;
  }
  return f;
}
bool same(const CanFrame& a, const CanFrame& b) {
  return a.id == b.id && a.len == b.len && a.flags == b.flags &&
         std::memcmp(a.data, b.data, a.len) == 0;
}
}  // namespace

TEST(ZynqmpCanWords, TheChipsLayoutIsUg1087s) {
  FrameWords w;
  CanFrame f = frame_with(0x123, 2, false);
  f.data[0] = 0xAB;
  f.data[1] = 0xCD;
  ASSERT_TRUE(encode_frame(f, FrameWordLayout::kUg1085, &w));
  EXPECT_EQ(w.id, 0x123u << 21);
  EXPECT_EQ(w.dlc, 2u << 28);
  EXPECT_EQ(w.dw1, 0xABCD0000u) << "byte 0 in DB0 = bits 31:24";
  ASSERT_TRUE(encode_frame(frame_with(0x1ABCDEF0u, 0, true), FrameWordLayout::kUg1085, &w));
  EXPECT_EQ(w.id, (0x1ABCDEF0u >> 18) << 21 | 1u << 20 | 1u << 19 | (0x1ABCDEF0u & 0x3FFFFu) << 1);
  ASSERT_TRUE(encode_frame(frame_with(0x321, 4, false, true), FrameWordLayout::kUg1085, &w));
  EXPECT_EQ(w.id, 0x321u << 21 | 1u << 20) << "a standard remote request is SRR";
  ASSERT_TRUE(encode_frame(f, FrameWordLayout::kQemu72, &w));
  EXPECT_EQ(w.id, 0x123u);
  EXPECT_EQ(w.dw1, 0x0000CDABu) << "QEMU's model: byte 0 in bits 7:0";
}

TEST(ZynqmpCanWords, EveryClassicFrameRoundTripsInBothLayoutsAndFdIsRefused) {
  for (auto layout : {FrameWordLayout::kUg1085, FrameWordLayout::kQemu72}) {
    for (uint8_t len = 0; len <= 8; ++len) {
      for (const CanFrame& f :
           {frame_with(0x7FF - len, len, false), frame_with(0x1FFFFFFFu - len, len, true),
            frame_with(0x000, len, false), frame_with(0x12345 + len, len, true, true),
            frame_with(0x65, len, false, true)}) {
        FrameWords w;
        ASSERT_TRUE(encode_frame(f, layout, &w));
        CanFrame back;
        ASSERT_TRUE(decode_frame(w, layout, &back));
        EXPECT_TRUE(same(back, f)) << int(layout) << " id " << f.id << " len " << int(len);
      }
    }
    FrameWords w;
    EXPECT_FALSE(encode_frame(frame_of(0x10, 12, true), layout, &w));  // FD
    CanFrame bad = frame_with(0x7FF, 1, false);
    bad.id = 0x800;  // does not fit 11 bits
    EXPECT_FALSE(encode_frame(bad, layout, &w));
    w.dlc = 9u << 28;
    CanFrame out;
    EXPECT_FALSE(decode_frame(w, layout, &out)) << "DLC 9 is no CAN 2.0B length";
  }
}

TEST(ZynqmpCanFilters, HardwareFiltersPassExactlyWhatTheHalFilterPasses) {
  const CanFilter filters[] = {{0x120, 0x7F0, IdType::kStandard},
                               {0x18DAF120u, 0x1FFFFFFFu, IdType::kExtended},
                               {0x00000700u, 0x1FFFFF00u, IdType::kExtended},
                               {0x7E0, 0x7FF, IdType::kStandard},
                               {0x123, 0x7FF, IdType::kAny}};
  std::vector<CanFrame> frames;
  for (uint32_t id : {0x0u, 0x120u, 0x121u, 0x12Fu, 0x130u, 0x7E0u, 0x7E1u, 0x123u, 0x7FFu})
    for (bool ext : {false, true}) frames.push_back(frame_with(id, 1, ext));
  for (uint32_t id : {0x18DAF120u, 0x18DAF121u, 0x00000705u, 0x10000705u, 0x1FFFFFFFu, 0x00000123u})
    frames.push_back(frame_with(id, 8, true));
  for (auto layout : {FrameWordLayout::kUg1085, FrameWordLayout::kQemu72}) {
    for (const CanFilter& flt : filters) {
      uint32_t mask = 0, id = 0;
      const bool in_hw = encode_filter(flt, layout, &mask, &id);
      if (!in_hw) {
        EXPECT_EQ(flt.type, IdType::kAny) << "only kAny falls back to software, chip layout only";
        EXPECT_EQ(layout, FrameWordLayout::kUg1085);
        continue;
      }
      for (const CanFrame& f : frames) {
        FrameWords w;
        ASSERT_TRUE(encode_frame(f, layout, &w));
        EXPECT_EQ((w.id & mask) == (id & mask), filter_matches(flt, f))
            << "layout " << int(layout) << " filter " << flt.id << "/" << flt.mask << " frame "
            << f.id << (f.extended() ? " ext" : " std");
      }
    }
  }
}

TEST(ZynqmpCanState, StatusRegisterMapsToTheHalStates) {
  using namespace can_reg;
  EXPECT_EQ(bus_state_from(kSrConfig), BusState::kDown);
  EXPECT_EQ(bus_state_from(1u << kSrEstatShift), BusState::kErrorActive);
  EXPECT_EQ(bus_state_from(1u << kSrEstatShift | kSrErrWrn), BusState::kErrorWarning);
  EXPECT_EQ(bus_state_from(3u << kSrEstatShift), BusState::kErrorPassive);
  EXPECT_EQ(bus_state_from(2u << kSrEstatShift), BusState::kBusOff);
  EXPECT_EQ(bus_state_from(0), BusState::kErrorActive) << "QEMU 7.2 leaves ESTAT at 00";
}

// ------------------------------------------------------------------ the contract on the image

namespace {

std::string image_path() {
  const char* env = std::getenv("CURIO_ZYNQMP_CONTRACT_IMAGE");
  return env != nullptr ? env : CURIO_ZYNQMP_CONTRACT_IMAGE;
}

// One QEMU running the contract server for the whole test binary; UART0 is a Unix socket.
class ImageLink {
 public:
  static ImageLink* get(std::string* why) {
    static std::unique_ptr<ImageLink> link;
    static std::string failure;
    if (!link && failure.empty()) {
      auto l = std::make_unique<ImageLink>();
      if (l->start(&failure)) link = std::move(l);
    }
    if (!link && why != nullptr) *why = failure;
    return link.get();
  }

  ~ImageLink() {
    if (fd_ >= 0) {
      rpc::ReplyHeader h;
      std::vector<uint8_t> out;
      call(rpc::Op::kExit, 0, nullptr, 0, &h, &out);
      close(fd_);
    }
    if (pid_ > 0) {
      int status = 0;
      for (int i = 0; i < 50 && waitpid(pid_, &status, WNOHANG) == 0; ++i) usleep(100'000);
      if (waitpid(pid_, &status, WNOHANG) == 0) {
        kill(pid_, SIGTERM);
        waitpid(pid_, &status, 0);
      }
    }
    if (!dir_.empty()) {
      unlink((dir_ + "/uart0").c_str());
      rmdir(dir_.c_str());
    }
  }

  bool call(rpc::Op op, uint8_t endpoint, const void* payload, uint32_t length,
            rpc::ReplyHeader* reply, std::vector<uint8_t>* out) {
    rpc::RequestHeader h;
    h.op = op;
    h.endpoint = endpoint;
    h.length = length;
    if (!write_all(&h, sizeof h) || !write_all(payload, length)) return false;
    if (!read_all(reply, sizeof *reply) || reply->magic != rpc::kReplyMagic) return false;
    out->resize(reply->length);
    return read_all(out->data(), reply->length);
  }

 private:
  bool start(std::string* why) {
    const std::string image = image_path();
    struct stat st {};
    if (stat(image.c_str(), &st) != 0) {
      *why = "no contract server image at " + image +
             " (cmake --preset zynqmp && cmake --build --preset zynqmp)";
      return false;
    }
    if (system("command -v qemu-system-aarch64 > /dev/null 2>&1") != 0) {
      *why = "qemu-system-aarch64 not installed";
      return false;
    }
    const char* tmp = std::getenv("TMPDIR");  // /run inside UML, whose /tmp is read-only
    std::string tmpl = std::string(tmp != nullptr ? tmp : "/tmp") + "/curio-zcu102.XXXXXX";
    if (mkdtemp(tmpl.data()) == nullptr) return (*why = "mkdtemp failed in " + tmpl, false);
    dir_ = tmpl;
    const std::string path = dir_ + "/uart0";
    const int listener = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    if (bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
        listen(listener, 1) != 0) {
      close(listener);
      return (*why = "cannot listen on " + path, false);
    }
    const std::string log = dir_ + "/qemu.log";
    pid_ = fork();
    if (pid_ == 0) {
      setenv("ZCU102_SERIAL", ("unix:" + path).c_str(), 1);
      const int lf = open("/dev/null", O_WRONLY);
      dup2(lf, 1);
      execl("/bin/sh", "sh", CURIO_ZCU102_RUN, image.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    pollfd p{listener, POLLIN, 0};
    if (poll(&p, 1, 120'000) != 1) {
      close(listener);
      return (*why = "QEMU did not connect to UART0's socket within 120 s", false);
    }
    fd_ = accept(listener, nullptr, nullptr);
    close(listener);
    if (fd_ < 0) return (*why = "accept failed", false);
    uint8_t ready = 0;
    if (!read_all(&ready, 1, 120'000) || ready != rpc::kReadyMagic) {
      return (*why = "the contract server image did not signal ready on UART0", false);
    }
    return true;
  }
  bool write_all(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    while (n > 0) {
      const ssize_t k = write(fd_, b, n);
      if (k <= 0) return false;
      b += k;
      n -= static_cast<size_t>(k);
    }
    return true;
  }
  bool read_all(void* p, size_t n, int timeout_ms = 60'000) {
    auto* b = static_cast<uint8_t*>(p);
    while (n > 0) {
      pollfd q{fd_, POLLIN, 0};
      if (poll(&q, 1, timeout_ms) != 1) return false;
      const ssize_t k = read(fd_, b, n);
      if (k <= 0) return false;
      b += k;
      n -= static_cast<size_t>(k);
    }
    return true;
  }
  std::string dir_;
  pid_t pid_ = -1;
  int fd_ = -1;
};

// A host-side endpoint whose every call runs on the image's controller `endpoint`.
class ImageBus final : public CanBus {
 public:
  ImageBus(ImageLink* link, uint8_t endpoint) : link_(link), ep_(endpoint) {}

  CanStatus send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                       size_t* accepted) override {
    size_t done = 0;
    CanStatus s = CanStatus::kOk;
    do {
      const auto k = static_cast<uint32_t>(std::min<size_t>(count - done, rpc::kMaxFrames));
      std::vector<uint8_t> in(12 + k * sizeof(CanFrame));
      std::memcpy(in.data(), &deadline_us, 8);
      std::memcpy(in.data() + 8, &k, 4);
      std::memcpy(in.data() + 12, frames + done, k * sizeof(CanFrame));
      std::vector<uint8_t> out;
      s = call(rpc::Op::kSend, in, &out);
      uint32_t a = 0;
      if (out.size() == 4) std::memcpy(&a, out.data(), 4);
      done += a;
      if (s != CanStatus::kOk) break;
    } while (done < count);
    if (accepted != nullptr) *accepted = done;
    return s;
  }
  CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) override {
    const auto cap = static_cast<uint32_t>(std::min<size_t>(capacity, rpc::kMaxFrames));
    std::vector<uint8_t> in(4), reply;
    std::memcpy(in.data(), &cap, 4);
    const CanStatus s = call(rpc::Op::kReceive, in, &reply);
    uint32_t n = 0;
    if (reply.size() >= 4) std::memcpy(&n, reply.data(), 4);
    if (reply.size() != 4 + n * sizeof(CanFrame) || n > cap) return CanStatus::kIoError;
    std::memcpy(out, reply.data() + 4, n * sizeof(CanFrame));
    if (received != nullptr) *received = n;
    return s;
  }
  CanStatus wait_readable(uint64_t timeout_us) override {
    std::vector<uint8_t> in(8), out;
    std::memcpy(in.data(), &timeout_us, 8);
    return call(rpc::Op::kWait, in, &out);
  }
  CanStatus set_filters(const CanFilter* filters, size_t count) override {
    const auto n = static_cast<uint32_t>(count);
    std::vector<uint8_t> in(4 + count * sizeof(CanFilter)), out;
    std::memcpy(in.data(), &n, 4);
    if (count > 0) std::memcpy(in.data() + 4, filters, count * sizeof(CanFilter));
    return call(rpc::Op::kFilters, in, &out);
  }
  CanStats stats() const override {
    CanStats st;
    std::vector<uint8_t> out;
    if (call(rpc::Op::kStats, {}, &out) == CanStatus::kOk && out.size() == sizeof st)
      std::memcpy(&st, out.data(), sizeof st);
    return st;
  }
  BusState state() const override {
    std::vector<uint8_t> out;
    call(rpc::Op::kState, {}, &out);
    return out.size() == 1 ? static_cast<BusState>(out[0]) : BusState::kDown;
  }
  bool carries_fd() const override {
    std::vector<uint8_t> out;
    call(rpc::Op::kCarriesFd, {}, &out);
    return out.size() == 1 && out[0] != 0;
  }
  uint64_t now_us() const override {
    std::vector<uint8_t> out;
    uint64_t now = 0;
    if (call(rpc::Op::kNow, {}, &out) == CanStatus::kOk && out.size() == 8)
      std::memcpy(&now, out.data(), 8);
    return now;
  }

 private:
  CanStatus call(rpc::Op op, const std::vector<uint8_t>& in, std::vector<uint8_t>* out) const {
    rpc::ReplyHeader h;
    if (!link_->call(op, ep_, in.data(), static_cast<uint32_t>(in.size()), &h, out)) {
      ADD_FAILURE() << "the contract server image stopped answering";
      return CanStatus::kIoError;
    }
    return static_cast<CanStatus>(h.status);
  }
  ImageLink* link_;
  uint8_t ep_;
};

BusBackend zynqmp_backend(FrameWordLayout layout, const char* name) {
  struct stat st {};
  const bool image_built = stat(image_path().c_str(), &st) == 0;
  return {name,
          [layout] {
            std::string why;
            ImageLink* link = ImageLink::get(&why);
            if (link != nullptr) {
              const auto l = static_cast<uint8_t>(layout);
              rpc::ReplyHeader h;
              std::vector<uint8_t> out;
              if (!link->call(rpc::Op::kReset, 0, &l, 1, &h, &out) || h.status != 0) {
                why = "the contract server could not reset its controllers";
                link = nullptr;
              }
            }
            auto next = std::make_shared<uint8_t>(0);
            return std::function<std::unique_ptr<CanBus>(std::string*)>(
                [link, why, next](std::string* w) -> std::unique_ptr<CanBus> {
                  if (link == nullptr) {
                    *w = why;
                    return nullptr;
                  }
                  if (*next >= 2) {
                    *w = "the ZynqMP has two CAN controllers: no third endpoint on its bus";
                    return nullptr;
                  }
                  return std::make_unique<ImageBus>(link, (*next)++);
                });
          },
          image_built, false};
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(
    ZynqmpCan, BusContract,
    ::testing::Values(zynqmp_backend(FrameWordLayout::kUg1085, "zynqmp_ug1085"),
                      zynqmp_backend(FrameWordLayout::kQemu72, "zynqmp_qemu72")),
    [](const auto& info) { return info.param.name; });
