// End to end through the curio-train binary at toy size: train → report → export, a
// killed-and-resumed run, and the exported file against the LibTorch encoder it came from.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "host_tools/model_io/float_encoder.hpp"
#include "host_tools/model_io/float_model.hpp"
#include "host_tools/model_io/model_meta.hpp"
#include "sim/render.hpp"
#include "host_tools/vae/scene_set.hpp"
#include "host_tools/vae/evaluate.hpp"
#include "host_tools/vae/latent_unmixing.hpp"
#include "host_tools/vae/checkpoint.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kWork = fs::path(CURIO_TEST_WORK_DIR) / "train_smoke";

int curio_train(const std::string& args) {
  const std::string cmd = std::string(CURIO_TRAIN_BINARY) + " " + args + " >> " +
                          (kWork / "log.txt").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct CsvRow {
  long iteration;
  double loss;
};

std::vector<CsvRow> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string a, b;
    std::getline(ss, a, ',');
    std::getline(ss, b, ',');
    rows.push_back({std::stol(a), std::stod(b)});
  }
  return rows;
}

const std::string kToy =
    " --batch 16 --dataset-size 1024 --threads 1 --log-every 20 --eval-images 200";

class TrainerSmoke : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fs::remove_all(kWork);
    fs::create_directories(kWork);
    vae_rc_ = curio_train("train --kind vae --lr 1e-3 --iterations 240 --eval-every 120"
                          " --checkpoint-every 120 --report-images 2000 --out " +
                          (kWork / "vae").string() + kToy);
    // A β-VAE killed after 60 iterations (its last checkpoint) and resumed to 100.
    const std::string bvae = " --kind beta-vae --warmup 30 --capacity-iters 40 --eval-every 0"
                             " --report-images 0 --checkpoint-every 30 --out " +
                             (kWork / "bvae").string() + kToy;
    first_rc_ = curio_train("train --iterations 60" + bvae);
    again_rc_ = curio_train("train --iterations 60" + bvae);  // no --resume: must refuse
    resume_rc_ = curio_train("train --iterations 100 --resume" + bvae);
    // The same checkpoint with one byte flipped (a bad zip CRC loads as NaN weights): refused.
    fs::copy(kWork / "bvae", kWork / "damaged", fs::copy_options::recursive);
    {
      std::fstream f(kWork / "damaged" / "checkpoint.pt", std::ios::in | std::ios::out |
                                                             std::ios::binary);
      f.seekg(static_cast<std::streamoff>(fs::file_size(kWork / "damaged" / "checkpoint.pt") / 2));
      const char c = static_cast<char>(f.get());
      f.seekp(static_cast<std::streamoff>(fs::file_size(kWork / "damaged" / "checkpoint.pt") / 2));
      f.put(static_cast<char>(c ^ 0x40));
    }
    damaged_before_ = fs::last_write_time(kWork / "damaged" / "checkpoint.pt");
    damaged_rc_ = curio_train("train --iterations 120 --resume --kind beta-vae --out " +
                              (kWork / "damaged").string() + kToy);
    // A learning rate that blows the loss up: stopped, non-zero, the last checkpoint kept.
    nan_rc_ = curio_train("train --kind beta-vae --iterations 200 --lr 1e12 --checkpoint-every 1"
                          " --eval-every 0 --report-images 0 --out " +
                          (kWork / "nan").string() + kToy);
    report_rc_ = curio_train("report --images 2000 --checkpoint " + (kWork / "vae").string());
    export_rc_ = curio_train("export --name vae --kl-images 300 --made-by 'a smoke test'"
                             " --checkpoint " +
                             (kWork / "vae").string() + " --out " + (kWork / "models").string());
    // The trials' re-alignment tools on the trained VAE: FastICA unmixing, then a run on top of it
    // that holds the active latents' read-out and recycles dormant units with live outgoing
    // weights. --checkpoint and --init-from take a checkpoint file or the folder holding it.
    unmix_rc_ = curio_train("unmix --images 300 --checkpoint " +
                            (kWork / "vae" / "checkpoint.pt").string() +
                            " --out " + (kWork / "unmixed").string());
    frozen_rc_ = curio_train(
        "train --kind beta-vae --iterations 20 --eval-every 0 --report-images 0 --init-from " +
        (kWork / "unmixed").string() +
        " --freeze-active-readout --recycle-every 10 --recycle-decoder-too"
        " --recycle-outgoing-scale 0.3 --ball-spread 0 --ball-spread-to 1 --ball-spread-iters 16"
        " --out " + (kWork / "frozen").string() + kToy);
    frozen_bad_rc_ = curio_train("train --kind beta-vae --iterations 5 --freeze-active-readout"
                                 " --out " + (kWork / "frozen_bad").string() + kToy);
  }
  static inline int vae_rc_, first_rc_, again_rc_, resume_rc_, report_rc_, export_rc_, unmix_rc_,
      frozen_rc_, frozen_bad_rc_, damaged_rc_, nan_rc_;
  static inline fs::file_time_type damaged_before_;
};

