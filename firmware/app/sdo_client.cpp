// The master's SDO client: expedited transfers, one node or every joint at once.
#include "firmware/app/sdo_client.hpp"

#include "firmware/app/canopen_master.hpp"

namespace curio::app {

using hal::CanFrame;
using namespace protocol;

namespace {

// Every pending transfer answered.
class SdoWait final : public Wait {
 public:
  explicit SdoWait(const SdoClient& c) : c_(c) {}
  bool done() const override { return c_.all_answered(); }

 private:
  const SdoClient& c_;
};

}  // namespace

bool SdoClient::Pending::is_answer(const SdoMessage& m) const {
  const bool expected_kind =
      m.kind == SdoKind::kNodeAbort ||
      (upload ? m.kind == SdoKind::kUploadResponse : m.kind == SdoKind::kDownloadResponse);
  return active && index == m.index && sub == m.subindex && expected_kind;
}

bool SdoClient::all_answered() const {
  for (const Pending& p : pending_)
    if (p.active && !p.done) return false;
  return true;
}

void SdoClient::begin_transfers() {
  for (int i = 0; i < kArmNodes; ++i) {
    if (pending_[i].done) answered_[i] = pending_[i];
    pending_[i] = Pending{};
  }
}

void SdoClient::failed(const Pending& p) {
  failed_index_ = p.index;
  failed_sub_ = p.sub;
  failed_abort_ = p.aborted ? p.value : 0;
}

// false: no transfer of ours is waiting for this answer.
bool SdoClient::on_response(const SdoMessage& m) {
  const int i = node_index(m.node);
  if (i < 0) return false;
  Pending& p = pending_[i];
  const bool pending = p.is_answer(m);
  // A CANopen SDO server answers each request once: a second answer is a second node with
  // this id (two arms on one bus), unless our request timed out (its late answer). It may come
  // while the transfer is still ours, or, from a slower second node, after we moved on.
  const Pending& before = answered_[i];
  if (pending ? p.done : before.done && before.is_answer(m)) {
    ++master_->counters().duplicate_answers;
    if (!timed_out_[i]) master_->raise(Fault::kDuplicateNode, m.node);
    return false;
  }
  if (!pending) return false;
  p.done = true;
  p.aborted = m.kind == SdoKind::kNodeAbort;
  p.value = m.value;
  return true;
}

// Marks node i's transfer pending and returns its request frame.
CanFrame SdoClient::request(int i, SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                            uint8_t size) {
  Pending& p = pending_[i];
  p.active = true;
  p.upload = kind == SdoKind::kUploadRequest;
  p.index = index;
  p.sub = sub;
  return encode_sdo({kind, node_id(i), index, sub, value, size});
}

bool SdoClient::transfer(uint8_t node, SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                         uint8_t size, uint32_t* read) {
  const int i = node_index(node);
  if (i < 0) return false;  // not one of the arm's nodes: nothing to ask
  begin_transfers();
  Pending& p = pending_[i];
  const CanFrame f = request(i, kind, index, sub, value, size);
  if (!master_->send(&f, 1)) return false;
  SdoWait answered(*this);
  if (!master_->pump_until(answered, master_->bus().now_us() + master_->config().sdo_timeout_us)) {
    if (!p.done) {
      timed_out_[i] = true;
      failed(p);
    }
    master_->raise(Fault::kSdoTimeout, node);
    return false;
  }
  if (p.aborted) {
    failed(p);
    master_->raise(Fault::kSdoAbort, node);
    return false;
  }
  if (read != nullptr) *read = p.value;
  return true;
}

bool SdoClient::transfer_all_joints(SdoKind kind, uint16_t index, uint8_t sub, uint32_t value,
                                    uint8_t size, uint8_t* answered_mask) {
  CanFrame frames[kJointNodes];
  if (answered_mask != nullptr) *answered_mask = 0;
  begin_transfers();
  for (int j = 0; j < kJointNodes; ++j) frames[j] = request(j, kind, index, sub, value, size);
  if (!master_->send(frames, kJointNodes)) return false;
  SdoWait answered(*this);
  const bool all =
      master_->pump_until(answered, master_->bus().now_us() + master_->config().sdo_timeout_us);
  if (answered_mask != nullptr) {
    // Tolerant: report who answered; no fault for the others.
    uint8_t mask = 0;
    for (int j = 0; j < kJointNodes; ++j) {
      if (!pending_[j].done) timed_out_[j] = true;
      if (pending_[j].done && !pending_[j].aborted) mask = static_cast<uint8_t>(mask | (1u << j));
    }
    *answered_mask = mask;
    return mask == (1u << kJointNodes) - 1;
  }
  if (!all) {
    for (int j = 0; j < kJointNodes; ++j) {
      if (pending_[j].done) continue;
      timed_out_[j] = true;
      failed(pending_[j]);
      master_->raise(Fault::kSdoTimeout, node_id(j));
    }
    return false;
  }
  for (int j = 0; j < kJointNodes; ++j) {
    if (pending_[j].aborted) {
      failed(pending_[j]);
      master_->raise(Fault::kSdoAbort, node_id(j));
      return false;
    }
  }
  return true;
}

}  // namespace curio::app
