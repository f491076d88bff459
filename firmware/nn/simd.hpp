// Which inner loops the kernels use. Like CMSIS-NN's ARM_MATH_DSP / ARM_MATH_MVEI paths:
// portable C by default, and an instruction-set path where the compiler cannot find a good
// loop by itself:
//   CURIO_NN_AVX512_VNNI  host with AVX-512 VNNI: the channel-vector conv (8 pixels × 16
//                         channels per vector)
//   CURIO_NN_AVX2         host with AVX2 but not AVX-512 VNNI: the same at 8 channels per
//                         vector (vpdpbusd with AVX-VNNI, else vpmaddubsw on |x|·(w·sign x))
//   CURIO_NN_ARM_DSP      Cortex-M with the DSP extension (__ARM_FEATURE_DSP: M4, M7, M33…):
//                         paired 16-bit multiply-accumulates (SMLAD) on sign-extended weight
//                         pairs (SXTB16), dsp_ops.hpp. CURIO_NN_EMULATE_DSP compiles the same
//                         path on a host with the instructions written in C, so host tests check
//                         its layout (reordered columns, tails) bit for bit.
// Define CURIO_NN_PORTABLE to force the portable path (the tests build every path and compare
// them bit for bit). Include this only from .cpp files: headers must not change with the
// compile flags.
#pragma once

#if !defined(CURIO_NN_PORTABLE) && !defined(CURIO_NN_EMULATE_DSP) && defined(__AVX512F__) && \
    defined(__AVX512BW__) && defined(__AVX512VNNI__)
#define CURIO_NN_AVX512_VNNI 1
#else
#define CURIO_NN_AVX512_VNNI 0
#endif

// AVX2 without AVX-512 VNNI (conv_channel_vector_avx2.hpp, with AVX-VNNI where the compiler
// targets it): the same channel-vector conv at 8 channels per vector.
#if !defined(CURIO_NN_PORTABLE) && !defined(CURIO_NN_EMULATE_DSP) && !CURIO_NN_AVX512_VNNI && \
    defined(__AVX2__)
#define CURIO_NN_AVX2 1
#else
#define CURIO_NN_AVX2 0
#endif
#define CURIO_NN_CHANNEL_VECTOR (CURIO_NN_AVX512_VNNI || CURIO_NN_AVX2)

#if !defined(CURIO_NN_PORTABLE) && (defined(__ARM_FEATURE_DSP) || defined(CURIO_NN_EMULATE_DSP))
#define CURIO_NN_ARM_DSP 1
#else
#define CURIO_NN_ARM_DSP 0
#endif
