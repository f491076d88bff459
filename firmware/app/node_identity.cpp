// Every node's CiA 301 identity, checked and kept.
#include "firmware/app/node_identity.hpp"

#include "firmware/app/canopen_master.hpp"

namespace curio::app {

using namespace protocol;

bool read_node_identities(CanOpenMaster& master, NodeIdentity out[kArmNodes]) {
  SdoClient& sdo = master.sdo();
  for (int i = 0; i < kArmNodes; ++i) {
    if (!master.node_on_bus(i)) continue;
    const uint8_t node = node_id(i);
    NodeIdentity id;
    if (!sdo.transfer(node, SdoKind::kUploadRequest, kDeviceTypeObject, 0, 0, 0, &id.device_type))
      return false;
    if (!expected_device_type(i, id.device_type)) {
      ControllerCounters& c = master.counters();
      c.config_node = node;
      c.config_index = kDeviceTypeObject;
      c.config_sub = 0;
      c.config_read = id.device_type;
      master.raise(Fault::kWrongDevice, node);
      return false;
    }
    uint32_t* fields[4] = {&id.vendor_id, &id.product_code, &id.revision, &id.serial};
    for (uint8_t sub = 1; sub <= 4; ++sub)
      if (!sdo.transfer(node, SdoKind::kUploadRequest, kIdentityObject, sub, 0, 0, fields[sub - 1]))
        return false;
    id.read = true;
    out[i] = id;
  }
  return true;
}

}  // namespace curio::app
