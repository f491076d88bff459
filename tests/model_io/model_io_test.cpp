// The float model file and meta JSON: round trip, and clear errors on damaged files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "host_tools/model_io/float_model.hpp"
#include "host_tools/model_io/model_meta.hpp"

namespace curio::model_io {
namespace {

using ::testing::HasSubstr;

std::vector<FloatTensor> sample_tensors() {
  return {{"enc.conv0.bias", {2}, {1.5f, -2.0f}},
          {"w", {2, 3}, {1, 2, 3, 4, 5, 6}},
          {"scalar", {}, {42.0f}}};
}

std::string expect_parse_error(const std::string& bytes) {
  try {
    parse_float_model(bytes, "test.cfm");
  } catch (const ModelFormatError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for a damaged file";
  return {};
}

TEST(FloatModel, RoundTripsThroughAFile) {
  const auto path = std::filesystem::temp_directory_path() / "curio_nn_roundtrip.cfm";
  write_float_model(path.string(), sample_tensors());
  const FloatModel m = read_float_model(path.string());
  ASSERT_EQ(m.tensors.size(), 3u);
  EXPECT_EQ(m.tensors[1].name, "w");
  EXPECT_EQ(m.tensors[1].dims, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(m.tensors[1].data, (std::vector<float>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(m.tensors[2].dims.size(), 0u);
  EXPECT_EQ(m.find("scalar")->data[0], 42.0f);
  EXPECT_EQ(m.find("nope"), nullptr);
  std::filesystem::remove(path);
}

// The trainer's model files are replaced by rename (temp + fsync), never truncated
// in place: a reader that opened the old model (curio-lab loading weights while curio-train
// exports) reads it whole, and no temporary file is left beside it.
TEST(FloatModel, ReplacingAModelLeavesAnOpenReaderTheOldFileWhole) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "curio_nn_atomic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string model = (dir / "m.cfm").string(), meta = (dir / "m.meta.json").string();
  write_float_model(model, sample_tensors());
  ModelMeta m;
  m.model = "beta-vae";
  m.kl_per_latent = {0.0, 3.2, 0.01, 3.1, 0, 0, 3.3, 0, 3.15, 0};
  m.kl_order = kl_order_of(m.kl_per_latent);
  write_model_meta(meta, m);
  const auto slurp = [](std::ifstream& in) {
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  std::ifstream old_model(model, std::ios::binary), old_meta(meta);
  std::ifstream copy_model(model, std::ios::binary), copy_meta(meta);
  const std::string model_before = slurp(copy_model), meta_before = slurp(copy_meta);
  auto bigger = sample_tensors();
  bigger.push_back({"more", {1000}, std::vector<float>(1000, 7.0f)});
  write_float_model(model, bigger);
  m.json = {{"steps", 5}};
  write_model_meta(meta, m);
  EXPECT_EQ(slurp(old_model), model_before);
  EXPECT_EQ(slurp(old_meta), meta_before);
  EXPECT_EQ(read_float_model(model).tensors.size(), 4u);
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 2u) << "a temporary file was left";
  fs::remove_all(dir);
}

TEST(FloatModel, LayoutIsLittleEndianAsDocumented) {
  const std::string b = serialize_float_model({{"ab", {1}, {1.0f}}});
  const std::string want(
      "CURIOFM1"
      "\x01\x00\x00\x00"  // count
      "\x02\x00\x00\x00"
      "ab"                                // name
      "\x01\x00\x00\x00"                  // ndim
      "\x01\x00\x00\x00\x00\x00\x00\x00"  // dims
      "\x00\x00\x80\x3f",                 // 1.0f
      8 + 4 + 4 + 2 + 4 + 8 + 4);
  EXPECT_EQ(b, want);
}

TEST(FloatModel, RejectsBadMagic) {
  std::string b = serialize_float_model(sample_tensors());
  b[7] = '2';
  EXPECT_THAT(expect_parse_error(b), HasSubstr("bad magic"));
}

TEST(FloatModel, RejectsEveryTruncation) {
  const std::string b = serialize_float_model(sample_tensors());
  for (size_t n = 0; n < b.size(); ++n) {
    const std::string msg = expect_parse_error(b.substr(0, n));
    EXPECT_FALSE(msg.empty()) << "prefix of " << n << " bytes accepted";
  }
}

TEST(FloatModel, RejectsTrailingBytesAndHugeSizes) {
  std::string b = serialize_float_model(sample_tensors());
  EXPECT_THAT(expect_parse_error(b + "x"), HasSubstr("unexpected bytes"));
  std::string huge = b;
  huge[8] = '\xff';  // tensor count 255
  EXPECT_THAT(expect_parse_error(huge), HasSubstr("tensor count"));
  std::string bigdim = serialize_float_model({{"ab", {1}, {1.0f}}});
  bigdim[8 + 4 + 4 + 2 + 4 + 7] = '\x7f';  // dims[0] ~ 2^62
  EXPECT_THAT(expect_parse_error(bigdim), HasSubstr("needs more data"));
}

TEST(FloatModel, WriterRejectsInconsistentTensors) {
  EXPECT_THROW(serialize_float_model({{"a", {2, 2}, {1, 2, 3}}}), ModelFormatError);
  EXPECT_THROW(serialize_float_model({{"", {1}, {1}}}), ModelFormatError);
  EXPECT_THROW(serialize_float_model({{"a", {1}, {1}}, {"a", {1}, {1}}}), ModelFormatError);
}

TEST(FloatModel, RequireNamesMissingAndMisshapenTensors) {
  FloatModel m{sample_tensors()};
  EXPECT_EQ(m.require("w", {2, 3}).data.size(), 6u);
  try {
    m.require("enc.fc1.weight", {256, 512});
    FAIL();
  } catch (const ModelFormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing tensor 'enc.fc1.weight'"));
  }
  try {
    m.require("w", {3, 2});
    FAIL();
  } catch (const ModelFormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("wrong shape"));
    EXPECT_THAT(e.what(), HasSubstr("[2,3]"));
  }
}

TEST(FloatModel, MissingFileSaysSo) {
  EXPECT_THROW(read_float_model("/nonexistent/x.cfm"), ModelFormatError);
}

TEST(ModelMeta, RoundTripsAndKeepsExtraKeys) {
  const auto path = std::filesystem::temp_directory_path() / "curio_nn_meta.meta.json";
  ModelMeta m;
  m.model = "beta-vae";
  m.kl_per_latent = {0.0, 3.2, 0.01, 3.1, 0, 0, 3.3, 0, 3.15, 0};
  m.kl_order = kl_order_of(m.kl_per_latent);
  m.json = {{"steps", 1000}};
  write_model_meta(path.string(), m);
  const ModelMeta r = read_model_meta(path.string());
  EXPECT_EQ(r.model, "beta-vae");
  EXPECT_EQ(r.kl_order, (std::array<int, 10>{6, 1, 8, 3, 2, 0, 4, 5, 7, 9}));
  EXPECT_EQ(r.json["steps"], 1000);
  std::filesystem::remove(path);
}

TEST(ModelMeta, RejectsInconsistentOrder) {
  const std::string base = R"({"model":"vae","kl_per_latent":[1,2,3,4,5,6,7,8,9,10],"kl_order":)";
  EXPECT_NO_THROW(parse_model_meta(base + "[9,8,7,6,5,4,3,2,1,0]}", "m"));
  EXPECT_THROW(parse_model_meta(base + "[0,1,2,3,4,5,6,7,8,9]}", "m"), ModelFormatError);
  EXPECT_THROW(parse_model_meta(base + "[9,9,7,6,5,4,3,2,1,0]}", "m"), ModelFormatError);
  EXPECT_THROW(parse_model_meta(base + "[9,8]}", "m"), ModelFormatError);
  EXPECT_THROW(parse_model_meta("{", "m"), ModelFormatError);
  EXPECT_THROW(parse_model_meta(R"({"model":"gan"})", "m"), ModelFormatError);
}

TEST(ModelMeta, MetaPathSitsBesideTheModel) {
  EXPECT_EQ(meta_path_for("firmware/nn/models/beta_vae.cfm"),
            "firmware/nn/models/beta_vae.meta.json");
  EXPECT_EQ(meta_path_for("a.b/model"), "a.b/model.meta.json");
}

}  // namespace
}  // namespace curio::model_io
