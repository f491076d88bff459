// SHA-256, the header banner, and `check`: a header goes stale when its inputs change and
// counts as edited when its body changes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "host_tools/model_io/float_model.hpp"
#include "host_tools/model_io/model_meta.hpp"
#include "host_tools/quantize/header_emitter.hpp"
#include "host_tools/quantize/pipeline.hpp"
#include "host_tools/quantize/sha256.hpp"
#include "tests/nn/synthetic_model.hpp"

namespace curio::quantize {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(Sha256, KnownVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, IncrementalEqualsOneShot) {
  const std::string text(1000, 'x');
  Sha256 h;
  for (size_t i = 0; i < text.size(); i += 7) h.update(std::string_view(text).substr(i, 7));
  EXPECT_EQ(to_hex(h.finish()), sha256_hex(text));
}

TEST(Calibration, SettingsRoundTripThroughTheBanner) {
  CalibrationSettings c{250, 99, ActivationScales::kPerTensor};
  const CalibrationSettings back = parse_calibration(c.describe());
  EXPECT_EQ(back.images, 250);
  EXPECT_EQ(back.seed, 99u);
  EXPECT_EQ(back.scales, ActivationScales::kPerTensor);
  EXPECT_THROW(parse_calibration("images=10"), std::runtime_error);
  EXPECT_THROW(parse_calibration("images=10 seed=1 activations=fancy"), std::runtime_error);
}

class HeaderCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("curio_nn_header_check_" + std::to_string(::getpid()));
    model_ = nn::testing::write_synthetic_model(dir_.string(), "toy", 3);
    meta_ = model_io::meta_path_for(model_);
    header_ = (dir_ / "toy_weights.hpp").string();
    const CalibrationSettings calibration{20, 1, ActivationScales::kPerTensor};
    QuantizedFiles q = quantize_files(model_, meta_, calibration, [](const std::string&) {});
    HeaderSource src{"toy", "curio-quantize quantize --model toy.cfm", q.inputs_sha256,
                     calibration};
    text_ = emit_header(src, q.encoder, q.meta);
    write_file_atomically(header_, text_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  std::string model_, meta_, header_, text_;
};

TEST_F(HeaderCheck, FreshHeaderIsUpToDate) {
  const CheckResult r = check_header(header_, model_, meta_);
  EXPECT_TRUE(r.up_to_date) << r.message;
  EXPECT_THAT(text_, HasSubstr("// DO NOT EDIT"));
  EXPECT_THAT(text_, HasSubstr("namespace curio::nn::toy"));
  EXPECT_THAT(text_, HasSubstr("alignas(16) inline constexpr int8_t conv0_filter[1536]"));
  EXPECT_THAT(text_, HasSubstr("inline constexpr EncoderModel kEncoderModel"));
}

TEST_F(HeaderCheck, ChangedMetaMakesItStale) {
  model_io::ModelMeta meta = model_io::read_model_meta(meta_);
  meta.json["note"] = "retrained";
  model_io::write_model_meta(meta_, meta);
  const CheckResult r = check_header(header_, model_, meta_);
  EXPECT_FALSE(r.up_to_date);
  EXPECT_THAT(r.message, HasSubstr("stale"));
  EXPECT_THAT(r.message, HasSubstr("curio-quantize quantize --model toy.cfm"));
}

TEST_F(HeaderCheck, ChangedModelMakesItStale) {
  auto model = model_io::read_float_model(model_);
  model.tensors[0].data[0] += 1.0f;
  model_io::write_float_model(model_, model.tensors);
  EXPECT_FALSE(check_header(header_, model_, meta_).up_to_date);
}

TEST_F(HeaderCheck, HandEditIsDetected) {
  std::string edited = text_;
  edited.replace(edited.find("conv0_bias[32] = {") + 23, 1, "7");
  write_file_atomically(header_, edited);
  const CheckResult r = check_header(header_, model_, meta_);
  EXPECT_FALSE(r.up_to_date);
  EXPECT_THAT(r.message, HasSubstr("edited by hand"));
}

TEST_F(HeaderCheck, ModulesFollowTheKlOrder) {
  const auto meta = model_io::read_model_meta(meta_);
  const auto& o = meta.kl_order;
  EXPECT_THAT(text_, HasSubstr("kPairModules[5][2] = {{" + std::to_string(o[0]) + ", " +
                               std::to_string(o[1]) + "}, {" + std::to_string(o[2])));
  EXPECT_THAT(text_, HasSubstr("kSingleModules[10][1] = {{" + std::to_string(o[0]) + "}, {" +
                               std::to_string(o[1]) + "}"));
}

}  // namespace
}  // namespace curio::quantize
