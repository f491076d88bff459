// The shipped β-VAE encoder (firmware/nn/models/beta_vae) in Curio's int8 kernels beside the
// int8 engines a PC user would pick, oneDNN (Intel's primitives, AVX-512 VNNI kernels) and
// XNNPACK (Google's, behind TFLite), and LibTorch fp32, in one process on the same frames:
// batch 1 and 64, one thread and two; µs per image, the time per layer at batch 1 on one
// thread, and how far each is from this core's vpdpbusd peak. Primitives are created and
// weights packed once, before any timing, as a user of each engine would.
//
// The same arithmetic where the engines allow it: every layer gets Curio's own input for that
// layer, and the bytes each engine writes are compared with Curio's. The engines' weights,
// biases and zero points are Curio's; their rescale is the float value of Curio's Q31
// multiplier and shift, applied in fp32 with round-half-to-even, where Curio rounds the exact
// Q31 product half away from zero: outputs can differ by one step where the exact value lies
// within an fp32 rounding of a half. oneDNN runs each activation as uint8 (q + 128, zero
// point 0: every zero point of this model is −128, so that is the same number and needs no
// zero-point attribute). The latent layer keeps int16 weights in Curio; both engines take
// int8 weights only, so they run an int8 stand-in of it (not compared).
//
// Usage: curio-bench-encoder-engines [--quick]   (--quick: fewer repetitions, for the tests)
#include <immintrin.h>
#include <omp.h>
#include <pthreadpool.h>
#include <xnnpack.h>
#include <dnnl.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "firmware/nn/encoder.hpp"
#include "firmware/nn/models/beta_vae_weights.hpp"
#include "host_tools/experiment/batch_encode.hpp"
#include "host_tools/model_io/float_model.hpp"
#include "host_tools/quantize/calibration.hpp"
#include "sim/render.hpp"
#include "tests/nn/torch_encoder.hpp"

namespace curio::nn::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kLayers = 7;  // conv0–3, fc1, fc2, latent
constexpr int kBigBatch = 64;
const char* const kLayerNames[kLayers] = {"conv0", "conv1", "conv2", "conv3",
                                          "fc1",   "fc2",   "latent"};
const EncoderModel& model() {
  return beta_vae::kEncoderModel;
}

int64_t layer_macs(int i) {
  if (i < kConvLayers) {
    return int64_t{conv_map_size(i + 1)} * conv_map_size(i + 1) * kConvChannels * kKernelSize *
           kKernelSize * conv_input_channels(i);
  }
  return i == 4 ? int64_t{kFlatten} * kHidden
                : (i == 5 ? int64_t{kHidden} * kHidden : int64_t{kHidden} * kLatentOutputs);
}
int64_t encoder_macs() {
  int64_t n = 0;
  for (int i = 0; i < kLayers; ++i) n += layer_macs(i);
  return n;
}
// Output values of layer i per image (int8; the latent layer's 20 sums).
int32_t layer_outputs(int i) {
  return i < kConvLayers ? arena::map_bytes(i + 1) : (i < 6 ? kHidden : kLatentOutputs);
}
int32_t layer_inputs(int i) {
  return i < kConvLayers ? arena::map_bytes(i) : (i == 4 ? kFlatten : kHidden);
}
const QuantizedLayer& qlayer(int i) {
  return i < kConvLayers ? model().conv[i] : (i == 4 ? model().fc1 : model().fc2);
}
// The rescale Curio applies, as a float: multiplier · 2^(shift − 31).
std::vector<float> rescales(int i) {
  const QuantizedLayer& l = qlayer(i);
  const int n = i < kConvLayers ? kConvChannels : kHidden;
  std::vector<float> s(static_cast<size_t>(n));
  for (int c = 0; c < n; ++c)
    s[static_cast<size_t>(c)] =
        static_cast<float>(std::ldexp(static_cast<double>(l.multiplier[c]), l.shift[c] - 31));
  return s;
}
// The latent layer's int16 weights rounded to int8 (the engines' stand-in), and its rescale.
std::vector<int8_t> latent_stand_in() {
  std::vector<int8_t> w(kLatentOutputs * kHidden);
  for (size_t k = 0; k < w.size(); ++k) {
    w[k] =
        static_cast<int8_t>(std::clamp(std::lround(model().latent.filter[k] / 128.0), -127L, 127L));
  }
  return w;
}

