// The CAN bus interface every backend implements (SocketCAN, UDP, in-process loopback, an
// MCU driver). Modelled on ArduPilot's AP_HAL::CANIface and Zephyr's CAN API: never blocks
// except in wait_readable(), TX deadlines, acceptance filters, statistics and bus state.
// Firmware-clean: no heap, no OS headers.
#pragma once
#include <cstddef>
#include <cstdint>

#include "hal/can_frame.hpp"

namespace curio::hal {

enum class CanStatus : uint8_t {
  kOk = 0,
  kEmpty,            // receive: nothing pending
  kWouldBlock,       // send: TX queue full now; retry later (frame not taken)
  kTimeout,          // wait_readable: nothing arrived in time
  kDeadlineExpired,  // send: the deadline had already passed (frame dropped, counted)
  kInvalidFrame,     // send: is_valid() false
  kNotSupported,     // e.g. an FD frame on a classic-only interface
  kTooManyFilters,   // set_filters: more than kMaxFilters
  kBusOff,           // controller is bus-off: nothing is sent
  kIoError,          // the backend's transport failed (see errors counter)
};

constexpr const char* to_string(CanStatus s) {
  switch (s) {
    case CanStatus::kOk:
      return "ok";
    case CanStatus::kEmpty:
      return "empty";
    case CanStatus::kWouldBlock:
      return "would block (TX queue full)";
    case CanStatus::kTimeout:
      return "timeout";
    case CanStatus::kDeadlineExpired:
      return "deadline expired";
    case CanStatus::kInvalidFrame:
      return "invalid frame";
    case CanStatus::kNotSupported:
      return "not supported by this bus";
    case CanStatus::kTooManyFilters:
      return "too many filters";
    case CanStatus::kBusOff:
      return "bus-off";
    case CanStatus::kIoError:
      return "I/O error";
  }
  return "?";
}

enum class BusState : uint8_t {
  kErrorActive = 0,  // normal
  kErrorWarning,     // error counters above 96
  kErrorPassive,     // error counters above 127
  kBusOff,           // TX error counter above 255: off the bus until recovery
  kDown,             // interface down or transport closed
};

constexpr const char* to_string(BusState s) {
  switch (s) {
    case BusState::kErrorActive:
      return "error-active";
    case BusState::kErrorWarning:
      return "error-warning";
    case BusState::kErrorPassive:
      return "error-passive";
    case BusState::kBusOff:
      return "bus-off";
    case BusState::kDown:
      return "down";
  }
  return "?";
}

// Acceptance filter: a frame passes when (frame.id & mask) == (id & mask) and its identifier
// width matches `type`. No filters installed = accept everything.
enum class IdType : uint8_t { kAny = 0, kStandard, kExtended };

struct CanFilter {
  uint32_t id = 0;
  uint32_t mask = 0;
  IdType type = IdType::kAny;
};

constexpr bool filter_matches(const CanFilter& f, const CanFrame& frame) {
  if (f.type == IdType::kStandard && frame.extended()) return false;
  if (f.type == IdType::kExtended && !frame.extended()) return false;
  return (frame.id & f.mask) == (f.id & f.mask);
}

// Error frames bypass the filters (they are opted into per backend).
constexpr bool filters_accept(const CanFilter* filters, size_t count, const CanFrame& frame) {
  if (count == 0 || frame.error()) return true;
  for (size_t i = 0; i < count; ++i) {
    if (filter_matches(filters[i], frame)) return true;
  }
  return false;
}

struct CanStats {
  uint64_t tx_frames = 0;    // frames put on the bus
  uint64_t rx_frames = 0;    // frames handed to the caller
  uint64_t tx_timedout = 0;  // dropped: deadline passed before they reached the bus
  uint64_t tx_rejected = 0;  // refused: queue full, invalid, unsupported, bus-off
  uint64_t rx_dropped = 0;   // lost: receive queue overrun
  uint64_t rx_filtered = 0;  // discarded by acceptance filters (software-filtering backends)
  uint64_t errors = 0;       // error frames, transport errors, malformed input
  uint64_t bus_off_events = 0;
};

class CanBus {
 public:
  static constexpr size_t kMaxFilters = 16;

