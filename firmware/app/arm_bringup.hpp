// Arm start-up: NMT, SDO configuration of all eight nodes, the CiA 402 enable sequence, and
// bringing the arm back after a fault.
#pragma once

#include "firmware/app/canopen_master.hpp"
#include "firmware/app/node_identity.hpp"

namespace curio::app {

// The controller's heartbeat on, NMT reset node (optional), boot-up, pre-operational, the
// nodes' identities (when `identities` is not null: start-up), configuration (heartbeats, the
// drives' safety objects of drive_config.hpp, CSP mode, interpolation period, capture content),
// NMT start, heartbeat consumer on, then every joint to "operation enabled" (fault reset where
// needed). false on the first fault (raised).
bool bring_up_arm(CanOpenMaster& master, bool reset_nodes, NodeIdentity* identities);

// After a fault: waits for the bus to come back and brings the arm up again (a rebooted node
// is re-initialised by the same sequence), within recovery_timeout_us (the hold time). false
// at once on a fatal fault (another master or arm on the bus).
bool recover_arm(CanOpenMaster& master);

}  // namespace curio::app
