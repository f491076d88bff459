// The drives' safety configuration, written by the controller at every bring-up (a rebooted
// drive has lost it) to every joint by SDO, each value read back: the heartbeat consumer that
// watches the controller (0x1016), what a lost controller, a quick stop and a fault do
// (0x6007, 0x605A, 0x605E), the quick-stop deceleration (0x6085), the joint range (0x607D),
// the speed limits (0x607F, 0x6080), the following-error window and time (0x6065, 0x6066).
// A drive that aborts a write, or reads back another value, stops the start-up: the fault is
// kConfigRejected, and counters() name the node, object, value written and read or the abort
// code. docs/hil.md tables every object with its value and why.
#pragma once
#include <cstddef>
#include <cstdint>

#include "firmware/app/controller_types.hpp"

namespace curio::app {

class CanOpenMaster;

// One object the controller writes to every joint.
struct DriveObject {
  uint16_t index = 0;
  uint8_t sub = 0;
  uint8_t size = 0;  // bytes (1, 2 or 4)
  uint32_t value = 0;
};

inline constexpr size_t kDriveObjects = 11;

// The objects and values for `config`, in the order they are written.
void drive_objects(const ControllerConfig& config, DriveObject out[kDriveObjects]);

// Writes every object to every joint and reads each back; false on the first refusal (fault
// raised: kConfigRejected, or an SDO timeout).
bool configure_drives(CanOpenMaster& master);

// The heartbeat consumer off on every joint (0x1016.1 = 0), at a controlled stop's end: the
// controller's heartbeat stops with it, and a disabled drive has nothing to stop. Best effort.
void release_drives(CanOpenMaster& master);

}  // namespace curio::app
