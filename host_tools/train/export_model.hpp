// `curio-train export`: a trained model as the float model file (CURIOFM1, PyTorch layout,
// encoder tensors first in encoder_spec order, then "dec.*") and its meta JSON.
#pragma once
#include <string>
#include <vector>

#include "host_tools/vae/recipe.hpp"
#include "host_tools/vae/vae_model.hpp"

namespace curio::train {

struct ExportResult {
  std::string model_path;  // <dir>/<name>.cfm
  std::string meta_path;   // <dir>/<name>.meta.json
  std::vector<double> kl_per_latent;
};

// kl_images: scenes (SPEC §2.4: 1,000, positions uniform) over which the per-latent KL of the
// meta file is averaged. made_by (may be empty): the command that trained the model when
// it took more than one `train` (the meta's recipe is only the last stage's), e.g. a script.
// Throws std::runtime_error / model_io::ModelFormatError on failure.
ExportResult export_model(Vae& model, const Recipe& recipe, int64_t iteration,
                          const std::string& dir, const std::string& name, int64_t kl_images,
                          const std::string& made_by = {});

}  // namespace curio::train
