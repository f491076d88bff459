#include "tests/nn/qemu_vectors.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "firmware/explore/prng.hpp"
#include "firmware/nn/nn_types.hpp"
#include "firmware/nn/quantize_multiplier.hpp"
#include "host_tools/quantize/sha256.hpp"
#include "tests/nn/reference_kernels.hpp"

namespace curio::nn::testing {
namespace {

// Bump when the reference kernels' semantics change.
constexpr const char* kGeneratorVersion = "qemu-vectors 2";
constexpr uint64_t kSeed = 20240601;

struct ConvSpec {
  const char* name;
  Dims in;
  Dims filter;
  Tile stride, pad;
  double rescale_factor;  // > 1: rescales ≥ 0.5 (general requantization form)
};

struct FcSpec {
  const char* name;
  FcDims dims;
  bool s32;   // accumulator output
  bool wide;  // int16 weights (the latent layer's kernel); implies s32
};

const std::vector<ConvSpec>& conv_specs() {
  static const std::vector<ConvSpec> specs = {
      {"conv_first_layer", {1, 9, 9, 3}, {16, 4, 4, 3}, {2, 2}, {1, 1}, 1.0},
      {"conv_encoder_conv3", {1, 8, 8, 32}, {32, 4, 4, 32}, {2, 2}, {1, 1}, 1.0},
      {"conv_odd_batch2", {2, 7, 5, 3}, {5, 3, 3, 3}, {1, 1}, {1, 1}, 1.0},
      {"conv_large_rescale", {1, 6, 6, 8}, {8, 3, 3, 8}, {1, 1}, {1, 1}, 3000.0},
  };
  return specs;
}

const std::vector<FcSpec>& fc_specs() {
  static const std::vector<FcSpec> specs = {
      {"fc_512_16", {1, 512, 16}, false, false},
      {"fc_s32_256_20", {1, 256, 20}, true, false},
      {"fc_latent_w16_256_20", {1, 256, 20}, true, true},
      {"fc_odd_batch3", {3, 37, 7}, false, false},
  };
  return specs;
}

std::string describe_specs() {
  std::ostringstream s;
  s << kGeneratorVersion << " seed " << kSeed << "\n";
  for (const auto& c : conv_specs()) {
    s << c.name << " " << c.in.n << "x" << c.in.h << "x" << c.in.w << "x" << c.in.c << " f"
      << c.filter.n << "x" << c.filter.h << "x" << c.filter.w << "x" << c.filter.c << " s"
      << c.stride.h << "," << c.stride.w << " p" << c.pad.h << "," << c.pad.w << " r"
      << c.rescale_factor << "\n";
  }
  for (const auto& f : fc_specs()) {
    s << f.name << " " << f.dims.batches << "x" << f.dims.input_depth << "->" << f.dims.output_depth
      << (f.s32 ? " s32" : " s8") << (f.wide ? " w16" : "") << "\n";
  }
  return s.str();
}

template <typename T>
void emit(std::ostringstream& out, const char* type, const std::string& name,
          const std::vector<T>& v) {
  out << "alignas(16) inline constexpr " << type << " " << name << "[" << v.size() << "] = {";
  for (size_t i = 0; i < v.size(); ++i) {
    out << (i % 24 == 0 ? "\n    " : " ") << static_cast<int64_t>(v[i])
        << (i + 1 < v.size() ? "," : "");
  }
  out << "};\n";
}

std::vector<int8_t> random_s8(Prng& rng, size_t n, int lo, int hi) {
  std::vector<int8_t> v(n);
  for (auto& x : v)
    x = static_cast<int8_t>(lo + static_cast<int>(rng.below(static_cast<uint32_t>(hi - lo + 1))));
  return v;
}

std::vector<int32_t> random_bias(Prng& rng, size_t n, int32_t depth) {
  const auto span = static_cast<uint32_t>(64.0 * 128.0 * std::sqrt(depth));
  std::vector<int32_t> v(n);
  for (auto& b : v) b = static_cast<int32_t>(rng.below(2 * span + 1) - span);
  return v;
}

void random_rescales(Prng& rng, size_t n, double typical, std::vector<int32_t>* mult,
                     std::vector<int32_t>* shift) {
  for (size_t c = 0; c < n; ++c) {
    QuantizedMultiplier m;
    quantize_multiplier(typical * rng.uniform(0.25, 4.0), &m);
    mult->push_back(m.multiplier);
    shift->push_back(m.shift);
  }
}

}  // namespace

std::string make_qemu_vectors_header() {
  Prng rng(kSeed);
  std::ostringstream body;
  body << "#pragma once\n#include <cstdint>\n\n#include \"firmware/nn/nn_types.hpp\"\n\n"
       << "namespace curio::nn::qemu_vectors {\n\n"
       << "struct ConvVector {\n  const char* name;\n  Dims input_dims, filter_dims, output_dims;\n"
       << "  ConvParams params;\n  const int8_t* input;\n  const int8_t* filter;\n"
       << "  const int32_t* bias;\n  const int32_t* multiplier;\n  const int32_t* shift;\n"
       << "  const int8_t* expected;\n  int32_t expected_size;\n};\n\n"
       << "struct FcVector {\n  const char* name;\n  FcDims dims;\n  FcParams params;\n"
       << "  bool s32;\n  const int8_t* input;\n  const int8_t* filter;      // when !wide\n"
       << "  const int16_t* filter_w16;  // int16 weights (fully_connected_s8_w16_s32)\n"
       << "  const int32_t* bias;\n"
       << "  const int32_t* multiplier;\n  const int32_t* shift;\n"
       << "  const int8_t* expected_s8;    // when !s32\n"
       << "  const int32_t* expected_s32;  // when s32\n  int32_t expected_size;\n};\n\n";
  std::ostringstream table;
  table << "inline constexpr ConvVector kConvVectors[] = {\n";
  for (const ConvSpec& c : conv_specs()) {
    const Dims& in = c.in;
    const Dims& f = c.filter;
    const Dims out{in.n, (in.h + 2 * c.pad.h - f.h) / c.stride.h + 1,
                   (in.w + 2 * c.pad.w - f.w) / c.stride.w + 1, f.n};
    ConvParams p;
    p.input_offset = static_cast<int32_t>(rng.below(256)) - 127;
    p.output_offset = static_cast<int32_t>(rng.below(129)) - 128;
    p.stride = c.stride;
    p.padding = c.pad;
    p.activation = {p.output_offset, 127};
    const auto input = random_s8(rng, static_cast<size_t>(in.n * in.h * in.w * in.c), -128, 127);
    const auto filter = random_s8(rng, static_cast<size_t>(f.n * f.h * f.w * f.c), -127, 127);
    const auto bias = random_bias(rng, static_cast<size_t>(f.n), f.h * f.w * f.c);
    std::vector<int32_t> mult, shift;
    random_rescales(rng, static_cast<size_t>(f.n),
                    c.rescale_factor * 2.0 / (128.0 * std::sqrt(f.h * f.w * f.c)), &mult, &shift);
    const auto expected = ref::conv(p, mult, shift, in, input, f, filter, bias, out);
    const std::string n = c.name;
    emit(body, "int8_t", n + "_input", input);
    emit(body, "int8_t", n + "_filter", filter);
    emit(body, "int32_t", n + "_bias", bias);
    emit(body, "int32_t", n + "_multiplier", mult);
    emit(body, "int32_t", n + "_shift", shift);
    emit(body, "int8_t", n + "_expected", expected);
    table << "    {\"" << n << "\", {" << in.n << ", " << in.h << ", " << in.w << ", " << in.c
          << "}, {" << f.n << ", " << f.h << ", " << f.w << ", " << f.c << "}, {" << out.n << ", "
          << out.h << ", " << out.w << ", " << out.c << "},\n     {" << p.input_offset << ", "
          << p.output_offset << ", {" << p.stride.h << ", " << p.stride.w << "}, {" << p.padding.h
          << ", " << p.padding.w << "}, {" << p.activation.min << ", " << p.activation.max
          << "}},\n     " << n << "_input, " << n << "_filter, " << n << "_bias, " << n
          << "_multiplier, " << n << "_shift, " << n << "_expected, " << expected.size() << "},\n";
  }
  table << "};\n\ninline constexpr FcVector kFcVectors[] = {\n";
  for (const FcSpec& s : fc_specs()) {
    const FcDims& d = s.dims;
    FcParams p;
    p.input_offset = static_cast<int32_t>(rng.below(256)) - 127;
    p.output_offset = static_cast<int32_t>(rng.below(129)) - 128;
    p.activation = {p.output_offset, 127};
    const auto input = random_s8(rng, static_cast<size_t>(d.batches * d.input_depth), -128, 127);
    const auto filter =
        random_s8(rng, static_cast<size_t>(d.output_depth * d.input_depth), -127, 127);
    std::vector<int16_t> wide(s.wide ? filter.size() : 0);
    for (auto& w : wide) w = static_cast<int16_t>(static_cast<int32_t>(rng.below(32767)) - 16383);
    const auto bias = random_bias(rng, static_cast<size_t>(d.output_depth), d.input_depth);
    std::vector<int32_t> mult, shift;
    random_rescales(rng, static_cast<size_t>(d.output_depth),
                    2.0 / (128.0 * std::sqrt(d.input_depth)), &mult, &shift);
    const auto acc = s.wide ? ref::fc_acc(p.input_offset, d, input, wide, bias)
                            : ref::fc_acc(p.input_offset, d, input, filter, bias);
    const std::string n = s.name;
    emit(body, "int8_t", n + "_input", input);
    if (s.wide) {
      emit(body, "int16_t", n + "_filter", wide);
    } else {
      emit(body, "int8_t", n + "_filter", filter);
    }
    emit(body, "int32_t", n + "_bias", bias);
    emit(body, "int32_t", n + "_multiplier", mult);
    emit(body, "int32_t", n + "_shift", shift);
    if (s.s32) {
      std::vector<int32_t> expected(acc.size());
      for (size_t i = 0; i < acc.size(); ++i) expected[i] = ref::clamp32(acc[i]);
      emit(body, "int32_t", n + "_expected", expected);
    } else {
      std::vector<int8_t> expected(acc.size());
      for (size_t i = 0; i < acc.size(); ++i) {
        const auto o = i % static_cast<size_t>(d.output_depth);
        expected[i] = ref::requant(acc[i], mult[o], shift[o], p.output_offset, p.activation);
      }
      emit(body, "int8_t", n + "_expected", expected);
    }
    table << "    {\"" << n << "\", {" << d.batches << ", " << d.input_depth << ", "
          << d.output_depth << "}, {" << p.input_offset << ", " << p.output_offset << ", {"
          << p.activation.min << ", " << p.activation.max << "}}, " << (s.s32 ? "true" : "false")
          << ",\n     " << n << "_input, "
          << (s.wide ? "nullptr, " + n + "_filter, " : n + "_filter, nullptr, ") << n << "_bias, "
          << n << "_multiplier, " << n << "_shift, " << (s.s32 ? "nullptr, " : n + "_expected, ")
          << (s.s32 ? n + "_expected, " : "nullptr, ") << acc.size() << "},\n";
  }
  table << "};\n\n}  // namespace curio::nn::qemu_vectors\n";

  std::ostringstream out;
  out << "// DO NOT EDIT: generated by curio_nn_make_qemu_vectors (tests/nn/qemu_vectors.cpp)\n"
      << "// from the plain reference kernels (tests/nn/reference_kernels.hpp). Regenerate with:\n"
      << "//   cmake --build <build> --target curio_nn_make_qemu_vectors &&\n"
      << "//   <build>/tests/nn/curio_nn_make_qemu_vectors " << kQemuVectorsPath << "\n"
      << "// The host test QemuVectors.CommittedHeaderIsCurrent fails when this file is stale.\n"
      << "// inputs-sha256: " << quantize::sha256_hex(describe_specs()) << "\n"
      << body.str() << table.str();
  return out.str();
}

}  // namespace curio::nn::testing
