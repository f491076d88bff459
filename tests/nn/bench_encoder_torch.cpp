// Int8 firmware encoder vs the same encoder in LibTorch fp32, same image, batch 1, one
// thread each; prints both latencies and the speed-up.
#include <benchmark/benchmark.h>
#include <torch/torch.h>

#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "tests/nn/bench_encoder_common.hpp"
#include "host_tools/experiment/batch_encode.hpp"
#include "host_tools/model_io/encoder_spec.hpp"
#include "host_tools/model_io/float_model.hpp"
#include "tests/nn/torch_encoder.hpp"

namespace curio::nn::bench {
namespace {

namespace mio = curio::model_io;

void BM_TorchEncoderFp32(benchmark::State& state) {
  torch::set_num_threads(1);
  static TorchEncoder encoder(mio::read_float_model(CURIO_NN_SYNTHETIC_MODEL));
  // HWC → NCHW, batch 1.
  const auto image = torch::from_blob(const_cast<float*>(scene_image().data()), {1, 64, 64, 3})
                         .permute({0, 3, 1, 2})
                         .contiguous();
  torch::NoGradGuard no_grad;
  for (auto _ : state) {
    auto out = encoder.net->forward(image);
    benchmark::DoNotOptimize(out.data_ptr<float>());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("batch 1, 1 thread, fp32");
}

// Batched: kBatch different frames per call. The int8 encoder one image after another
// (Encoder::encode_batch) on one thread, and split over two threads (lab::encode_frames);
// LibTorch on one [kBatch,3,64,64] tensor, one thread. Times are per call: the reporter
// divides by kBatch.
constexpr int kBatch = 64;

const std::vector<uint8_t>& batch_frames() {
  static const std::vector<uint8_t> frames = [] {
    std::vector<uint8_t> f;
    for (int i = 0; i < kBatch; ++i) {
      sim::Image img{};
      sim::render_scene({-0.9 + 1.8 * i / kBatch, 0.7 - 1.4 * i / kBatch}, {0.5, -0.5}, &img);
      const auto frame = quantize::to_camera_frame(img.data());
      f.insert(f.end(), frame.begin(), frame.end());
    }
    return f;
  }();
  return frames;
}

void BM_Int8EncoderBatch(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  static Encoder encoder(testing::synthetic_firmware_model());
  std::vector<float> mu(kBatch * kLatents);
  for (auto _ : state) {
    const bool ok = threads == 1
                        ? encoder.encode_batch(batch_frames().data(), kBatch, mu.data()) == Status::kOk
                        : lab::encode_frames(testing::synthetic_firmware_model(), batch_frames().data(), kBatch,
                                             threads, mu.data(), nullptr)
                              .empty();
    if (!ok) {
      state.SkipWithError("encode failed");
      break;
    }
    benchmark::DoNotOptimize(mu.data());
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
  state.SetLabel("batch " + std::to_string(kBatch) + ", " + std::to_string(threads) + " thread(s), " + simd_path());
}

void BM_TorchEncoderFp32Batch(benchmark::State& state) {
  torch::set_num_threads(1);
  static TorchEncoder encoder(mio::read_float_model(CURIO_NN_SYNTHETIC_MODEL));
  std::vector<float> pixels(batch_frames().size());
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<float>(batch_frames()[i]) / 255.0f;
  const auto images = torch::from_blob(pixels.data(), {kBatch, 64, 64, 3}).permute({0, 3, 1, 2}).contiguous();
  torch::NoGradGuard no_grad;
  for (auto _ : state) {
    auto out = encoder.net->forward(images);
    benchmark::DoNotOptimize(out.data_ptr<float>());
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
  state.SetLabel("batch " + std::to_string(kBatch) + ", 1 thread, fp32");
}

BENCHMARK(BM_Int8Encoder)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TorchEncoderFp32)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Int8EncoderBatch)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_TorchEncoderFp32Batch)->Unit(benchmark::kMicrosecond);

// Keeps each benchmark's time per iteration to print the ratio at the end.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      // With --benchmark_repetitions the median wins; otherwise the single run.
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (median ||
          (run.run_type == Run::RT_Iteration && !medians_.count(run.run_name.str()))) {
        const std::string key = run.run_name.str();
        times_[key] = {run.GetAdjustedRealTime(), run.GetAdjustedCPUTime()};
        if (median) medians_.insert(key);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  void Finalize() override {
    ConsoleReporter::Finalize();
    const auto a = times_.find("BM_Int8Encoder");
    const auto b = times_.find("BM_TorchEncoderFp32");
    if (a != times_.end() && b != times_.end() && a->second.first > 0 && a->second.second > 0) {
      std::printf(
          "per image: int8 %.1f us (CPU %.1f), LibTorch fp32 %.1f us (CPU %.1f): int8 is %.2fx "
          "faster (CPU time %.2fx)\n",
          a->second.first, a->second.second, b->second.first, b->second.second,
          b->second.first / a->second.first, b->second.second / a->second.second);
    }
    const auto b1 = times_.find("BM_Int8EncoderBatch/1/real_time");
    const auto b2 = times_.find("BM_Int8EncoderBatch/2/real_time");
    const auto bt = times_.find("BM_TorchEncoderFp32Batch");
    if (b1 != times_.end() && b2 != times_.end() && bt != times_.end()) {
      const double one = b1->second.first / kBatch, two = b2->second.first / kBatch,
                   torch = bt->second.first / kBatch;
      std::printf(
          "per image, batch %d: int8 %.1f us on 1 thread, %.1f us on 2 threads (wall, %.2fx); LibTorch fp32 "
          "%.1f us on 1 thread (its batch-1 figure above is its best per image here)\n",
          kBatch, one, two, one / two, torch);
    }
  }

 private:
  std::map<std::string, std::pair<double, double>> times_;  // real, CPU (reporter's unit: us)
  std::set<std::string> medians_;
};

}  // namespace
}  // namespace curio::nn::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  curio::nn::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
