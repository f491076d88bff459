#include "firmware/protocol/isotp.hpp"

#include "firmware/protocol/bytes.hpp"

namespace curio::protocol {
namespace {

constexpr uint8_t kFsContinue = 0, kFsWait = 1, kFsOverflow = 2;
constexpr size_t kMaxSingleClassic = 7;
constexpr uint32_t kMaxFfDl12 = 4095;

bool on_link(const IsoTpLink& link, const CanFrame& f) {
  return f.id == link.rx_id && f.extended() == link.extended && !f.remote() && !f.error();
}

// Data length of our SF/FF/CF frames.
uint8_t tx_frame_len(const IsoTpLink& link) {
  if (!link.fd) return 8;
  const uint8_t dl = hal::fd_padded_len(link.tx_dl);
  return (dl < 8 || dl > hal::kFdMaxLen) ? uint8_t{8} : dl;
}

// Assembles PCI + payload into a frame padded to a valid length of at least 8 bytes.
void build(const IsoTpLink& link, const uint8_t* pci, size_t pci_len, const uint8_t* payload,
           size_t payload_len, CanFrame* out) {
  uint8_t bytes[hal::kFdMaxLen];
  for (size_t i = 0; i < pci_len; ++i) bytes[i] = pci[i];
  for (size_t i = 0; i < payload_len; ++i) bytes[pci_len + i] = payload[i];
  size_t len = pci_len + payload_len;
  while (len < 8) bytes[len++] = kIsoTpPadding;
  hal::make_frame(out, link.tx_id, link.extended, link.fd, bytes, len, kIsoTpPadding);
}

}  // namespace

const char* to_string(IsoTpStatus s) {
  switch (s) {
    case IsoTpStatus::kIdle:
      return "idle";
    case IsoTpStatus::kInProgress:
      return "in progress";
    case IsoTpStatus::kComplete:
      return "complete";
    case IsoTpStatus::kIgnored:
      return "ignored (not this link)";
    case IsoTpStatus::kSequenceError:
      return "consecutive frame out of order";
    case IsoTpStatus::kTruncated:
      return "truncated frame";
    case IsoTpStatus::kOversized:
      return "message larger than the buffer";
    case IsoTpStatus::kTimeout:
      return "timeout";
    case IsoTpStatus::kUnexpected:
      return "unexpected frame";
    case IsoTpStatus::kOverflowAbort:
      return "receiver reported overflow";
    case IsoTpStatus::kWaitLimit:
      return "too many WAIT flow controls";
    case IsoTpStatus::kBusy:
      return "busy";
    case IsoTpStatus::kBadArgument:
      return "bad argument";
  }
  return "?";
}

IsoTpFrameType isotp_frame_type(const CanFrame& f) {
  if (f.len == 0 || f.remote() || f.error()) return IsoTpFrameType::kInvalid;
  const uint8_t t = static_cast<uint8_t>(f.data[0] >> 4);
  return t <= 3 ? static_cast<IsoTpFrameType>(t) : IsoTpFrameType::kInvalid;
}

namespace {

void count(IsoTpCounters& c, IsoTpStatus s) {
  switch (s) {
    case IsoTpStatus::kSequenceError:
      ++c.sequence_errors;
      break;
    case IsoTpStatus::kTruncated:
      ++c.truncated;
      break;
    case IsoTpStatus::kOversized:
      ++c.oversized;
      break;
    case IsoTpStatus::kTimeout:
      ++c.timeouts;
      break;
    case IsoTpStatus::kUnexpected:
      ++c.unexpected;
      break;
    case IsoTpStatus::kOverflowAbort:
      ++c.overflow_aborts;
      break;
    case IsoTpStatus::kWaitLimit:
      ++c.wait_limits;
      break;
    case IsoTpStatus::kIgnored:
      ++c.ignored;
      break;
    default:
      break;
  }
}

}  // namespace

// ---------------------------------------------------------------- receiver

IsoTpReceiver::IsoTpReceiver(const IsoTpLink& link, uint8_t* buffer, size_t capacity)
    : link_(link), buffer_(buffer), capacity_(buffer ? capacity : 0) {}

void IsoTpReceiver::reset() {
  state_ = State::kIdle;
  size_ = received_ = 0;
}

IsoTpStatus IsoTpReceiver::fail(IsoTpStatus s) {
  count(counters_, s);
  state_ = State::kIdle;
  received_ = 0;
  return s;
}

void IsoTpReceiver::flow_control(uint8_t status, IsoTpReply* reply) {
  const uint8_t pci[3] = {static_cast<uint8_t>(0x30 | status), link_.block_size, link_.st_min};
  if (reply) {
    build(link_, pci, 3, nullptr, 0, &reply->frame);
    reply->valid = true;
  }
}

IsoTpStatus IsoTpReceiver::on_frame(const CanFrame& f, uint64_t now_us, IsoTpReply* reply) {
  if (reply) reply->valid = false;
  if (!on_link(link_, f)) {
    ++counters_.ignored;
    return IsoTpStatus::kIgnored;
  }
  switch (isotp_frame_type(f)) {
    case IsoTpFrameType::kSingle:
    case IsoTpFrameType::kFirst: {
      // A First/Single frame arriving mid-message aborts the one in progress (ISO 15765-2 9.8.3).
      if (state_ != State::kIdle) {
        ++counters_.unexpected;
        reset();
      }
      return isotp_frame_type(f) == IsoTpFrameType::kSingle ? on_single(f)
                                                            : on_first(f, now_us, reply);
    }
    case IsoTpFrameType::kConsecutive:
      return on_consecutive(f, now_us, reply);
    case IsoTpFrameType::kFlowControl:
    case IsoTpFrameType::kInvalid:
      break;
  }
  ++counters_.unexpected;  // ignored; a message in progress continues
  return IsoTpStatus::kUnexpected;
}

IsoTpStatus IsoTpReceiver::on_single(const CanFrame& f) {
  const uint8_t nibble = f.data[0] & 0x0F;
  size_t len = 0, offset = 0;
  if (f.len <= 8) {
    if (nibble == 0) return fail(IsoTpStatus::kUnexpected);  // escape needs CAN_DL > 8
    len = nibble;
    offset = 1;
  } else {
    if (nibble != 0) return fail(IsoTpStatus::kUnexpected);
    len = f.data[1];
    offset = 2;
    if (len == 0) return fail(IsoTpStatus::kUnexpected);
  }
  if (offset + len > f.len) return fail(IsoTpStatus::kTruncated);
  if (len > capacity_) return fail(IsoTpStatus::kOversized);
  for (size_t i = 0; i < len; ++i) buffer_[i] = f.data[offset + i];
  size_ = received_ = len;
  state_ = State::kIdle;
  ++counters_.completed;
  return IsoTpStatus::kComplete;
}

IsoTpStatus IsoTpReceiver::on_first(const CanFrame& f, uint64_t now_us, IsoTpReply* reply) {
  if (f.len < 8) return fail(IsoTpStatus::kTruncated);
  size_t len = static_cast<size_t>(((f.data[0] & 0x0F) << 8) | f.data[1]);
  size_t offset = 2;
  if (len == 0) {
    len = get_be32(f.data + 2);
    offset = 6;
    if (len <= kMaxFfDl12) return fail(IsoTpStatus::kUnexpected);  // escape only above 4095
  }
  // A message that fits a single frame must not come as FF (FF_DLmin).
  const size_t min_len = f.len == 8 ? 8 : static_cast<size_t>(f.len) - 1;
  if (len < min_len) return fail(IsoTpStatus::kUnexpected);
  if (len > capacity_) {
    flow_control(kFsOverflow, reply);
    return fail(IsoTpStatus::kOversized);
  }
  rx_dl_ = f.len;
  received_ = f.len - offset;
  for (size_t i = 0; i < received_; ++i) buffer_[i] = f.data[offset + i];
  size_ = len;
  next_sn_ = 1;
  last_us_ = now_us;
  if (held_) {
    state_ = State::kWaitHold;
    flow_control(kFsWait, reply);
    return IsoTpStatus::kInProgress;
  }
  state_ = State::kReceiving;
  block_left_ = link_.block_size;
  flow_control(kFsContinue, reply);
  return IsoTpStatus::kInProgress;
}

IsoTpStatus IsoTpReceiver::on_consecutive(const CanFrame& f, uint64_t now_us, IsoTpReply* reply) {
  if (state_ != State::kReceiving) {
    ++counters_.unexpected;
    return IsoTpStatus::kUnexpected;
  }
  if ((f.data[0] & 0x0F) != next_sn_) return fail(IsoTpStatus::kSequenceError);
  const size_t remaining = size_ - received_;
  const size_t per_frame = static_cast<size_t>(rx_dl_) - 1;
  size_t n = remaining;
  if (remaining > per_frame) {
    // Every CF but the last carries exactly RX_DL bytes.
    if (f.len < rx_dl_) return fail(IsoTpStatus::kTruncated);
    if (f.len > rx_dl_) return fail(IsoTpStatus::kUnexpected);
    n = per_frame;
  } else if (static_cast<size_t>(f.len) - 1 < remaining) {
    return fail(IsoTpStatus::kTruncated);
  }
  for (size_t i = 0; i < n; ++i) buffer_[received_ + i] = f.data[1 + i];
  received_ += n;
  next_sn_ = static_cast<uint8_t>((next_sn_ + 1) & 0x0F);
  last_us_ = now_us;
  if (received_ == size_) {
    state_ = State::kIdle;
    ++counters_.completed;
    return IsoTpStatus::kComplete;
  }
  if (link_.block_size != 0 && --block_left_ == 0) {
    block_left_ = link_.block_size;
    flow_control(kFsContinue, reply);
  }
  return IsoTpStatus::kInProgress;
}

IsoTpStatus IsoTpReceiver::poll(uint64_t now_us, IsoTpReply* reply) {
  if (reply) reply->valid = false;
  const uint64_t quiet = now_us > last_us_ ? now_us - last_us_ : 0;
  switch (state_) {
    case State::kIdle:
      return IsoTpStatus::kIdle;
    case State::kReceiving:
      if (quiet > link_.timeout_us) return fail(IsoTpStatus::kTimeout);
      return IsoTpStatus::kInProgress;
    case State::kWaitHold:
      if (!held_) {
        state_ = State::kReceiving;
        block_left_ = link_.block_size;
        last_us_ = now_us;
        flow_control(kFsContinue, reply);
      } else if (quiet >= link_.timeout_us / 2) {  // keep the sender's N_Bs from expiring
        last_us_ = now_us;
        flow_control(kFsWait, reply);
      }
      return IsoTpStatus::kInProgress;
  }
  return IsoTpStatus::kIdle;
}

// ---------------------------------------------------------------- sender

IsoTpSender::IsoTpSender(const IsoTpLink& link) : link_(link) {}

void IsoTpSender::abort() {
  state_ = State::kIdle;
}

IsoTpStatus IsoTpSender::fail(IsoTpStatus s) {
  count(counters_, s);
  state_ = State::kIdle;
  return s;
}

IsoTpStatus IsoTpSender::start(const uint8_t* data, size_t size, uint64_t now_us) {
  if (state_ != State::kIdle) return IsoTpStatus::kBusy;
  if (data == nullptr || size == 0 || ((size >> 16) >> 16) != 0) {  // FF_DL is 32-bit
    return IsoTpStatus::kBadArgument;
  }
  const uint8_t dl = tx_frame_len(link_);
  const size_t single_max = dl > 8 ? static_cast<size_t>(dl) - 2 : kMaxSingleClassic;
  data_ = data;
  size_ = size;
  sent_ = 0;
  sn_ = 1;
  waits_ = 0;
  next_us_ = now_us;
  state_ = size <= single_max ? State::kSendSingle : State::kSendFirst;
  return IsoTpStatus::kInProgress;
}

IsoTpStatus IsoTpSender::poll(uint64_t now_us, IsoTpReply* out) {
  out->valid = false;
  const uint8_t dl = tx_frame_len(link_);
  switch (state_) {
    case State::kIdle:
      return IsoTpStatus::kIdle;
    case State::kSendSingle: {
      uint8_t pci[2] = {static_cast<uint8_t>(size_), 0};
      size_t pci_len = 1;
      if (size_ > kMaxSingleClassic) {
        pci[0] = 0x00;
        pci[1] = static_cast<uint8_t>(size_);
        pci_len = 2;
      }
      build(link_, pci, pci_len, data_, size_, &out->frame);
      out->valid = true;
      state_ = State::kIdle;
      ++counters_.completed;
      return IsoTpStatus::kComplete;
    }
    case State::kSendFirst: {
      uint8_t pci[6] = {0x10, 0, 0, 0, 0, 0};
      size_t pci_len = 2;
      if (size_ <= kMaxFfDl12) {
        pci[0] = static_cast<uint8_t>(0x10 | (size_ >> 8));
        pci[1] = static_cast<uint8_t>(size_ & 0xFF);
      } else {
        put_be32(pci + 2, static_cast<uint32_t>(size_));
        pci_len = 6;
      }
      const size_t n = dl - pci_len;
      build(link_, pci, pci_len, data_, n, &out->frame);
      out->valid = true;
      sent_ = n;
      state_ = State::kWaitFlowControl;
      next_us_ = now_us + link_.timeout_us;
      return IsoTpStatus::kInProgress;
    }
    case State::kWaitFlowControl:
      if (now_us > next_us_) return fail(IsoTpStatus::kTimeout);
      return IsoTpStatus::kInProgress;
    case State::kSendConsecutive: {
      if (now_us < next_us_) return IsoTpStatus::kInProgress;  // STmin
      const uint8_t pci = static_cast<uint8_t>(0x20 | sn_);
      const size_t left = size_ - sent_;
      const size_t n = left < static_cast<size_t>(dl - 1) ? left : static_cast<size_t>(dl - 1);
      build(link_, &pci, 1, data_ + sent_, n, &out->frame);
      out->valid = true;
      sent_ += n;
      sn_ = static_cast<uint8_t>((sn_ + 1) & 0x0F);
      if (sent_ == size_) {
        state_ = State::kIdle;
        ++counters_.completed;
        return IsoTpStatus::kComplete;
      }
      if (block_size_ != 0 && --block_left_ == 0) {
        state_ = State::kWaitFlowControl;
        next_us_ = now_us + link_.timeout_us;
      } else {
        next_us_ = now_us + st_min_us_;
      }
      return IsoTpStatus::kInProgress;
    }
  }
  return IsoTpStatus::kIdle;
}

IsoTpStatus IsoTpSender::on_frame(const CanFrame& f, uint64_t now_us) {
  if (!on_link(link_, f)) {
    ++counters_.ignored;
    return IsoTpStatus::kIgnored;
  }
  if (isotp_frame_type(f) != IsoTpFrameType::kFlowControl || state_ != State::kWaitFlowControl) {
    ++counters_.unexpected;  // ignored; a message in progress continues
    return IsoTpStatus::kUnexpected;
  }
  if (f.len < 3) return fail(IsoTpStatus::kTruncated);
  switch (f.data[0] & 0x0F) {
    case kFsContinue:
      block_size_ = f.data[1];
      block_left_ = block_size_;
      st_min_us_ = st_min_us(f.data[2]);
      waits_ = 0;
      state_ = State::kSendConsecutive;
      next_us_ = now_us;
      return IsoTpStatus::kInProgress;
    case kFsWait:
      if (++waits_ > link_.max_wait_frames) return fail(IsoTpStatus::kWaitLimit);
      next_us_ = now_us + link_.timeout_us;
      return IsoTpStatus::kInProgress;
    case kFsOverflow:
      return fail(IsoTpStatus::kOverflowAbort);
    default:
      return fail(IsoTpStatus::kUnexpected);  // invalid flow status aborts (N_INVALID_FS)
  }
}

}  // namespace curio::protocol