// Frames: a sweep of the ball over the table (one render each), as camera bytes.
std::vector<uint8_t> frames(int count) {
  std::vector<uint8_t> f;
  for (int i = 0; i < count; ++i) {
    sim::Image img{};
    sim::render_scene({-0.9 + 1.8 * i / count, 0.7 - 1.4 * i / count}, {0.5, -0.5}, &img);
    const auto frame = quantize::to_camera_frame(img.data());
    f.insert(f.end(), frame.begin(), frame.end());
  }
  return f;
}

// The process's CPU time in µs (all its threads): on a shared machine the wall time of a
// one-thread run also counts the time other processes held the core.
double cpu_us() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

// Medians over `reps` of the mean wall and CPU time of `iters` calls, in µs.
struct Timing {
  double wall, cpu;
};
Timing time_us(const std::function<void()>& run, int reps, int iters) {
  run();  // warm up
  std::vector<double> wall, cpu;
  for (int r = 0; r < reps; ++r) {
    const double c0 = cpu_us();
    const auto a = Clock::now();
    for (int i = 0; i < iters; ++i) run();
    wall.push_back(std::chrono::duration<double, std::micro>(Clock::now() - a).count() / iters);
    cpu.push_back((cpu_us() - c0) / iters);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], cpu[cpu.size() / 2]};
}

// Curio's outputs of every layer for one frame (layer i's input is layer i − 1's output; the
// image copy q = p − 128 enters layer 0).
struct CurioLayers {
  std::vector<int8_t> image;
  std::vector<int8_t> out[kLayers];
};
CurioLayers curio_layers(const uint8_t* frame) {
  static Encoder encoder(model());
  CurioLayers r;
  r.image.resize(kImageBytes);
  for (int k = 0; k < kImageBytes; ++k)
    r.image[static_cast<size_t>(k)] = static_cast<int8_t>(frame[k] - 128);
  auto probe = [](void* user, int32_t layer) {
    auto* self = static_cast<CurioLayers*>(user);
    if (layer < 0) return;
    const Encoder::LayerOutput o = encoder.layer_output(layer);
    const auto* p = static_cast<const int8_t*>(o.data);
    self->out[layer].assign(p, p + o.bytes);
  };
  encoder.set_layer_probe(probe, &r);
  float mu[kLatents];
  encoder.encode(frame, mu);
  encoder.set_layer_probe(nullptr, nullptr);
  return r;
}

// ---- oneDNN: u8 activations (q + 128), s8 weights, s32 bias, per-channel output scales.
struct OneDnn {
  dnnl::engine eng{dnnl::engine::kind::cpu, 0};
  dnnl::stream strm{eng};
  struct Layer {
    dnnl::primitive prim;
    dnnl::memory src, wei, bias, dst;
  };
  std::vector<Layer> layers;
  int batch;

