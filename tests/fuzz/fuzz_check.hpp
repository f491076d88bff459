// The oracle check of the libFuzzer targets: names the failed oracle's file, line and
// expression before aborting, so the reproducer libFuzzer writes says which one failed.
#pragma once
#include <cstdio>
#include <cstdlib>

#define check(ok)                                                                   \
  do {                                                                              \
    if (!(ok)) {                                                                    \
      std::fprintf(stderr, "%s:%d: oracle failed: %s\n", __FILE__, __LINE__, #ok); \
      std::abort();                                                                 \
    }                                                                               \
  } while (0)
