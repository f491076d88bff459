// Int8 encoder latency per image on one core, and the share of each layer.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "tests/nn/bench_encoder_common.hpp"
#include "firmware/nn/conv_s8.hpp"
#include "firmware/nn/fully_connected_s8.hpp"

namespace curio::nn::bench {
namespace {

BENCHMARK(BM_Int8Encoder)->Unit(benchmark::kMicrosecond);

// One conv layer of the encoder on its real shape (weights from the synthetic model).
void BM_ConvLayer(benchmark::State& state) {
  const auto i = static_cast<int32_t>(state.range(0));
  const QuantizedLayer& layer = testing::synthetic_firmware_model().conv[i];
  const Dims in = arena::conv_input_dims(i);
  const Dims out{1, conv_map_size(i + 1), conv_map_size(i + 1), kConvChannels};
  std::vector<int8_t> input(static_cast<size_t>(in.h * in.w * in.c));
  for (size_t k = 0; k < input.size(); ++k) input[k] = static_cast<int8_t>((k * 37) % 256 - 128);
  std::vector<int8_t> output(static_cast<size_t>(out.h * out.w * out.c));
  alignas(16) static int8_t scratch[arena::kScratchBytes];
  ConvParams p;
  p.input_offset = layer.input_offset;
  p.output_offset = layer.output_offset;
  p.stride = {kConvStride, kConvStride};
  p.padding = {kConvPad, kConvPad};
  p.activation = {layer.output_offset, 127};
  for (auto _ : state) {
    conv_s8({scratch, arena::kScratchBytes}, p, {layer.multiplier, layer.shift}, in, input.data(),
            arena::conv_filter_dims(i), layer.filter, layer.bias, out, output.data());
    benchmark::DoNotOptimize(output.data());
  }
  const int64_t macs = int64_t{out.h} * out.w * out.c * kKernelSize * kKernelSize * in.c;
  state.counters["MAC/s"] = benchmark::Counter(static_cast<double>(macs) * state.iterations(),
                                               benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ConvLayer)->DenseRange(0, kConvLayers - 1)->Unit(benchmark::kMicrosecond);

void BM_Fc1(benchmark::State& state) {
  const QuantizedLayer& layer = testing::synthetic_firmware_model().fc1;
  std::vector<int8_t> input(kFlatten, 3), output(kHidden);
  alignas(16) static int8_t scratch[arena::kScratchBytes];
  FcParams p;
  p.input_offset = layer.input_offset;
  p.output_offset = layer.output_offset;
  p.activation = {layer.output_offset, 127};
  for (auto _ : state) {
    fully_connected_s8({scratch, arena::kScratchBytes}, p, {layer.multiplier, layer.shift},
                       {1, kFlatten, kHidden}, input.data(), layer.filter, layer.bias,
                       output.data());
    benchmark::DoNotOptimize(output.data());
  }
}
BENCHMARK(BM_Fc1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace curio::nn::bench

BENCHMARK_MAIN();
