// Writes, as JSON on stdout, frames made by Curio's encoders together with the signal values
// they must carry. check_dbc.py decodes the frames with canmatrix and firmware/protocol/curio.dbc
// and compares: the DBC and the C++ codecs must describe the same bytes.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "firmware/protocol/arm_messages.hpp"
#include "firmware/protocol/arm_objects.hpp"
#include "firmware/protocol/canopen.hpp"
#include "firmware/protocol/cia402.hpp"

using namespace curio::protocol;
namespace od = curio::protocol::od;
using json = nlohmann::json;

namespace {

json frame_json(const CanFrame& f, json signals) {
  char hex[2 * 64 + 1] = {};
  for (size_t i = 0; i < f.len; ++i) std::snprintf(hex + 2 * i, 3, "%02X", f.data[i]);
  return {{"id", f.id},  {"extended", f.extended()},     {"fd", f.fd()}, {"len", f.len},
          {"data", hex}, {"signals", std::move(signals)}};
}

json position(int32_t counts) {
  return {{"raw", counts}, {"phys", counts_to_angle(counts)}};
}

}  // namespace

int main() {
  json frames = json::array();
  frames.push_back(
      frame_json(encode_nmt({NmtCommand::kStart, 0}), {{"NMT_Command", 1}, {"NMT_NodeId", 0}}));
  frames.push_back(frame_json(encode_nmt({NmtCommand::kResetCommunication, 5}),
                              {{"NMT_Command", 0x82}, {"NMT_NodeId", 5}}));
  frames.push_back(frame_json(encode_sync(17), {{"SYNC_Counter", 17}}));
  // The controller's heartbeat (node 127): what the joints' consumers watch.
  frames.push_back(frame_json(encode_heartbeat({od::kDefaultMasterNode, NmtState::kOperational}),
                              {{"NmtState", 5}, {"Toggle", 0}}));

  std::vector<uint8_t> nodes = {1, 2, 3, 4, 5, 6, 7, kCameraNode};
  for (uint8_t node : nodes) {
    const std::string name = node == kCameraNode ? "Camera" : "Joint" + std::to_string(node);
    Emergency e{node, 0x8611, 0x81, {1, 2, 3, 4, 0xFF}};
    frames.push_back(frame_json(encode_emcy(e), {{"EMCY_ErrorCode", 0x8611},
                                                 {"EMCY_ErrorRegister", 0x81},
                                                 {"EMCY_VendorData", 0xFF04030201ull}}));
    frames.push_back(frame_json(encode_heartbeat({node, NmtState::kPreOperational}),
                                {{"NmtState", 0x7F}, {"Toggle", 0}}));
    const SdoMessage down{SdoKind::kDownloadRequest, node, cia402::kModesOfOperation, 0, 8, 1};
    frames.push_back(frame_json(
        encode_sdo(down),
        {{"SDO_Command", 0x2F}, {"SDO_Index", 0x6060}, {"SDO_SubIndex", 0}, {"SDO_Data", 8}}));
    const SdoMessage up{
        SdoKind::kUploadResponse, node, cia402::kPositionActualValue, 0, 0xFFFFFF9Cu, 4};
    frames.push_back(frame_json(encode_sdo(up), {{"SDO_Command", 0x43},
                                                 {"SDO_Index", 0x6064},
                                                 {"SDO_SubIndex", 0},
                                                 {"SDO_Data", 0xFFFFFF9Cu}}));
    if (node == kCameraNode) continue;
    for (int32_t counts : {-3141593, 0, 2147483647, -2147483647 - 1, 1234567}) {
      frames.push_back(frame_json(encode_joint_command({node, cia402::kCwEnableOperation, counts}),
                                  {{"Controlword", 0x0F}, {"TargetPosition", position(counts)}}));
      frames.push_back(frame_json(encode_joint_feedback({node, 0x1637, counts}),
                                  {{"Statusword", 0x1637}, {"ActualPosition", position(counts)}}));
    }
  }
  frames.push_back(frame_json(encode_camera_capture({4000000001u}), {{"Episode", 4000000001u}}));
  const GroundTruth g{9666, true, 0.6000000000000001, -0.25, -0.95, 0.123456789012345};
  frames.push_back(frame_json(encode_ground_truth(g), {{"Episode", 9666},
                                                       {"BallGrasped", 1},
                                                       {"Reserved", 0},
                                                       {"BallX", g.ball_x},
                                                       {"BallY", g.ball_y},
                                                       {"DistractorX", g.distractor_x},
                                                       {"DistractorY", g.distractor_y}}));

  // The classic profile's five frames.
  CanFrame classic[kGroundTruthClassicFrames];
  encode_ground_truth(g, CanProfile::kClassic, classic);
  frames.push_back(frame_json(classic[0], {{"Episode", 9666}, {"BallGrasped", 1}, {"Reserved", 0}}));
  frames.push_back(frame_json(classic[1], {{"BallX", g.ball_x}}));
  frames.push_back(frame_json(classic[2], {{"BallY", g.ball_y}}));
  frames.push_back(frame_json(classic[3], {{"DistractorX", g.distractor_x}}));
  frames.push_back(frame_json(classic[4], {{"DistractorY", g.distractor_y}}));

  // ISO-TP: SF, FF (escape), CF and FC of the camera link, in both profiles. The first CF
  // starts after the FF's payload: 58 bytes (FD) or 2 (classic).
  std::vector<uint8_t> image(kCameraImageBytes);
  for (size_t i = 0; i < image.size(); ++i) image[i] = static_cast<uint8_t>(i);
  for (const CanProfile profile : {CanProfile::kFd, CanProfile::kClassic}) {
    IsoTpSender tx(camera_link_for_camera(profile));
    IsoTpReply out;
    tx.start(image.data(), 20, 0);
    tx.poll(0, &out);
    if (profile == CanProfile::kFd) {  // a classic SF holds 7 bytes: 20 is an FF there
      frames.push_back(
          frame_json(out.frame, {{"IsoTp_PciType", 0}, {"IsoTp_PciLow", 0}, {"IsoTp_Byte1", 20}}));
    } else {
      tx.abort();
      tx.start(image.data(), 5, 0);
      tx.poll(0, &out);
      frames.push_back(frame_json(
          out.frame, {{"IsoTp_PciType", 0}, {"IsoTp_PciLow", 5}, {"IsoTp_Byte1", image[0]}}));
    }
    tx.abort();
    tx.start(image.data(), image.size(), 0);
    tx.poll(0, &out);
    frames.push_back(
        frame_json(out.frame, {{"IsoTp_PciType", 1}, {"IsoTp_PciLow", 0}, {"IsoTp_Byte1", 0}}));
    std::vector<uint8_t> buf(kIsoTpMaxMessage);
    IsoTpReceiver rx(camera_link_for_controller(profile), buf.data(), buf.size());
    IsoTpReply fc;
    rx.on_frame(out.frame, 0, &fc);
    frames.push_back(frame_json(
        fc.frame, {{"FC_PciType", 3}, {"FC_FlowStatus", 0}, {"FC_BlockSize", 0}, {"FC_STmin", 0}}));
    tx.on_frame(fc.frame, 0);
    tx.poll(0, &out);
    const size_t first_cf_byte = profile == CanProfile::kFd ? 58 : 2;
    frames.push_back(frame_json(out.frame, {{"IsoTp_PciType", 2},
                                            {"IsoTp_PciLow", 1},
                                            {"IsoTp_Byte1", image[first_cf_byte]}}));
  }
  std::printf("%s\n", json{{"frames", frames}}.dump(1).c_str());
  return 0;
}