  virtual ~CanBus() = default;

  // Takes up to `count` frames for transmission, in order, without blocking. A taken frame
  // that cannot reach the bus by `deadline_us` (this bus's clock, now_us()) is dropped and
  // counted in tx_timedout. Returns kOk when all were taken; otherwise *accepted (may be
  // null) says how many were and the status says why the next one was not.
  virtual CanStatus send_batch(const CanFrame* frames, size_t count, uint64_t deadline_us,
                               size_t* accepted) = 0;

  // Moves up to `capacity` received frames into `out`, oldest first, without blocking.
  // Returns kOk if at least one frame was received, kEmpty if none.
  virtual CanStatus receive_batch(CanFrame* out, size_t capacity, size_t* received) = 0;

  // Blocks until a frame can be received (kOk) or `timeout_us` passes (kTimeout).
  virtual CanStatus wait_readable(uint64_t timeout_us) = 0;

  // receive_batch, first waiting up to `timeout_us` if nothing is pending: kOk or kTimeout.
  // Socket backends override it to do both in one syscall (~20 µs each inside UML).
  virtual CanStatus receive_wait(CanFrame* out, size_t capacity, size_t* received,
                                 uint64_t timeout_us) {
    const CanStatus s = receive_batch(out, capacity, received);
    if (s != CanStatus::kEmpty) return s;
    const CanStatus w = wait_readable(timeout_us);
    if (w != CanStatus::kOk) return w;
    const CanStatus r = receive_batch(out, capacity, received);
    return r == CanStatus::kEmpty ? CanStatus::kTimeout : r;  // e.g. all filtered out
  }

  // Replaces the acceptance filters; count 0 accepts every frame.
  virtual CanStatus set_filters(const CanFilter* filters, size_t count) = 0;

  virtual CanStats stats() const = 0;
  virtual BusState state() const = 0;

  // Whether CAN FD frames travel on this bus. False: a classic bus (a SocketCAN interface with
  // MTU 16, the kernel's slcan, a classic-only adapter or controller): FD frames are refused
  // with kNotSupported, and the arm protocol runs its classic profile (arm_messages.hpp).
  virtual bool carries_fd() const = 0;

  // Microseconds on the clock that deadlines refer to (monotonic).
  virtual uint64_t now_us() const = 0;

  // Convenience wrappers over the batch calls.
  CanStatus send(const CanFrame& frame, uint64_t deadline_us) {
    return send_batch(&frame, 1, deadline_us, nullptr);
  }
  CanStatus receive(CanFrame* out) {
    size_t n = 0;
    return receive_batch(out, 1, &n);
  }
  // Waits up to timeout_us for one frame: kOk or kTimeout.
  CanStatus receive(CanFrame* out, uint64_t timeout_us) {
    size_t n = 0;
    return receive_wait(out, 1, &n, timeout_us);
  }
};

// Sends frames[0..count) in order until all are taken or the bus refuses one. A full TX queue
// (kWouldBlock) is waited out, letting a socket backlog move with wait_readable(0), until the
// deadline, after which send_batch answers kDeadlineExpired. Returns kOk, or the refusal, in
// which case frames[*sent] is the refused frame (*sent may be null).
inline CanStatus send_all(CanBus& bus, const CanFrame* frames, size_t count, uint64_t deadline_us,
                          size_t* sent = nullptr) {
  size_t done = 0;
  CanStatus s = CanStatus::kOk;
  while (done < count) {
    size_t k = 0;
    s = bus.send_batch(frames + done, count - done, deadline_us, &k);
    done += k;
    if (s == CanStatus::kWouldBlock) {
      bus.wait_readable(0);
      s = CanStatus::kOk;
    } else if (s != CanStatus::kOk) {
      break;
    }
  }
  if (sent != nullptr) *sent = done;
  return s;
}

}  // namespace curio::hal