  explicit OneDnn(int n) : batch(n) {
    using dt = dnnl::memory::data_type;
    using tag = dnnl::memory::format_tag;
    for (int i = 0; i < kLayers; ++i) {
      Layer L;
      dnnl::primitive_attr attr;
      const bool latent = i == 6;
      const int oc = i < kConvLayers ? kConvChannels : (latent ? kLatentOutputs : kHidden);
      if (!latent) attr.set_output_scales(1 << 1, rescales(i));
      const dnnl::memory::desc bias_md({oc}, dt::s32, tag::x);
      const int32_t* bias = latent ? model().latent.bias : qlayer(i).bias;
      if (i < kConvLayers) {
        const int s = conv_map_size(i), o = conv_map_size(i + 1), c = conv_input_channels(i);
        const dnnl::memory::desc src_md({n, c, s, s}, dt::u8, tag::nhwc);
        const dnnl::memory::desc wei_any({oc, c, kKernelSize, kKernelSize}, dt::s8, tag::any);
        const dnnl::memory::desc dst_md({n, oc, o, o}, dt::u8, tag::nhwc);
        const dnnl::convolution_forward::desc d(
            dnnl::prop_kind::forward_inference, dnnl::algorithm::convolution_direct, src_md,
            wei_any, bias_md, dst_md, {kConvStride, kConvStride}, {kConvPad, kConvPad},
            {kConvPad, kConvPad});
        const dnnl::convolution_forward::primitive_desc pd(d, attr, eng);
        L.prim = dnnl::convolution_forward(pd);
        L.src = dnnl::memory(src_md, eng);
        L.dst = dnnl::memory(dst_md, eng);
        L.wei = dnnl::memory(pd.weights_desc(), eng);
        dnnl::memory user({{oc, c, kKernelSize, kKernelSize}, dt::s8, tag::ohwi}, eng,
                          const_cast<int8_t*>(qlayer(i).filter));
        dnnl::reorder(user, L.wei).execute(strm, user, L.wei);
      } else {
        const int ic = i == 4 ? kFlatten : kHidden;
        const dnnl::memory::desc src_md({n, ic}, dt::u8, tag::nc);
        const dnnl::memory::desc wei_any({oc, ic}, dt::s8, tag::any);
        const dnnl::memory::desc dst_md({n, oc}, latent ? dt::s32 : dt::u8, tag::nc);
        const dnnl::inner_product_forward::desc d(dnnl::prop_kind::forward_inference, src_md,
                                                  wei_any, bias_md, dst_md);
        const dnnl::inner_product_forward::primitive_desc pd(d, attr, eng);
        L.prim = dnnl::inner_product_forward(pd);
        L.src = dnnl::memory(src_md, eng);
        L.dst = dnnl::memory(dst_md, eng);
        L.wei = dnnl::memory(pd.weights_desc(), eng);
        static const std::vector<int8_t> stand_in = latent_stand_in();
        dnnl::memory user({{oc, ic}, dt::s8, tag::oi}, eng,
                          const_cast<int8_t*>(latent ? stand_in.data() : qlayer(i).filter));
        dnnl::reorder(user, L.wei).execute(strm, user, L.wei);
      }
      L.bias = dnnl::memory(bias_md, eng, const_cast<int32_t*>(bias));
      layers.push_back(L);
    }
    // Each layer reads the previous layer's output buffer (the flatten is NHWC, as fc1's
    // columns are).
    for (int i = 1; i < kLayers; ++i)
      layers[static_cast<size_t>(i)].src = layers[static_cast<size_t>(i - 1)].dst;
    strm.wait();
  }
  void run_layer(int i) {
    Layer& L = layers[static_cast<size_t>(i)];
    L.prim.execute(strm, {{DNNL_ARG_SRC, L.src},
                          {DNNL_ARG_WEIGHTS, L.wei},
                          {DNNL_ARG_BIAS, L.bias},
                          {DNNL_ARG_DST, L.dst}});
    strm.wait();
  }
  // Camera bytes are already q + 128.
  void set_frames(const uint8_t* f) {
    std::memcpy(layers[0].src.get_data_handle(), f, static_cast<size_t>(batch) * kImageBytes);
  }
  void run() {
    for (int i = 0; i < kLayers; ++i) run_layer(i);
  }
};

// ---- XNNPACK: qs8 activations (zero point −128), qc8 (per-channel) convolutions; the FCs as
// 1×1 qc8 convolutions on a 1×1 map (its fully-connected operator has one weight scale per
// tensor), the latent stand-in as a qs8 fully-connected operator.
struct Xnn {
  pthreadpool_t pool = nullptr;
  xnn_operator_t ops[kLayers] = {};
  std::vector<int8_t> buf[kLayers + 1];
  int batch;

