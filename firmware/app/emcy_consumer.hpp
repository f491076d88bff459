// The master's EMCY consumer (CiA 301, like CANopenNode's CO_Emergency on the receiving side):
// every emergency with an error code is counted, remembered (node, code) and ends the attempt
// with the fault its code names: 0x8611 following error, 0x8130 a drive that lost the
// controller's heartbeat (life guard / heartbeat error), anything else an emergency. An 0x8130
// that arrives during a bring-up before the drives' consumers are configured for this
// controller is an earlier master's loss (a killed controller, then --resume): counted only.
#pragma once
#include <cstdint>

#include "firmware/app/app_status.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/canopen.hpp"

namespace curio::app {

class CanOpenMaster;

// The CiA 301/402 codes the controller names (the drives' side: arm_objects.hpp).
inline constexpr uint16_t kEmcyHeartbeatError = protocol::od::kEmcyHeartbeatLost;
inline constexpr uint16_t kEmcyFollowingErrorCode = protocol::od::kEmcyFollowingError;

// The fault an emergency's code raises.
constexpr Fault fault_of_emcy(uint16_t code) {
  return code == kEmcyFollowingErrorCode ? Fault::kFollowingError
         : code == kEmcyHeartbeatError   ? Fault::kMasterHeartbeatMissed
                                         : Fault::kEmergency;
}

class EmcyConsumer {
 public:
  explicit EmcyConsumer(CanOpenMaster* master) : master_(master) {}
  void on_emcy(const protocol::Emergency& e);

 private:
  CanOpenMaster* master_;
};

}  // namespace curio::app
