// curio-can: talk to any Curio bus URL from the shell (socketcan:IFACE, udp:127.0.0.1:PORT).
//   curio-can send --bus URL 123#DEADBEEF 18DAF120##1AABB...   send frames (can-utils notation)
//   curio-can dump --bus URL [-n COUNT] [-t MS]          print frames as they arrive
//   curio-can echo --bus URL [-n COUNT] [-t MS]          answer each even-id frame with id|1
//   curio-can bench --bus URL [--fd] [-n FRAMES] [--in-flight K]
//                                                        round trip and frames/s vs an echo
//                                                        process it starts itself
//   curio-can mock-arm --bus URL                         7 CiA 402 joints + camera node
//   curio-can episodes --bus URL [-e N]                  time whole episodes (50 SYNC periods
//                                                        + one camera frame) vs a mock arm
//                                                        process it starts itself
//   curio-can slcan-bridge --serial unix:PATH|pty|fd:N --bus URL [--fd] [--max-fps F --burst B]
//                                                        join an SLCAN byte stream (QEMU's
//                                                        UART, a pty) to the bus, both ways
//   curio-can budget [--bitrate B] [--fd-data-bitrate D] worst-case bus time of a control
//                                                        period and an episode, per profile
//                                                        (no bus needed)
// Every subcommand that talks to a bus names it with --bus URL, as curio-controller and
// curio-sim serve do. Exit codes as every Curio program (host_tools/cli/command_line.hpp): 2 for a
// usage error (a URL or frame that does not parse included), 1 when the bus cannot be opened
// or does not answer.
#include <sys/wait.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "firmware/protocol/arm_messages.hpp"
#include "hal/host/can_text.hpp"
#include "hal/linux/open_bus.hpp"
#include "host_tools/can_tools/bus_budget.hpp"
#include "host_tools/can_tools/mock_arm.hpp"
#include "host_tools/can_tools/slcan_bridge.hpp"
#include "host_tools/cli/bus_url_option.hpp"
#include "host_tools/cli/command_line.hpp"

using namespace curio::hal;

