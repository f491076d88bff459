// Which inner loops the kernels use. Like CMSIS-NN's ARM_MATH_DSP / ARM_MATH_MVEI paths:
// portable C by default (the Cortex-M build and any host), and an instruction-set path
// only where the compiler cannot find a good loop by itself. Define CURIO_NN_PORTABLE to
// force the portable path (the tests build both and compare them bit for bit). Include
// this only from .cpp files: headers must not change with the compile flags.
#pragma once

#if !defined(CURIO_NN_PORTABLE) && defined(__AVX512F__) && defined(__AVX512BW__) && \
    defined(__AVX512VNNI__)
#define CURIO_NN_AVX512_VNNI 1
#else
#define CURIO_NN_AVX512_VNNI 0
#endif