std::string log_text() {
  std::ifstream f(kWork / "log.txt");
  return {std::istreambuf_iterator<char>(f), {}};
}

TEST_F(TrainerSmoke, ADamagedCheckpointIsRefusedAndLeftAsItIs) {
  EXPECT_EQ(damaged_rc_, 1);
  EXPECT_NE(log_text().find("damaged checkpoint"), std::string::npos);
  EXPECT_EQ(fs::last_write_time(kWork / "damaged" / "checkpoint.pt"), damaged_before_);
  curio::train::Vae model;
  EXPECT_THROW(curio::train::load_checkpoint((kWork / "damaged" / "checkpoint.pt").string(), model,
                                             nullptr),
               std::runtime_error);
  // The intact one beside it is vouched for by its .crc.
  EXPECT_TRUE(curio::train::load_checkpoint((kWork / "bvae" / "checkpoint.pt").string(), model,
                                            nullptr)
                  .verified);
}

TEST_F(TrainerSmoke, ANonFiniteLossStopsTrainingAndKeepsTheLastGoodCheckpoint) {
  EXPECT_EQ(nan_rc_, 1);
  const std::string log = log_text();
  EXPECT_TRUE(log.find("the loss is not finite") != std::string::npos ||
              log.find("the weights are not finite") != std::string::npos);
  if (!fs::exists(kWork / "nan" / "checkpoint.pt")) return;  // it blew up at once
  curio::train::Vae model;
  const auto info =
      curio::train::load_checkpoint((kWork / "nan" / "checkpoint.pt").string(), model, nullptr);
  EXPECT_LT(info.iteration, 200);
  for (const auto& p : model->parameters())
    EXPECT_TRUE(torch::isfinite(p).all().item<bool>()) << "a checkpoint holds non-finite weights";
}

TEST_F(TrainerSmoke, FrozenReadOutOfActiveLatentsStaysExactAfterUnmixing) {
  using namespace curio::train;
  ASSERT_EQ(unmix_rc_, 0) << "see " << (kWork / "log.txt");
  ASSERT_EQ(frozen_rc_, 0) << "see " << (kWork / "log.txt");
  EXPECT_NE(frozen_bad_rc_, 0) << "--freeze-active-readout without --init-from was accepted";
  Vae init, after;
  load_checkpoint(checkpoint_path((kWork / "unmixed").string()), init, nullptr);
  load_checkpoint(checkpoint_path((kWork / "frozen").string()), after, nullptr);
  // The trainer picks the latents with KL > 0.5 on the first 512 training images (seed 1).
  const SceneSet set = render_scene_set(512, 1, kTrainStream, 1);
  torch::NoGradGuard g;
  auto [mu, logvar] = init->enc->forward(to_float(set.images));
  const auto kl = kl_per_latent(mu, logvar);
  int active = 0;
  for (int l = 0; l < kLatents; ++l) {
    if (kl[l].item<double>() <= 0.5) continue;
    ++active;
    for (int64_t row : {int64_t{l}, l + kLatents}) {
      EXPECT_TRUE(torch::equal(init->enc->fc_out->weight[row], after->enc->fc_out->weight[row]))
          << "row " << row;
      EXPECT_EQ(init->enc->fc_out->bias[row].item<float>(), after->enc->fc_out->bias[row].item<float>());
    }
  }
  EXPECT_GE(active, 2);
  EXPECT_FALSE(torch::equal(init->enc->fc1->weight, after->enc->fc1->weight));  // the rest trains
}