  Xnn(int n, int threads) : batch(n) {
    if (threads > 1) pool = pthreadpool_create(static_cast<size_t>(threads));
    for (int i = 0; i <= kLayers; ++i) {
      buf[i].assign(static_cast<size_t>(n) * (i == 0 ? kImageBytes : layer_outputs(i - 1)) + 64, 0);
    }
    for (int i = 0; i < kLayers; ++i) {
      xnn_status s;
      if (i < 6) {
        const bool conv = i < kConvLayers;
        const uint32_t k = conv ? kKernelSize : 1, st = conv ? kConvStride : 1,
                       pad = conv ? kConvPad : 0;
        const size_t ic =
            static_cast<size_t>(conv ? conv_input_channels(i) : (i == 4 ? kFlatten : kHidden));
        const size_t oc = conv ? kConvChannels : kHidden;
        const std::vector<float> scale = rescales(i);
        s = xnn_create_convolution2d_nhwc_qc8(pad, pad, pad, pad, k, k, st, st, 1, 1, 1, ic, oc, ic,
                                              oc, -128, 1.0f, scale.data(), qlayer(i).filter,
                                              qlayer(i).bias, -128, 1.0f, -128, 127, 0, &ops[i]);
        if (s == xnn_status_success) {
          const size_t hw = conv ? static_cast<size_t>(conv_map_size(i)) : 1;
          s = xnn_setup_convolution2d_nhwc_qc8(ops[i], static_cast<size_t>(n), hw, hw,
                                               buf[i].data(), buf[i + 1].data(), pool);
        }
      } else {
        static const std::vector<int8_t> stand_in = latent_stand_in();
        s = xnn_create_fully_connected_nc_qs8(kHidden, kLatentOutputs, kHidden, kLatentOutputs,
                                              -128, 1.0f, 1.0f / 128, stand_in.data(),
                                              model().latent.bias, 0, 1.0f, -128, 127, 0, &ops[i]);
        if (s == xnn_status_success) {
          s = xnn_setup_fully_connected_nc_qs8(ops[i], static_cast<size_t>(n), buf[i].data(),
                                               buf[i + 1].data(), pool);
        }
      }
      if (s != xnn_status_success) {
        std::fprintf(stderr, "curio-bench-encoder-engines: XNNPACK refused layer %s (status %d)\n",
                     kLayerNames[i], static_cast<int>(s));
        std::exit(1);
      }
    }
  }
  ~Xnn() {
    for (xnn_operator_t op : ops) xnn_delete_operator(op);
    if (pool != nullptr) pthreadpool_destroy(pool);
  }
  void run_layer(int i) { xnn_run_operator(ops[i], pool); }
  void set_frames(const uint8_t* f) {
    for (size_t k = 0; k < static_cast<size_t>(batch) * kImageBytes; ++k)
      buf[0][k] = static_cast<int8_t>(f[k] - 128);
  }
  void run() {
    for (int i = 0; i < kLayers; ++i) run_layer(i);
  }
};

// This core's peak of vpdpbusd on zmm registers (64 multiply-accumulates each): 24 independent
// accumulators in one asm loop, so neither latency nor the compiler's moves bound it.
// Multiply-accumulates per µs of CPU time (the best of 20 tries: other processes only lower it).
__attribute__((target("avx512f,avx512bw,avx512vnni"))) double vnni_peak_macs_per_us() {
  constexpr long kSteps = 1 << 15;
  constexpr int kChains = 24;
  double best = 0;
  for (int rep = 0; rep < 20; ++rep) {
    const double t0 = cpu_us();
    long n = kSteps;
#define CURIO_DP(i) "vpdpbusd %%zmm30, %%zmm31, %%zmm" #i "\n\t"
    __asm__ volatile(
        "vpternlogd $0xff, %%zmm30, %%zmm30, %%zmm30\n\t"
        "vpternlogd $0xff, %%zmm31, %%zmm31, %%zmm31\n\t"
        "1:\n\t" CURIO_DP(0) CURIO_DP(1) CURIO_DP(2) CURIO_DP(3) CURIO_DP(4) CURIO_DP(5) CURIO_DP(6) CURIO_DP(7)
            CURIO_DP(8) CURIO_DP(9) CURIO_DP(10) CURIO_DP(11) CURIO_DP(12) CURIO_DP(13) CURIO_DP(14) CURIO_DP(15)
                CURIO_DP(16) CURIO_DP(17) CURIO_DP(18) CURIO_DP(19) CURIO_DP(20) CURIO_DP(21) CURIO_DP(22)
                    CURIO_DP(23) "dec %0\n\t"
        "jnz 1b\n\t"
        : "+r"(n)
        :
        : "xmm0", "xmm1", "xmm2", "xmm3", "xmm4", "xmm5", "xmm6", "xmm7", "xmm8", "xmm9", "xmm10", "xmm11", "xmm12",
          "xmm13", "xmm14", "xmm15", "xmm16", "xmm17", "xmm18", "xmm19", "xmm20", "xmm21", "xmm22", "xmm23", "xmm30",
          "xmm31", "cc");
#undef CURIO_DP
    best = std::max(best, 64.0 * kChains * static_cast<double>(kSteps) / (cpu_us() - t0));
  }
  return best;
}

