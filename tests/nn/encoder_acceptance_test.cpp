// Acceptance of the committed int8 encoders (issue 3): on 1,000 rendered scenes the
// firmware encoder, running the committed weights header, stays within 0.05 of the float
// model's μ on every latent of every image, and orders the latents by KL as the float
// model does. Skips (with what to run) while firmware/nn/models/ holds no trained model.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "model_io/float_encoder.hpp"
#include "model_io/model_meta.hpp"
#include "nn/encoder_model.hpp"
#include "quantize/calibration.hpp"
#include "quantize/evaluation.hpp"
#include "quantize/pipeline.hpp"

#if CURIO_NN_HAVE_BETA_VAE
#include "nn/models/beta_vae_weights.hpp"
#endif
#if CURIO_NN_HAVE_VAE
#include "nn/models/vae_weights.hpp"
#endif

namespace curio::nn {
namespace {

namespace fs = std::filesystem;

constexpr int kTestImages = 1000;
constexpr uint64_t kTestSeed = 2024;  // not the calibration seed
constexpr double kMaxMuError = 0.05;
constexpr double kKlTieNats = 0.05;  // latents closer than this in KL may swap places

struct CompiledModel {
  const EncoderModel* model = nullptr;  // nullptr: header not compiled in
  const int* kl_order = nullptr;
};

void check_model(const std::string& name, const CompiledModel& compiled) {
  const fs::path dir = CURIO_NN_MODELS_DIR;
  const std::string cfm = (dir / (name + ".cfm")).string();
  const std::string meta_path = model_io::meta_path_for(cfm);
  const std::string header = (dir / (name + "_weights.hpp")).string();
  if (!fs::exists(cfm)) {
    GTEST_SKIP() << "no trained model " << cfm << " yet: export one with\n  curio-train export "
                 << "--model-dir <run> --out firmware/nn/models --name " << name
                 << "\nthen\n  curio-quantize quantize --model firmware/nn/models/" << name
                 << ".cfm";
  }
  ASSERT_TRUE(fs::exists(header)) << cfm << " has no header; run\n  curio-quantize quantize "
                                  << "--model firmware/nn/models/" << name << ".cfm";
  ASSERT_NE(compiled.model, nullptr) << header << " exists but this test was built without "
                                     << "it: re-run cmake so the build sees it";
  const quantize::CheckResult check = quantize::check_header(header, cfm, meta_path);
  ASSERT_TRUE(check.up_to_date) << check.message;

  const model_io::FloatModel model = model_io::read_float_model(cfm);
  const model_io::ModelMeta meta = model_io::read_model_meta(meta_path);
  for (size_t i = 0; i < kLatents; ++i) EXPECT_EQ(compiled.kl_order[i], meta.kl_order[i]);

  const model_io::FloatEncoder float_encoder(model);
  const auto images = quantize::render_scenes(kTestImages, kTestSeed);
  const quantize::Int8VsFloat r =
      quantize::compare_int8_to_float(float_encoder, *compiled.model, images);
  ASSERT_EQ(r.encoder_faults, 0);
  ASSERT_EQ(r.images, kTestImages);
  std::printf("%s: %d images, max|dmu| %.5f, mean|dmu| %.6f\n", name.c_str(), r.images,
              r.max_abs_mu_error, r.mean_abs_mu_error);
  std::printf("latent  max|dmu|  KL float  KL int8\n");
  for (size_t j = 0; j < kLatents; ++j) {
    std::printf("%6zu  %8.5f  %8.4f  %8.4f\n", j, r.max_abs_mu_error_per_latent[j], r.kl_float[j],
                r.kl_int8[j]);
  }
  EXPECT_LE(r.max_abs_mu_error, kMaxMuError);
  EXPECT_TRUE(quantize::same_kl_order(r.kl_float, r.kl_int8, kKlTieNats))
      << "the int8 encoder orders the latents by KL differently from the float model";
}

TEST(EncoderAcceptance, BetaVae) {
#if CURIO_NN_HAVE_BETA_VAE
  check_model("beta_vae", {&beta_vae::kEncoderModel, beta_vae::kKlOrder});
#else
  check_model("beta_vae", {});
#endif
}

TEST(EncoderAcceptance, Vae) {
#if CURIO_NN_HAVE_VAE
  check_model("vae", {&vae::kEncoderModel, vae::kKlOrder});
#else
  check_model("vae", {});
#endif
}

}  // namespace
}  // namespace curio::nn