// The same run ramped the ball spread 0 → 1 over 16 iterations: the set was re-rendered at
// every 1/32 step it crossed and ended at SPEC §3's full range.
TEST_F(TrainerSmoke, BallSpreadRampReRendersUpToTheFullRange) {
  ASSERT_EQ(frozen_rc_, 0) << "see " << (kWork / "log.txt");
  std::ifstream in(kWork / "log.txt");
  std::string line, last;
  int renders = 0;
  while (std::getline(in, line))
    if (line.find("training images re-rendered with ball spread") != std::string::npos)
      ++renders, last = line;
  EXPECT_EQ(renders, 16);  // iterations 1..16 of 20, each 2/32 further
  EXPECT_NE(last.find("spread 1.0000"), std::string::npos) << last;
}

TEST_F(TrainerSmoke, TrainingWritesItsOutputsAndLowersTheLoss) {
  ASSERT_EQ(vae_rc_, 0) << "see " << (kWork / "log.txt");
  for (const char* f : {"checkpoint.pt", "training.csv", "recipe.json", "eval.jsonl",
                        "factor_report.json", "kl_per_latent.png", "traversal.png",
                        "reconstruction.png"})
    EXPECT_TRUE(fs::exists(kWork / "vae" / f)) << f;
  const auto rows = read_csv(kWork / "vae" / "training.csv");
  ASSERT_EQ(rows.size(), 12u);
  EXPECT_EQ(rows.back().iteration, 240);
  EXPECT_LT(rows.back().loss, 0.8 * rows.front().loss);
}