namespace {

std::unique_ptr<CanBus> open_or_die(const std::string& url) {
  std::string error;
  auto bus = open_bus(url, &error);
  if (!bus) {
    std::fprintf(stderr, "curio-can: %s\n", error.c_str());
    std::exit(curio::cli::kRuntimeFailure);
  }
  return bus;
}

// Starts `curio-can ARGS...` as a child process on the same bus.
pid_t spawn_self(const std::vector<std::string>& args) {
  const pid_t child = fork();
  if (child == 0) {
    std::vector<char*> argv{const_cast<char*>("curio-can")};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  return child;
}

int cmd_send(const std::string& url, const std::vector<std::string>& texts) {
  auto bus = open_or_die(url);
  std::vector<CanFrame> frames;
  for (const auto& t : texts) {
    CanFrame f;
    parse_frame(t, &f);  // checked when parsed (main)
    frames.push_back(f);
  }
  const CanStatus s = send_all(*bus, frames.data(), frames.size(), bus->now_us() + 1'000'000);
  if (s != CanStatus::kOk) {
    std::fprintf(stderr, "curio-can: send failed: %s\n", to_string(s));
    return 1;
  }
  // Socket backends may hold frames in their backlog: drain it before exiting.
  while (bus->stats().tx_frames + bus->stats().tx_timedout < frames.size()) {
    bus->wait_readable(1000);
  }
  return bus->stats().tx_timedout == 0 ? 0 : 1;
}

// Runs `on_frame` on each frame until `count` frames (0 = forever) or `timeout_ms` of silence.
template <typename F>
int receive_loop(CanBus& bus, uint64_t count, int timeout_ms, F on_frame) {
  uint64_t seen = 0;
  CanFrame batch[64];
  const uint64_t wait =
      timeout_ms > 0 ? static_cast<uint64_t>(timeout_ms) * 1000 : 3'600'000'000ull;
  while (count == 0 || seen < count) {
    size_t n = 0;
    if (bus.receive_wait(batch, 64, &n, wait) != CanStatus::kOk) {
      if (timeout_ms > 0) return 1;
      continue;
    }
    for (size_t i = 0; i < n; ++i) on_frame(batch[i]);
    seen += n;
  }
  return 0;
}

int cmd_dump(const std::string& url, uint64_t count, int timeout_ms) {
  auto bus = open_or_die(url);
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = receive_loop(*bus, count, timeout_ms, [&](const CanFrame& f) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("(%.6f) %s %s\n", t, url.c_str(), format_frame(f).c_str());
    std::fflush(stdout);
  });
  return count == 0 ? 0 : rc;
}

int cmd_echo(const std::string& url, uint64_t count, int timeout_ms) {
  auto bus = open_or_die(url);
  std::printf("echo ready\n");
  std::fflush(stdout);
  std::vector<CanFrame> replies;
  CanFrame batch[64];
  uint64_t seen = 0;
  while (count == 0 || seen < count) {
    size_t n = 0;
    if (bus->receive_wait(batch, 64, &n, static_cast<uint64_t>(timeout_ms) * 1000) !=
        CanStatus::kOk) {
      return count == 0 ? 0 : 1;
    }
    replies.clear();
    for (size_t i = 0; i < n; ++i) {
      if (batch[i].id & 1u) continue;
      replies.push_back(batch[i]);
      replies.back().id |= 1u;
    }
    seen += n;
    if (send_all(*bus, replies.data(), replies.size(), bus->now_us() + 1'000'000) != CanStatus::kOk)
      return 1;
  }
  return 0;
}

CanFrame bench_frame(bool fd, uint32_t seq) {
  CanFrame f;
  uint8_t payload[64];
  for (size_t i = 0; i < sizeof(payload); ++i) payload[i] = static_cast<uint8_t>(seq + i);
  make_frame(&f, 0x100, false, fd, payload, fd ? 64 : 8);
  return f;
}

int cmd_bench(const std::string& url, bool fd, uint64_t frames, unsigned in_flight_max,
              int rtt_count) {
  auto bus = open_or_die(url);
  const pid_t child = spawn_self({"echo", "--bus", url, "-t", "3000"});  // the peer process
  const CanFilter echoes{0x101, 0x7FF, IdType::kStandard};
  bus->set_filters(&echoes, 1);
  auto now = [&] { return bus->now_us(); };
  CanFrame rx;
  // Wait until the echo answers (process start, bind).
  bool up = false;
  for (int i = 0; i < 500 && !up; ++i) {
    bus->send(bench_frame(fd, 0), now() + 100000);
    up = bus->receive(&rx, 10000) == CanStatus::kOk;
  }
  if (!up) {
    std::fprintf(stderr, "curio-can bench: no echo on %s\n", url.c_str());
    kill(child, SIGTERM);
    return 1;
  }
  while (bus->receive(&rx, 20000) == CanStatus::kOk) {
  }
  // Round trip, one frame outstanding.
  std::vector<double> rtt;
  for (int i = 0; i < rtt_count; ++i) {
    const uint64_t t0 = now();
    bus->send(bench_frame(fd, static_cast<uint32_t>(i)), t0 + 100000);
    if (bus->receive(&rx, 1'000'000) != CanStatus::kOk) {
      std::fprintf(stderr, "curio-can bench: echo lost\n");
      break;
    }
    rtt.push_back(static_cast<double>(now() - t0));
  }
  std::sort(rtt.begin(), rtt.end());
  // Throughput: keep `in_flight_max` frames in flight until `frames` have come back.
  std::vector<CanFrame> tx(in_flight_max);
  uint64_t sent = 0, back = 0;
  CanFrame batch[64];
  const uint64_t t0 = now();
  while (back < frames) {
    const uint64_t in_flight = sent - back;
    if (sent < frames && in_flight < in_flight_max) {
      const size_t k =
          static_cast<size_t>(std::min<uint64_t>(in_flight_max - in_flight, frames - sent));
      for (size_t i = 0; i < k; ++i) tx[i] = bench_frame(fd, static_cast<uint32_t>(sent + i));
      size_t acc = 0;
      bus->send_batch(tx.data(), k, now() + 1'000'000, &acc);
      sent += acc;
    }
    size_t n = 0;
    if (bus->receive_wait(batch, 64, &n, 2'000'000) != CanStatus::kOk) {
      std::fprintf(stderr, "curio-can bench: stalled at %llu/%llu frames\n",
                   static_cast<unsigned long long>(back), static_cast<unsigned long long>(frames));
      break;
    }
    back += n;
  }
  const double secs = static_cast<double>(now() - t0) * 1e-6;
  kill(child, SIGTERM);
  waitpid(child, nullptr, 0);
  const auto pct = [&](double p) {
    return rtt.empty() ? 0.0 : rtt[static_cast<size_t>(p * static_cast<double>(rtt.size() - 1))];
  };
  std::printf(
      "bench %s %s: round trip median %.1f us, p99 %.1f us (%zu pings); "
      "%.0f frames/s each way (%llu frames, %u in flight)\n",
      url.c_str(), fd ? "FD64" : "classic8", pct(0.5), pct(0.99), rtt.size(),
      static_cast<double>(back) / secs, static_cast<unsigned long long>(back), in_flight_max);
  return back == frames ? 0 : 1;
}

int cmd_episodes(const std::string& url, int episodes) {
  auto bus = open_or_die(url);
  // An in-process bus gets the mock arm in a thread; any other bus, in another process.
  const bool in_process = url.rfind("loopback", 0) == 0;
  std::unique_ptr<CanBus> arm_bus = in_process ? open_or_die(url) : nullptr;
  std::thread arm_thread;
  pid_t child = -1;
  if (in_process) {
    arm_thread = std::thread([&] { tools::run_mock_arm(*arm_bus, 300'000); });
  } else {
    child = spawn_self({"mock-arm", "--bus", url});
  }
  // Wait for the mock arm: a SYNC is answered with TPDOs once it runs.
  bool up = false;
  CanFrame rx;
  for (int i = 0; i < 300 && !up; ++i) {
    bus->send(curio::protocol::encode_sync(1), bus->now_us() + 100000);
    up = bus->receive(&rx, 20000) == CanStatus::kOk;
  }
  while (bus->receive(&rx, 50000) == CanStatus::kOk) {
  }
  const auto r = up ? tools::run_episode_bench(*bus, episodes) : tools::EpisodeBenchResult{};
  if (in_process) {
    arm_thread.join();  // the mock arm leaves after 300 ms of silence
  } else {
    kill(child, SIGTERM);
    waitpid(child, nullptr, 0);
  }
  if (!r.ok) {
    std::fprintf(stderr, "curio-can episodes: failed on %s\n", url.c_str());
    return 1;
  }
  std::printf(
      "episodes %s: %d episodes, %.1f episodes/s; control period mean %.1f us (slowest episode "
      "%.1f us); camera frame median %.1f ms; %llu frames per episode; %.1f reads per period\n",
      url.c_str(), r.episodes, r.episodes_per_s, r.cycle_mean_us, r.cycle_worst_us,
      r.image_median_us * 1e-3, static_cast<unsigned long long>(r.frames_per_episode),
      r.reads_per_cycle);
  return 0;
}

const CLI::Validator kBusUrl = curio::cli::bus_url_check();

// --serial: unix:PATH, pty or fd:N.
const CLI::Validator kSerial(
    [](std::string& s) {
      const bool fd = s.rfind("fd:", 0) == 0 && s.size() > 3 &&
                      s.find_first_not_of("0123456789", 3) == std::string::npos;
      const bool unix_socket = s.rfind("unix:", 0) == 0 && s.size() > 5;
      return fd || unix_socket || s == "pty" ? std::string()
                                             : "'" + s + "' is not unix:PATH, pty or fd:N";
    },
    "SERIAL");

// Every subcommand's options; each subcommand reads only its own.
struct CanOptions {
  std::string url;
  std::vector<std::string> frames;
  uint64_t count = 0;
  int timeout_ms = 0;
  bool fd = false;
  uint64_t n_frames = 20000;
  unsigned in_flight = 32;
  int rtt_count = 1000;
  int episodes = 20;
  tools::SlcanBridgeOptions bridge;
  bool bridge_fd = false;
  double bitrate = 0;       // budget: 0 = the table of 125k, 250k, 500k, 1M
  double data_bitrate = 0;  // budget: 0 = the nominal bitrate (no switch)
};

constexpr int kDay_ms = 86'400'000;

CLI::App* add_bus_command(CLI::App& app, const char* name, const char* help, CanOptions& o) {
  CLI::App* sub = app.add_subcommand(name, help);
  sub->add_option("--bus", o.url, "bus URL")->required()->check(kBusUrl);
  return sub;
}

// send, dump, echo: frames by hand.
void add_frame_commands(CLI::App& app, CanOptions& o) {
  auto* send =
      add_bus_command(app, "send", "send frames (can-utils notation: 123#DEADBEEF, 123##1AABB)", o);
  send->add_option("frames", o.frames, "frames")
      ->required()
      ->check(CLI::Validator(
          [](std::string& t) {
            CanFrame f;
            return parse_frame(t, &f)
                       ? std::string()
                       : "'" + t + "' is not a frame (e.g. 123#DEADBEEF, 123##1AABB)";
          },
          "FRAME"));
  auto* dump = add_bus_command(app, "dump", "print received frames", o);
  dump->add_option("-n,--count", o.count, "stop after COUNT frames (0 = never)")
      ->check(curio::cli::kNonNegative);
  dump->add_option("-t,--timeout-ms", o.timeout_ms, "give up after this much silence (0 = never)")
      ->check(CLI::Range(0, kDay_ms));
  auto* echo =
      add_bus_command(app, "echo", "answer every even-id frame with the same frame, id|1", o);
  echo->add_option("-n,--count", o.count, "stop after COUNT frames (0 = never)")
      ->check(curio::cli::kNonNegative);
  echo->add_option("-t,--timeout-ms", o.timeout_ms, "exit after this much silence")
      ->default_val(10000)
      ->check(CLI::Range(1, kDay_ms));
}

// bench, mock-arm, episodes: the bus and the protocol timed against a forked peer.
void add_timing_commands(CLI::App& app, CanOptions& o) {
  auto* bench =
      add_bus_command(app, "bench", "round trip and frames/s against a forked echo process", o);
  bench->add_flag("--fd", o.fd, "64-byte FD frames (default: 8-byte classic)");
  bench->add_option("-n,--frames", o.n_frames, "frames for the throughput run")
      ->default_val(20000)
      ->check(CLI::Range(uint64_t{1}, uint64_t{1'000'000'000}));
  bench->add_option("--in-flight", o.in_flight, "frames in flight in the throughput run")
      ->default_val(32)
      ->check(CLI::Range(1u, 512u));
  bench->add_option("-r,--pings", o.rtt_count, "round trips to time")
      ->default_val(1000)
      ->check(CLI::Range(1, 10'000'000));
  auto* mock = add_bus_command(app, "mock-arm", "serve as 7 CiA 402 joints + the camera node", o);
  mock->add_option("-t,--timeout-ms", o.timeout_ms, "exit after this much silence")
      ->default_val(10000)
      ->check(CLI::Range(1, kDay_ms));
  auto* eps = add_bus_command(app, "episodes", "time episodes against a forked mock arm", o);
  eps->add_option("-e,--episodes", o.episodes, "episodes to run")
      ->default_val(20)
      ->check(CLI::Range(1, 1'000'000));
}

void add_bridge_command(CLI::App& app, CanOptions& o) {
  auto* bridge = app.add_subcommand(
      "slcan-bridge", "join an SLCAN serial stream (QEMU UART socket, pty, fd) to a bus URL");
  tools::SlcanBridgeOptions& b = o.bridge;
  bridge
      ->add_option("--serial", b.serial,
                   "unix:PATH (connect, e.g. QEMU -serial unix:PATH,server=on), pty (open one "
                   "and print its path) or fd:N (an inherited descriptor)")
      ->required()
      ->check(kSerial);
  bridge->add_option("--bus", b.bus, "bus URL")->required()->check(kBusUrl);
  bridge->add_flag("--fd", o.bridge_fd,
                   "also carry CAN FD frames (d/D/b/B lines; the kernel's slcan is classic only)");
  bridge
      ->add_option("--max-fps", b.max_fps,
                   "pace lines to the serial side (lines/s; 0 = as fast as it takes them)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e9));
  bridge->add_option("--burst", b.burst, "burst of the --max-fps pacing, lines")
      ->capture_default_str()
      ->check(CLI::Range(1u, 4096u));
  bridge
      ->add_option("--connect-timeout", b.connect_timeout_s,
                   "unix:PATH: keep trying to connect this many seconds")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 86400.0));
  bridge
      ->add_option("--status-every", b.stats_every_s,
                   "seconds between statistics lines on stderr (0 = only at the end)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 86400.0));
}

void add_budget_command(CLI::App& app, CanOptions& o) {
  auto* budget = app.add_subcommand(
      "budget",
      "worst-case bus time (bit stuffing included) of one control period and one episode in the "
      "FD and classic profiles, and whether they fit 10 ms and the episode's 500 ms");
  budget
      ->add_option("--bitrate", o.bitrate,
                   "nominal (arbitration) bitrate in bit/s, e.g. 500000 (default: a table of "
                   "125k, 250k, 500k and 1M)")
      ->check(CLI::Range(10'000.0, 1'000'000.0));
  budget
      ->add_option("--fd-data-bitrate", o.data_bitrate,
                   "CAN FD data-phase bitrate in bit/s, e.g. 2000000 (default: the nominal "
                   "bitrate); at least the nominal one")
      ->check(CLI::Range(10'000.0, 8'000'000.0));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "curio-can: send, dump, echo and benchmark frames on a Curio bus URL\n"
      "URLs: " +
          std::string(kBusUrlHelp),
      "curio-can"};
  app.require_subcommand(1);
  CanOptions o;
  add_frame_commands(app, o);
  add_timing_commands(app, o);
  add_bridge_command(app, o);
  add_budget_command(app, o);
  if (const auto code = curio::cli::parse(app, argc, argv)) return *code;

  const std::string command = app.get_subcommands().front()->get_name();
  if (command == "slcan-bridge") {
    o.bridge.mode =
        o.bridge_fd ? curio::protocol::SlcanMode::kFd : curio::protocol::SlcanMode::kClassic;
    return tools::run_slcan_bridge(o.bridge);
  }
  if (command == "budget") {
    if (o.data_bitrate > 0 && o.bitrate > 0 && o.data_bitrate < o.bitrate) {
      std::fprintf(stderr,
                   "curio-can budget: --fd-data-bitrate %.0f is below --bitrate %.0f (the data "
                   "phase is never slower than arbitration)\n",
                   o.data_bitrate, o.bitrate);
      return curio::cli::kUsageError;
    }
    const std::vector<double> rates =
        o.bitrate > 0 ? std::vector<double>{o.bitrate}
                      : std::vector<double>{125'000, 250'000, 500'000, 1'000'000};
    curio::tools::print_budget(rates, o.data_bitrate);
    return 0;
  }
  if (command == "mock-arm") {
    auto bus = open_or_die(o.url);
    return tools::run_mock_arm(*bus, static_cast<uint64_t>(o.timeout_ms) * 1000);
  }
  if (command == "episodes") return cmd_episodes(o.url, o.episodes);
  if (command == "send") return cmd_send(o.url, o.frames);
  if (command == "dump") return cmd_dump(o.url, o.count, o.timeout_ms);
  if (command == "echo") return cmd_echo(o.url, o.count, o.timeout_ms);
  if (command == "bench") return cmd_bench(o.url, o.fd, o.n_frames, o.in_flight, o.rtt_count);
  return curio::cli::kUsageError;
}
