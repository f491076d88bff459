// Every node's standard identity (CiA 301), read at start-up as a CANopen master does before it
// starts a node (the CiA 302 boot-up): the device type (0x1000) must be what the controller
// drives (a CiA 402 drive on a joint, a device of no standard profile as the camera), else the
// start is refused (kWrongDevice, naming node and value); the identity object (0x1018: vendor,
// product, revision, serial) is kept for the run's summary.
#pragma once
#include <cstdint>

#include "firmware/app/sdo_client.hpp"
#include "firmware/protocol/arm_objects.hpp"

namespace curio::app {

class CanOpenMaster;

inline constexpr uint16_t kDeviceTypeObject = protocol::od::kDeviceType;
inline constexpr uint16_t kIdentityObject = protocol::od::kIdentity;
inline constexpr uint32_t kCia402Profile = 402;  // the device type's low 16 bits on a joint

struct NodeIdentity {
  bool read = false;
  uint32_t device_type = 0;
  uint32_t vendor_id = 0;
  uint32_t product_code = 0;
  uint32_t revision = 0;
  uint32_t serial = 0;
};

// Whether `device_type` is what node index i must be.
constexpr bool expected_device_type(int i, uint32_t device_type) {
  const uint32_t profile = device_type & 0xFFFFu;
  return i == kCameraIndex ? profile == 0 : profile == kCia402Profile;
}

// Reads 0x1000 and 0x1018.1–4 of every node into `out`; false on the first node that does not
// answer, refuses, or has another device type (fault raised; for kWrongDevice the counters'
// config_node and config_read hold the node and its device type).
bool read_node_identities(CanOpenMaster& master, NodeIdentity out[kArmNodes]);

}  // namespace curio::app