TEST_F(TrainerSmoke, FactorReportIsWellFormed) {
  EXPECT_TRUE(report_rc_ == 0 || report_rc_ == 1) << report_rc_;  // 1 = criteria not met
  std::ifstream in(kWork / "vae" / "factor_report.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("model"), "vae");
  EXPECT_EQ(j.at("images"), 2000);
  ASSERT_EQ(j.at("latents").size(), 10u);
  for (const auto& l : j.at("latents")) {
    EXPECT_GE(l.at("kl").get<double>(), 0.0);
    for (const auto& [factor, r] : l.at("corr").items()) EXPECT_LE(std::abs(r.get<double>()), 1.0);
  }
  const double mig = j.at("mig");
  EXPECT_GE(mig, 0.0);
  EXPECT_LE(mig, 1.0);
  EXPECT_TRUE(j.at("pass").is_boolean());
  EXPECT_EQ(j.at("pass").get<bool>(), report_rc_ == 0);
}

TEST_F(TrainerSmoke, KilledRunResumesFromItsCheckpoint) {
  ASSERT_EQ(first_rc_, 0);
  EXPECT_NE(again_rc_, 0) << "overwrote a checkpoint without --resume";
  ASSERT_EQ(resume_rc_, 0);
  const auto rows = read_csv(kWork / "bvae" / "training.csv");
  std::vector<long> its;
  for (const auto& r : rows) its.push_back(r.iteration);
  EXPECT_EQ(its, (std::vector<long>{20, 40, 60, 80, 100}));
  curio::train::Vae model;
  const auto info = curio::train::load_checkpoint(
      curio::train::checkpoint_path((kWork / "bvae").string()), model, nullptr);
  EXPECT_EQ(info.iteration, 100);
  EXPECT_EQ(info.recipe.model, "beta-vae");
  EXPECT_EQ(info.recipe.trial.warmup, 30);
}

TEST_F(TrainerSmoke, ExportedModelMatchesTheTrainedEncoder) {
  ASSERT_EQ(export_rc_, 0);
  const auto file = curio::model_io::read_float_model((kWork / "models" / "vae.cfm").string());
  curio::model_io::validate_encoder(file);
  EXPECT_NE(file.find("dec.deconv3.weight"), nullptr);
  const auto meta = curio::model_io::read_model_meta((kWork / "models" / "vae.meta.json").string());
  EXPECT_EQ(meta.model, "vae");
  EXPECT_EQ(meta.json.at("iteration"), 240);
  EXPECT_EQ(meta.json.at("made_by"), "a smoke test");

  curio::train::Vae model;
  curio::train::load_checkpoint(curio::train::checkpoint_path((kWork / "vae").string()), model,
                                nullptr);
  model->eval();
  curio::sim::Image img;
  curio::sim::render_scene({0.3, -0.4}, {-0.5, 0.6}, &img);
  // HWC → NCHW for LibTorch.
  const auto x = torch::from_blob(img.data(), {1, 64, 64, 3}, torch::kFloat32).permute({0, 3, 1, 2});
  torch::NoGradGuard no_grad;
  const auto mu = model->enc->forward(x.contiguous()).first.contiguous();
  const auto reference = curio::model_io::FloatEncoder(file).mu(img.data());
  for (int l = 0; l < 10; ++l)
    EXPECT_NEAR(reference[static_cast<size_t>(l)], mu.data_ptr<float>()[l], 1e-4) << "z" << l;
}

}  // namespace

