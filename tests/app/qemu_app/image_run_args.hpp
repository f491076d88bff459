// The run parameters of the controller images that talk to a real link (the Cortex-M7 SLCAN
// image, tests/app/qemu_slcan/; the ZynqMP CAN image, tests/zynqmp/), read from the
// semihosting command line, and curio-controller's explorer configuration for them, so that
// the image and `curio-controller --print-checksum` run the same exploration:
//   algo=MGE-EFR|RGE-EFR|RPE|MGE-bVAE   seed=N   episodes=N (after the bootstrap)
//   bootstrap=N (default: 100 EFR, 400 βVAE)   progress=N (a line every N episodes, 0 = none)
//   plus one two-valued link option of the image (can=fd|classic, layout=qemu|chip).
// Freestanding: no heap, parsed in place.
#pragma once
#include <cstdint>
#include <cstring>

#include "firmware/explore/config.hpp"
#include "firmware/explore/module_layouts.hpp"
#include "firmware/nn/models/beta_vae_weights.hpp"

namespace curio::test {

struct ImageRunArgs {
  char algo[16] = "MGE-EFR";
  uint32_t seed = 0;
  int episodes = 400;
  int bootstrap = -1;
  int progress = 100;
  bool link_alt = false;  // the link option has its second value (classic, chip)
};

// The image's link option: key=first|second (first is the default).
struct ImageLinkOption {
  const char* key;
  const char* first;
  const char* second;
};

inline bool parse_image_uint(const char* s, uint32_t* out) {
  if (*s == '\0') return false;
  uint32_t v = 0;
  for (; *s != '\0'; ++s) {
    if (*s < '0' || *s > '9') return false;
    v = v * 10u + static_cast<uint32_t>(*s - '0');
  }
  *out = v;
  return true;
}

// "k=v k=v ..." in place; false on an unknown key or a bad value.
inline bool parse_image_args(char* line, const ImageLinkOption& link, ImageRunArgs* a) {
  char* p = line;
  while (*p != '\0') {
    while (*p == ' ') ++p;
    if (*p == '\0') break;
    char* word = p;
    while (*p != '\0' && *p != ' ') ++p;
    if (*p == ' ') *p++ = '\0';
    char* eq = std::strchr(word, '=');
    if (eq == nullptr) continue;  // the image's own name, when QEMU puts it first
    *eq = '\0';
    const char* key = word;
    const char* value = eq + 1;
    uint32_t v = 0;
    if (std::strcmp(key, "algo") == 0) {
      if (std::strlen(value) >= sizeof a->algo) return false;
      std::strcpy(a->algo, value);
    } else if (std::strcmp(key, "seed") == 0 && parse_image_uint(value, &v)) {
      a->seed = v;
    } else if (std::strcmp(key, "episodes") == 0 && parse_image_uint(value, &v)) {
      a->episodes = static_cast<int>(v);
    } else if (std::strcmp(key, "bootstrap") == 0 && parse_image_uint(value, &v)) {
      a->bootstrap = static_cast<int>(v);
    } else if (std::strcmp(key, "progress") == 0 && parse_image_uint(value, &v)) {
      a->progress = static_cast<int>(v);
    } else if (std::strcmp(key, link.key) == 0 &&
               (std::strcmp(value, link.first) == 0 || std::strcmp(value, link.second) == 0)) {
      a->link_alt = std::strcmp(value, link.second) == 0;
    } else {
      return false;
    }
  }
  return true;
}

// curio-controller's configuration for the same algorithm (host_tools/experiment/algorithms.cpp,
// campaign.cpp): σ 0.05, D 1 EFR / 2 learned, window 1000, ε 0.1; false for an algorithm the
// images do not know.
inline bool image_explorer_config(const ImageRunArgs& a, ExplorerConfig* c, bool* learned) {
  *learned = false;
  Algorithm algorithm = Algorithm::kMge;
  if (std::strcmp(a.algo, "MGE-EFR") == 0) {
    algorithm = Algorithm::kMge;
  } else if (std::strcmp(a.algo, "RGE-EFR") == 0) {
    algorithm = Algorithm::kRge;
  } else if (std::strcmp(a.algo, "RPE") == 0) {
    algorithm = Algorithm::kRpe;
  } else if (std::strcmp(a.algo, "MGE-bVAE") == 0) {
    *learned = true;
  } else {
    return false;
  }
  if (*learned) {
    uint8_t order[kLatentDim];
    for (int i = 0; i < kLatentDim; ++i) order[i] = static_cast<uint8_t>(nn::beta_vae::kKlOrder[i]);
    if (set_latent_modules(*c, order, 2) != Status::kOk) return false;
    c->n_bootstrap = a.bootstrap >= 0 ? a.bootstrap : 400;
    c->competence_cap = 2.0f;
  } else {
    if (set_efr_modules(*c, algorithm) != Status::kOk) return false;
    c->n_bootstrap = a.bootstrap >= 0 ? a.bootstrap : 100;
    c->competence_cap = 1.0f;
  }
  c->n_episodes = a.episodes;
  c->seed = a.seed;
  c->sigma = 0.05f;
  c->window = 1000.0f;
  c->epsilon = 0.1f;
  return validate(*c) == Status::kOk;
}

}  // namespace curio::test
