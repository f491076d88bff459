// What a goal space makes of a user's images (curio-encode): for each image μ and log σ² of
// every latent from the int8 encoder the controller runs, and from the float model it was
// quantized from where that model is present, with their difference; the latents ranked by
// their KL over the training scenes and grouped into goal modules as MGE with that goal space
// groups them (SPEC §2.4); per image, how much each module's posterior departs from the prior.
#pragma once
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware/nn/encoder.hpp"
#include "host_tools/encode/camera_png.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/model_io/float_decoder.hpp"
#include "host_tools/model_io/float_encoder.hpp"

namespace curio::encode {

inline constexpr int kLatents = nn::kLatents;
using Latents = std::array<float, kLatents>;

// One image's codes.
struct ImageCodes {
  CameraImage image;
  Latents mu_int8{}, log_var_int8{};
  bool has_float = false;
  Latents mu_float{}, log_var_float{};
  Latents kl{};  // per latent, KL(q(z|x) ‖ N(0, 1)) of the int8 posterior
  std::vector<double> module_activity;  // per goal module: the sum of its latents' kl
};

// The goal space: the int8 model compiled into this build and, when its float model file is
// found beside the weights (firmware/nn/models/<name>.cfm), the float encoder and decoder.
class GoalSpace {
 public:
  // Throws std::runtime_error naming the model when this build has no such weights.
  GoalSpace(const std::string& name, const std::string& models_dir);

  const lab::Representation& representation() const { return *rep_; }
  // modules()[k]: the latents of goal module k, in KL order.
  const std::vector<std::vector<int>>& modules() const { return modules_; }
  bool has_float() const { return float_encoder_.has_value(); }
  bool has_decoder() const { return decoder_.has_value(); }
  const std::string& float_model_path() const { return float_path_; }
  // Why there is no float model or decoder ("" when both are there).
  const std::string& float_note() const { return float_note_; }

  ImageCodes encode(const CameraImage& image) const;
  // The same for many images, the int8 encoder on `threads` threads (lab::encode_frames);
  // the codes do not depend on the thread count.
  std::vector<ImageCodes> encode_all(const std::vector<CameraImage>& images, int threads) const;
  // The float decoder's image for z (has_decoder() only).
  std::vector<float> decode(const Latents& z) const;

 private:
  const lab::Representation* rep_ = nullptr;
  std::vector<std::vector<int>> modules_;
  std::optional<model_io::FloatEncoder> float_encoder_;
  std::optional<model_io::FloatDecoder> decoder_;
  std::string float_path_, float_note_;
  std::unique_ptr<nn::Encoder> encoder_;  // the controller's int8 encoder (no state between calls)
  // The float codes, KL and module activity of c, whose int8 codes are set.
  void complete(ImageCodes* c) const;
};

// latents.csv: one row per image and latent, latents in KL order.
std::string codes_csv(const GoalSpace& space, const std::vector<ImageCodes>& codes);
// summary.json: the goal space, every image's codes, and the files refused with why.
nlohmann::json codes_json(const GoalSpace& space, const std::vector<ImageCodes>& codes,
                          const std::vector<std::pair<std::string, std::string>>& refused);

// The figure's pixels (HWC floats in [0, 1]) and size: for each of the first `max_images`
// images a block of 4 rows of 64×64 tiles, in columns: the image, the float model's
// reconstruction from its μ, a gap, then 7 decodings with one latent set to −3 … 3 and the
// others at μ: rows 1–2 the two latents of the image's most active module, rows 3–4 those of
// the second. Needs has_decoder().
struct Figure {
  int width = 0, height = 0;
  std::vector<float> hwc;
};
Figure codes_figure(const GoalSpace& space, const std::vector<ImageCodes>& codes, int max_images);

}  // namespace curio::encode