void set_threads(int t) {
  omp_set_num_threads(t);
  torch::set_num_threads(t);
}

int run(bool quick) {
  const int reps = quick ? 3 : 7;
  const std::vector<uint8_t> big = frames(kBigBatch);
  const uint8_t* one = big.data() + 17 * kImageBytes;
  // oneDNN runs activations as uint8 with zero point 0, the same numbers only where every
  // activation's zero point is −128 (as in the shipped model).
  for (int i = 0; i < 6; ++i) {
    if (qlayer(i).input_offset != 128 || qlayer(i).output_offset != -128) {
      std::fprintf(
          stderr,
          "curio-bench-encoder-engines: layer %s has a zero point other than -128; the oneDNN "
          "runner maps activations to uint8 and would not compute the same numbers\n",
          kLayerNames[i]);
      return 1;
    }
  }
  if (model().latent.input_offset != 128) {
    std::fprintf(stderr,
                 "curio-bench-encoder-engines: the latent layer's input zero point is not -128\n");
    return 1;
  }
  if (xnn_initialize(nullptr) != xnn_status_success) {
    std::fprintf(stderr, "curio-bench-encoder-engines: xnn_initialize failed\n");
    return 1;
  }
  std::printf(
      "int8 encoder (shipped beta_vae weights, %lld MACs per image) beside oneDNN %d.%d, XNNPACK "
      "and LibTorch fp32\n",
      static_cast<long long>(encoder_macs()), dnnl_version()->major, dnnl_version()->minor);
  std::printf("Curio's kernels take the %s path\n", simd_path());

  // ---- Agreement, layer by layer, on Curio's own inputs (batch 1).
  const CurioLayers ref = curio_layers(one);
  {
    set_threads(1);
    OneDnn dnn(1);
    Xnn xnn(1, 1);
    std::printf(
        "\nsame frame, each layer fed Curio's input for it: output bytes equal to Curio's\n");
    std::printf("  %-7s %8s %16s %16s\n", "layer", "values", "oneDNN", "XNNPACK");
    for (int i = 0; i < 6; ++i) {
      const std::vector<int8_t>& in = i == 0 ? ref.image : ref.out[i - 1];
      auto* dsrc = static_cast<uint8_t*>(dnn.layers[static_cast<size_t>(i)].src.get_data_handle());
      for (size_t k = 0; k < in.size(); ++k) dsrc[k] = static_cast<uint8_t>(in[k] + 128);
      dnn.run_layer(i);
      std::memcpy(xnn.buf[i].data(), in.data(), in.size());
      xnn.run_layer(i);
      const auto* dout =
          static_cast<const uint8_t*>(dnn.layers[static_cast<size_t>(i)].dst.get_data_handle());
      int same_d = 0, same_x = 0, off_d = 0, off_x = 0;
      const std::vector<int8_t>& want = ref.out[i];
      for (size_t k = 0; k < want.size(); ++k) {
        const int d = dout[k] - 128, x = xnn.buf[i + 1][k], w = want[k];
        same_d += d == w;
        same_x += x == w;
        off_d = std::max(off_d, std::abs(d - w));
        off_x = std::max(off_x, std::abs(x - w));
      }
      const double n = static_cast<double>(want.size());
      std::printf("  %-7s %8zu %7.3f%% (|d|<=%d) %7.3f%% (|d|<=%d)\n", kLayerNames[i], want.size(),
                  100.0 * same_d / n, off_d, 100.0 * same_x / n, off_x);
    }
    std::printf(
        "  latent  (Curio: int16 weights, int32 sums; the engines run an int8 stand-in: not "
        "compared)\n");
  }

  // ---- Speed.
  struct Row {
    std::string engine;
    int batch, threads;
    double wall, cpu;  // µs per image
  };
  auto row = [](const std::string& engine, int batch, int threads, Timing t) {
    return Row{engine, batch, threads, t.wall / batch, t.cpu / batch};
  };
  std::vector<Row> rows;
  double curio_layer_us[kLayers] = {}, dnn_layer_us[kLayers] = {}, xnn_layer_us[kLayers] = {};
  double dnn64_layer_us[kLayers] = {}, xnn64_layer_us[kLayers] = {};  // per image at batch 64
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  static Encoder encoder(model());
  const model_io::FloatModel float_model = model_io::read_float_model(CURIO_NN_BETA_VAE_MODEL);
  TorchEncoder torch_encoder(float_model);
  torch::NoGradGuard no_grad;
  std::vector<float> pixels(big.size());
  for (size_t k = 0; k < big.size(); ++k) pixels[k] = static_cast<float>(big[k]) / 255.0f;
  float mu[kBigBatch * kLatents];
  for (const int batch : {1, kBigBatch}) {
    const int iters1 = batch == 1 ? (quick ? 100 : 400) : (quick ? 2 : 6);
    for (const int threads : {1, 2}) {
      set_threads(threads);
      const uint8_t* f = batch == 1 ? one : big.data();
      // Curio: one encoder per thread; a single image is not split.
      Timing t;
      if (batch == 1) {
        t = time_us([&] { encoder.encode(f, mu); }, reps, iters1);
      } else {
        t = time_us(
            [&] {
              if (threads == 1) {
                encoder.encode_batch(f, batch, mu);
              } else {
                lab::encode_frames(model(), f, batch, threads, mu, nullptr);
              }
            },
            reps, iters1);
      }
      rows.push_back(
          row(batch == 1 && threads == 2 ? "Curio int8 (one image: 1 thread)" : "Curio int8", batch,
              threads, t));
      OneDnn dnn(batch);
      dnn.set_frames(f);
      rows.push_back(row("oneDNN int8", batch, threads, time_us([&] { dnn.run(); }, reps, iters1)));
      Xnn xnn(batch, threads);
      xnn.set_frames(f);
      rows.push_back(
          row("XNNPACK int8", batch, threads, time_us([&] { xnn.run(); }, reps, iters1)));
      const auto images = torch::from_blob(pixels.data(), {kBigBatch, 64, 64, 3})
                              .slice(0, 0, batch)
                              .permute({0, 3, 1, 2})
                              .contiguous();
      rows.push_back(
          row("LibTorch fp32", batch, threads,
              time_us([&] { torch_encoder.net->forward(images); }, reps, std::max(1, iters1 / 4))));
      if (batch == 1 && threads == 1) {  // per layer: medians over n calls of each
        const int n = quick ? 101 : 1001;
        static Clock::time_point last;
        static std::vector<double> curio_runs[kLayers];
        std::vector<double> dnn_runs[kLayers], xnn_runs[kLayers];
        encoder.set_layer_probe(
            [](void*, int32_t layer) {
              const auto now = Clock::now();
              if (layer >= 0)
                curio_runs[layer].push_back(
                    std::chrono::duration<double, std::micro>(now - last).count());
              last = now;
            },
            nullptr);
        for (int r = 0; r < n; ++r) encoder.encode(f, mu);
        encoder.set_layer_probe(nullptr, nullptr);
        for (int r = 0; r < n; ++r) {
          for (int i = 0; i < kLayers; ++i) {
            const auto a = Clock::now();
            dnn.run_layer(i);
            const auto b = Clock::now();
            xnn.run_layer(i);
            const auto c = Clock::now();
            dnn_runs[i].push_back(std::chrono::duration<double, std::micro>(b - a).count());
            xnn_runs[i].push_back(std::chrono::duration<double, std::micro>(c - b).count());
          }
        }
        for (int i = 0; i < kLayers; ++i) {
          curio_layer_us[i] = median(curio_runs[i]);
          dnn_layer_us[i] = median(dnn_runs[i]);
          xnn_layer_us[i] = median(xnn_runs[i]);
        }
      }
      if (batch == kBigBatch && threads == 1) {  // the engines' layers at batch 64, per image
        const int n = quick ? 5 : 21;
        std::vector<double> dnn_runs[kLayers], xnn_runs[kLayers];
        for (int r = 0; r < n; ++r) {  // CPU time: a call this long is often preempted here
          for (int i = 0; i < kLayers; ++i) {
            const double a = cpu_us();
            dnn.run_layer(i);
            const double b = cpu_us();
            xnn.run_layer(i);
            const double c = cpu_us();
            dnn_runs[i].push_back((b - a) / batch);
            xnn_runs[i].push_back((c - b) / batch);
          }
        }
        for (int i = 0; i < kLayers; ++i) {
          dnn64_layer_us[i] = median(dnn_runs[i]);
          xnn64_layer_us[i] = median(xnn_runs[i]);
        }
      }
    }
  }

  const double peak = vnni_peak_macs_per_us();
  const double floor_us = static_cast<double>(encoder_macs()) / peak;
  std::printf(
      "\nus per image (median of %d): wall, and the process's CPU time (all threads); vs Curio: "
      "CPU time over\n"
      "Curio's at the same batch and threads; of peak: the encoder's MACs at this core's measured "
      "vpdpbusd\n"
      "peak (%.0f MACs/us, %.2f us per image) over the CPU time per image\n",
      reps, peak, floor_us);
  std::printf("  %-34s %5s %7s %9s %9s %9s %8s\n", "engine", "batch", "threads", "wall us",
              "CPU us", "vs Curio", "of peak");
  for (const Row& r : rows) {
    double curio = 0;
    for (const Row& c : rows) {
      if (c.engine.rfind("Curio", 0) == 0 && c.batch == r.batch && c.threads == r.threads)
        curio = c.cpu;
    }
    std::printf("  %-34s %5d %7d %9.1f %9.1f %8.2fx %7.1f%%\n", r.engine.c_str(), r.batch,
                r.threads, r.wall, r.cpu, r.cpu / curio, 100.0 * floor_us / r.cpu);
  }
  std::printf(
      "\none thread, per layer (median us per image; Curio's from its layer probe, the engines' "
      "per "
      "primitive call, at batch 64\nin CPU time; Curio encodes a batch one image after another, so "
      "its batch-64 layers are its batch-1 ones)\n");
  std::printf("  %-7s %9s %9s %9s %9s %11s %11s %11s\n", "layer", "MACs", "Curio", "oneDNN",
              "XNNPACK", "oneDNN b64", "XNNPACK b64", "peak floor");
  double tc = 0, td = 0, tx = 0, td64 = 0, tx64 = 0;
  for (int i = 0; i < kLayers; ++i) {
    tc += curio_layer_us[i];
    td += dnn_layer_us[i];
    tx += xnn_layer_us[i];
    td64 += dnn64_layer_us[i];
    tx64 += xnn64_layer_us[i];
    std::printf("  %-7s %9lld %9.2f %9.2f %9.2f %11.2f %11.2f %11.2f\n", kLayerNames[i],
                static_cast<long long>(layer_macs(i)), curio_layer_us[i], dnn_layer_us[i],
                xnn_layer_us[i], dnn64_layer_us[i], xnn64_layer_us[i],
                static_cast<double>(layer_macs(i)) / peak);
  }
  std::printf("  %-7s %9lld %9.2f %9.2f %9.2f %11.2f %11.2f %11.2f\n", "sum",
              static_cast<long long>(encoder_macs()), tc, td, tx, td64, tx64, floor_us);
  xnn_deinitialize();
  return 0;
}

}  // namespace
}  // namespace curio::nn::bench

int main(int argc, char** argv) {
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      quick = true;
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: curio-bench-encoder-engines [--quick]\n"
          "The shipped int8 encoder in Curio's kernels beside oneDNN, XNNPACK and LibTorch fp32 "
          "(same process,\n"
          "same frames): output agreement per layer, us per image at batch 1 and 64 on 1 and 2 "
          "threads, the\n"
          "time per layer, and the distance to this core's measured vpdpbusd peak. --quick: fewer "
          "repetitions.\n");
      return 0;
    } else {
      std::fprintf(stderr, "curio-bench-encoder-engines: unknown option '%s' (try --help)\n",
                   a.c_str());
      return 2;
    }
  }
  return curio::nn::bench::run(quick);
}