namespace {

// Progressive latents: a held latent is exactly the prior (μ = 0, log σ² = 0, KL 0), stays so
// through an Adam step on a loss that would move it, and trains once released.
TEST(HeldLatents, StayAtThePriorThroughTrainingUntilReleased) {
  using namespace curio::train;
  torch::manual_seed(3);
  Vae model;
  model->kaiming_init(1.0);
  LatentMask held{};
  for (int l = 4; l < 10; ++l) held[static_cast<size_t>(l)] = true;
  model->hold_latents(held);
  EXPECT_EQ(model->held_latents(), held);
  torch::optim::Adam opt(model->parameters(), torch::optim::AdamOptions(1e-3));
  const auto x = torch::rand({8, 3, 64, 64});
  auto held_kl = [&] {
    torch::NoGradGuard g;
    auto [mu, logvar] = model->enc->forward(x);
    return kl_per_latent(mu, logvar);
  };
  for (int step = 0; step < 3; ++step) {
    auto [mu, logvar] = model->enc->forward(x);
    const auto z = mu + torch::randn_like(mu) * (0.5 * logvar).exp();
    const auto loss = torch::binary_cross_entropy_with_logits(model->dec->forward(z), x) -
                      0.01 * kl_per_latent(mu, logvar).sum();  // rewards KL: would grow every latent
    opt.zero_grad();
    loss.backward();
    model->mask_held_gradients(held);
    opt.step();
  }
  const auto kl = held_kl();
  for (int l = 4; l < 10; ++l) EXPECT_EQ(kl[l].item<float>(), 0.0f) << "latent " << l;
  EXPECT_GT(kl.narrow(0, 0, 4).min().item<float>(), 0.0f);
  EXPECT_EQ(model->dec->fc1->weight.narrow(1, 4, 6).abs().max().item<float>(), 0.0f);

  EXPECT_EQ(model->held_latents(), held);
  model->release_latents(held, 1.0);
  EXPECT_EQ(model->held_latents(), LatentMask{});
  const auto released = held_kl();
  for (int l = 4; l < 10; ++l) EXPECT_GT(released[l].item<float>(), 0.0f) << "latent " << l;
  EXPECT_GT(model->dec->fc1->weight.narrow(1, 4, 6).abs().max().item<float>(), 0.0f);
}

// The encoder freeze: frozen feature layers stay bit-identical through Adam steps (even after
// steps that built up momentum), enc.fc_out and the decoder keep learning; convs_only leaves
// fc1/fc2 training; with the decoder held too, only dec.fc1 learns on that side.
TEST(EncoderFreeze, FrozenLayersStayExactlyWhileTheRestTrains) {
  using namespace curio::train;
  struct Case {
    bool convs_only, decoder_too;
  };
  for (const Case c : {Case{false, false}, Case{true, false}, Case{false, true}}) {
    torch::manual_seed(5);
    Vae model;
    model->kaiming_init(1.0);
    torch::optim::Adam opt(model->parameters(), torch::optim::AdamOptions(1e-3));
    const auto x = torch::rand({8, 3, 64, 64});
    auto step = [&](bool freeze) {
      auto [mu, logvar] = model->enc->forward(x);
      const auto z = mu + torch::randn_like(mu) * (0.5 * logvar).exp();
      const auto loss = torch::binary_cross_entropy_with_logits(model->dec->forward(z), x) +
                        0.01 * kl_per_latent(mu, logvar).sum();
      opt.zero_grad();
      loss.backward();
      if (freeze) {
        model->drop_encoder_feature_gradients(c.convs_only);
        if (c.decoder_too) model->drop_decoder_feature_gradients();
      }
      opt.step();
    };
    for (int i = 0; i < 3; ++i) step(false);  // momentum in every layer first
    const auto conv0 = model->enc->conv0->weight.clone();
    const auto fc1 = model->enc->fc1->weight.clone();
    const auto fc_out = model->enc->fc_out->weight.clone();
    const auto dec_fc1 = model->dec->fc1->weight.clone();
    const auto dec_fc2 = model->dec->fc2->weight.clone();
    const auto deconv3 = model->dec->deconv3->weight.clone();
    for (int i = 0; i < 3; ++i) step(true);
    const auto tag = ::testing::Message() << "convs_only " << c.convs_only << " decoder_too "
                                          << c.decoder_too;
    EXPECT_TRUE(torch::equal(conv0, model->enc->conv0->weight)) << tag;
    EXPECT_EQ(torch::equal(fc1, model->enc->fc1->weight), !c.convs_only) << tag;
    EXPECT_FALSE(torch::equal(fc_out, model->enc->fc_out->weight)) << tag;
    EXPECT_FALSE(torch::equal(dec_fc1, model->dec->fc1->weight)) << tag;
    EXPECT_EQ(torch::equal(dec_fc2, model->dec->fc2->weight), c.decoder_too) << tag;
    EXPECT_EQ(torch::equal(deconv3, model->dec->deconv3->weight), c.decoder_too) << tag;
  }
}

// Dormant-unit recycling: a dead fc1 unit and a dead conv3 channel get fresh incoming weights
// and zero outgoing weights, so the encoder's output does not change at all.
TEST(Recycling, DeadEncoderUnitsGetFreshInputsAndNoOutputs) {
  using namespace curio::train;
  torch::manual_seed(11);
  Vae model;
  model->kaiming_init(1.0);
  {
    torch::NoGradGuard g;
    model->enc->fc1->weight[5].zero_();
    model->enc->fc1->bias[5].fill_(-1.0);
    model->enc->conv3->weight[7].zero_();
    model->enc->conv3->bias[7].fill_(-1.0);
  }
  const auto x = torch::rand({16, 3, 64, 64});
  torch::NoGradGuard g;
  const auto [mu0, logvar0] = model->enc->forward(x);
  const auto n = model->recycle_dormant_encoder_units(x, 0.0);  // exactly-dead units only
  EXPECT_GE(n[3], 1);  // (other units may happen to be dead on these images too)
  EXPECT_GE(n[4], 1);
  EXPECT_GT(model->enc->fc1->weight[5].abs().max().item<float>(), 0.0f);
  EXPECT_EQ(model->enc->fc1->bias[5].item<float>(), 0.0f);
  EXPECT_EQ(model->enc->fc2->weight.select(1, 5).abs().max().item<float>(), 0.0f);
  EXPECT_GT(model->enc->conv3->weight[7].abs().max().item<float>(), 0.0f);
  EXPECT_EQ(model->enc->fc1->weight.narrow(1, 7 * 16, 16).abs().max().item<float>(), 0.0f);
  const auto [mu1, logvar1] = model->enc->forward(x);
  EXPECT_TRUE(torch::equal(mu0, mu1));
  EXPECT_TRUE(torch::equal(logvar0, logvar1));
}

// Decoder recycling: a dead fc1 unit and a dead deconv1 channel get fresh incoming weights;
// with zero outgoing weights the decoder's output is unchanged, with outgoing_scale > 0 the
// next layer reads the fresh unit at once (a live path through recycled layers).
TEST(Recycling, DeadDecoderUnitsGetFreshInputsAndZeroOrLiveOutputs) {
  using namespace curio::train;
  for (const double outgoing : {0.0, 0.5}) {
    torch::manual_seed(17);
    Vae model;
    model->kaiming_init(1.0);
    {
      torch::NoGradGuard g;
      model->dec->fc1->weight[9].zero_();
      model->dec->fc1->bias[9].fill_(-1.0);
      model->dec->deconv1->weight.select(1, 4).zero_();  // [in, out, k, k]: out channel 4
      model->dec->deconv1->bias[4] = -1.0;
    }
    const auto z = torch::randn({16, kLatents});
    torch::NoGradGuard g;
    const auto before = model->dec->forward(z);
    const auto n = model->recycle_dormant_decoder_units(z, 0.0, outgoing);
    const std::string tag = "outgoing " + std::to_string(outgoing);
    EXPECT_GE(n[0], 1) << tag;
    EXPECT_GE(n[3], 1) << tag;
    EXPECT_GT(model->dec->fc1->weight[9].abs().max().item<float>(), 0.0f) << tag;
    EXPECT_EQ(model->dec->fc1->bias[9].item<float>(), 0.0f) << tag;
    EXPECT_GT(model->dec->deconv1->weight.select(1, 4).abs().max().item<float>(), 0.0f) << tag;
    const float out_fc1 = model->dec->fc2->weight.select(1, 9).abs().max().item<float>();
    const float out_deconv1 = model->dec->deconv2->weight[4].abs().max().item<float>();
    if (outgoing == 0.0) {
      EXPECT_EQ(out_fc1, 0.0f) << tag;
      EXPECT_EQ(out_deconv1, 0.0f) << tag;
      EXPECT_TRUE(torch::equal(before, model->dec->forward(z))) << tag;
    } else {
      EXPECT_GT(out_fc1, 0.0f) << tag;
      EXPECT_GT(out_deconv1, 0.0f) << tag;
    }
  }
}

// Revival keeps the active latents' read-out from every live unit, gives collapsed latents
// fresh read-out rows (recycled fc2 units get fresh outgoing columns into all latents).
TEST(Recycling, ReviveKeepsActiveLatentsAndFreshensCollapsedOnes) {
  using namespace curio::train;
  torch::manual_seed(19);
  Vae model;
  model->kaiming_init(1.0);
  LatentMask held{};
  for (int l = 2; l < kLatents; ++l) held[static_cast<size_t>(l)] = true;
  model->hold_latents(held);  // latents 2..9 sit at the prior (KL 0)
  {
    torch::NoGradGuard g;
    model->enc->fc_out->bias.narrow(0, 0, 2).fill_(2.0);  // μ ≈ 2: latents 0 and 1 active
  }
  const auto x = torch::rand({16, 3, 64, 64});
  torch::Tensor live;  // fc2 units active on x: revival leaves their fc_out columns alone
  {
    torch::NoGradGuard g;
    auto h = x;
    for (auto* c : {&model->enc->conv0, &model->enc->conv1, &model->enc->conv2,
                    &model->enc->conv3})
      h = torch::relu((*c)(h));
    h = torch::relu(model->enc->fc1(h.flatten(1)));
    h = torch::relu(model->enc->fc2(h));
    live = (h.mean(0) > 0).nonzero().flatten();
  }
  const auto active_rows = model->enc->fc_out->weight.narrow(0, 0, 2).index_select(1, live);
  std::array<int, 11> counts{};
  const LatentMask revived = model->revive(x, 0.0, 0.3, 0.5, 0.1, false, counts);
  EXPECT_FALSE(revived[0]);
  EXPECT_FALSE(revived[1]);
  for (int l = 2; l < kLatents; ++l) {
    EXPECT_TRUE(revived[static_cast<size_t>(l)]) << l;
    EXPECT_GT(model->enc->fc_out->weight[l].abs().max().item<float>(), 0.0f) << l;
  }
  EXPECT_TRUE(torch::equal(active_rows,
                           model->enc->fc_out->weight.narrow(0, 0, 2).index_select(1, live)));
}

// FastICA recovers independent uniform sources from a linear mixture (up to order and sign).
TEST(LatentUnmixing, FastIcaSeparatesAMixtureOfUniformSources) {
  using namespace curio::train;
  torch::manual_seed(23);
  const auto opts = torch::TensorOptions().dtype(torch::kFloat64);
  const auto sources = torch::rand({20000, 4}, opts) * 2.0 - 1.0;
  const auto mixed = sources.matmul(torch::randn({4, 4}, opts));
  const auto centred = mixed - mixed.mean(0);
  auto [values, vectors] = torch::linalg_eigh(centred.t().matmul(centred) / 19999.0);
  const auto whitening = vectors.matmul(torch::diag(values.rsqrt())).matmul(vectors.t());
  const FastIcaResult r = fast_ica(centred.matmul(whitening), 5);
  ASSERT_TRUE(r.converged);
  const auto recovered = centred.matmul(whitening).matmul(r.unmixing.t());
  for (int64_t k = 0; k < 4; ++k) {
    double best = 0.0;
    for (int64_t j = 0; j < 4; ++j) {
      const auto c = torch::corrcoef(torch::stack({recovered.select(1, j), sources.select(1, k)}));
      best = std::max(best, std::abs(c[0][1].item<double>()));
    }
    EXPECT_GT(best, 0.99) << "source " << k;
  }
}

// Unmixing rewrites the μ path exactly: decoding the new μ gives the image decoding the old
// μ gave, and the unmixed active latents have zero mean and unit covariance.
TEST(LatentUnmixing, ReparameterisationKeepsTheDecodedImage) {
  using namespace curio::train;
  torch::manual_seed(29);
  Vae model;
  model->kaiming_init(1.0);
  model->eval();
  const auto x = torch::rand({400, 3, 64, 64});
  torch::NoGradGuard g;
  const auto before = torch::sigmoid(model->dec->forward(model->enc->forward(x).first));
  const auto images = (x * 255.0).round().to(torch::kUInt8);
  const UnmixResult u = unmix_active_latents(model, images, 3, 0.0);
  ASSERT_GE(u.active.size(), 2u);
  const auto mu = model->enc->forward(x).first;
  const auto after = torch::sigmoid(model->dec->forward(mu));
  EXPECT_LT((after - before).abs().max().item<double>(), 1e-3);
  const auto index = torch::tensor(std::vector<int64_t>(u.active.begin(), u.active.end()));
  const auto m = mu.index_select(1, index).to(torch::kFloat64);
  EXPECT_LT(m.mean(0).abs().max().item<double>(), 0.05);
  const auto c = m - m.mean(0);
  const auto cov = c.t().matmul(c) / static_cast<double>(m.size(0) - 1);
  EXPECT_LT((cov - torch::eye(m.size(1), torch::kFloat64)).abs().max().item<double>(), 0.05);
}

// The ball-spread curriculum scales only the ball's draws: the distractor of every scene is
// the one the full-range set has, and spread 0 puts the ball at the centre of every image.
TEST(SceneSetCurriculum, BallSpreadScalesOnlyTheBall) {
  using namespace curio::train;
  const SceneSet full = render_scene_set(64, 3, kTrainStream, 1);
  const SceneSet fixed = render_scene_set(64, 3, kTrainStream, 1, 0.0);
  const SceneSet narrow = render_scene_set(64, 3, kTrainStream, 1, 0.25);
  EXPECT_TRUE(torch::equal(fixed.factors.narrow(1, 2, 2), full.factors.narrow(1, 2, 2)));
  EXPECT_EQ(fixed.factors.narrow(1, 0, 2).abs().max().item<float>(), 0.0f);
  EXPECT_TRUE(torch::allclose(narrow.factors.narrow(1, 0, 2), full.factors.narrow(1, 0, 2) * 0.25));
  // Ball always at the centre: every fixed-ball image has its centre pixel lit in red.
  for (int64_t i = 0; i < 64; ++i) {
    const float d2 = full.factors[i][2].item<float>() * full.factors[i][2].item<float>() +
                     full.factors[i][3].item<float>() * full.factors[i][3].item<float>();
    if (d2 < 0.2f * 0.2f) continue;  // the distractor covers the centre
    EXPECT_GT(fixed.images[i][0][32][32].item<uint8_t>(), 200) << i;
  }
}

// Pruning by reconstruction: a latent the decoder ignores costs nothing when set to the prior
// mean; one it reads costs something.
TEST(LatentImportance, ReconstructionCostIsZeroForALatentTheDecoderIgnores) {
  using namespace curio::train;
  torch::manual_seed(13);
  Vae model;
  model->kaiming_init(1.0);
  {
    torch::NoGradGuard g;
    model->dec->fc1->weight.select(1, 3).zero_();
  }
  const auto cost = model->reconstruction_cost_of_each_latent(torch::rand({8, 3, 64, 64}));
  EXPECT_EQ(cost[3], 0.0);
  int read = 0;
  for (int l = 0; l < kLatents; ++l)
    if (l != 3 && cost[static_cast<size_t>(l)] != 0.0) ++read;
  EXPECT_EQ(read, kLatents - 1);
}

// --init torch-default keeps LibTorch's own layer init (non-zero biases), kaiming zeroes the
// biases; both scale only the encoder's output layer by out_scale.
TEST(Init, TorchDefaultKeepsLayerInitAndScalesOnlyTheOutputLayer) {
  using namespace curio::train;
  torch::manual_seed(7);
  Vae plain;
  torch::manual_seed(7);
  Vae scaled;
  scaled->scale_encoder_output(0.01);
  EXPECT_TRUE(torch::allclose(scaled->enc->fc_out->weight, plain->enc->fc_out->weight * 0.01));
  EXPECT_TRUE(torch::equal(scaled->enc->fc1->weight, plain->enc->fc1->weight));
  EXPECT_GT(plain->enc->fc1->bias.abs().max().item<float>(), 0.0f);
  Vae kaiming;
  kaiming->kaiming_init(1.0);
  EXPECT_EQ(kaiming->enc->fc1->bias.abs().max().item<float>(), 0.0f);
}

}  // namespace
