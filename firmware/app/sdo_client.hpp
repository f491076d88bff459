// The master's SDO client (CiA 301 expedited transfers): one transfer to a node, or the same one
// to every joint at once, and the check that each request is answered once. Like CANopenNode's
// CO_SDOclient, one service in its own file; the CanOpenMaster dispatches SDO responses here.
#pragma once
#include <cstdint>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/canopen.hpp"

namespace curio::app {

class CanOpenMaster;

// Nodes by index: 0..6 the joints, 7 the camera.
inline constexpr int kArmNodes = protocol::kJointNodes + 1;
inline constexpr int kCameraIndex = protocol::kJointNodes;
constexpr uint8_t node_id(int index) {
  return index == kCameraIndex ? protocol::kCameraNode
                               : static_cast<uint8_t>(protocol::kFirstJointNode + index);
}
// -1 for a node that is not the arm's.
constexpr int node_index(uint8_t node) {
  if (protocol::is_joint_node(node)) return node - protocol::kFirstJointNode;
  if (node == protocol::kCameraNode) return kCameraIndex;
  return -1;
}

class SdoClient {
 public:
  explicit SdoClient(CanOpenMaster* master) : master_(master) {}

  // One expedited transfer to `node`; false (fault raised: kSdoTimeout, kSdoAbort) when it was
  // not answered in sdo_timeout_us or was aborted. `read` receives an upload's value.
  bool transfer(uint8_t node, protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                uint8_t size, uint32_t* read = nullptr);
  // The same transfer to every joint in one batch, then all answers; joint_value(j) is joint
  // j's. With `answered_mask` (bit j: joint j answered without abort) a joint that does not
  // answer or aborts raises no fault (the controlled stop goes on with the others).
  bool transfer_all_joints(protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                           uint8_t size, uint8_t* answered_mask = nullptr);
  uint32_t joint_value(int j) const { return pending_[j].value; }  // an abort's code too
  bool joint_aborted(int j) const { return pending_[j].done && pending_[j].aborted; }

  // The last transfer that failed: its object, and the abort code (0 for a timeout).
  uint16_t failed_index() const { return failed_index_; }
  uint8_t failed_sub() const { return failed_sub_; }
  uint32_t failed_abort_code() const { return failed_abort_; }

  // Each attempt re-arms the duplicate-answer check of nodes whose transfer timed out (a late
  // answer to the timed-out request is not a second node).
  void begin_attempt() {
    for (bool& t : timed_out_) t = false;
  }

  // The dispatcher's SDO response; false when no transfer of ours waits for it.
  bool on_response(const protocol::SdoMessage& m);
  // Every pending transfer answered (the pump's wait).
  bool all_answered() const;

 private:
  struct Pending {
    bool active = false;
    bool done = false;
    bool aborted = false;
    bool upload = false;
    uint16_t index = 0;
    uint8_t sub = 0;
    uint32_t value = 0;
    // m answers this transfer's request: same object, the response kind the request asks for.
    bool is_answer(const protocol::SdoMessage& m) const;
  };
  void begin_transfers();  // keeps the answered transfers in answered_, clears pending_
  hal::CanFrame request(int i, protocol::SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                        uint8_t size);
  void failed(const Pending& p);

  CanOpenMaster* master_;
  Pending pending_[kArmNodes];  // stay active after the answer: a second answer is a duplicate
  // Each node's last answered transfer, kept when the master moves on: a second node with the
  // same id that answers late (after our next request went out) is caught by it too.
  Pending answered_[kArmNodes];
  bool timed_out_[kArmNodes] = {};  // this attempt: a late answer may still come
  uint16_t failed_index_ = 0;
  uint8_t failed_sub_ = 0;
  uint32_t failed_abort_ = 0;
};

}  // namespace curio::app
