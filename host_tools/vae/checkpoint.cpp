#include "host_tools/vae/checkpoint.hpp"

#include <ATen/CPUGeneratorImpl.h>

#include <filesystem>
#include <stdexcept>

#include "host_tools/common/atomic_file.hpp"

namespace curio::train {

std::string checkpoint_path(const std::string& dir) {
  return (std::filesystem::path(dir) / "checkpoint.pt").string();
}

void save_checkpoint(const std::string& path, Vae& model, torch::optim::Adam& optimizer,
                     const Recipe& recipe, int64_t iteration) {
  torch::serialize::OutputArchive archive, model_archive, optim_archive;
  model->save(model_archive);
  optimizer.save(optim_archive);
  archive.write("model", model_archive);
  archive.write("optim", optim_archive);
  archive.write("iteration", torch::tensor(iteration, torch::kInt64));
  archive.write("rng", at::detail::getDefaultCPUGenerator().get_state());
  archive.write("recipe", c10::IValue(to_json(recipe).dump()));
  const std::string tmp = host::temp_path_for(path);  // fsync'ed, then renamed over path
  archive.save_to(tmp);
  std::string error;
  if (!host::commit_temp(tmp, path, &error)) throw std::runtime_error(error);
}

CheckpointInfo load_checkpoint(const std::string& path, Vae& model,
                               torch::optim::Adam* optimizer) {
  if (!std::filesystem::exists(path))
    throw std::runtime_error(path + ": no checkpoint (train first, or check --out/--model-dir)");
  torch::serialize::InputArchive archive, model_archive;
  try {
    archive.load_from(path);
    archive.read("model", model_archive);
    model->load(model_archive);
    CheckpointInfo info;
    torch::Tensor it;
    archive.read("iteration", it);
    info.iteration = it.item<int64_t>();
    c10::IValue recipe;
    archive.read("recipe", recipe);
    info.recipe = recipe_from_json(nlohmann::json::parse(recipe.toStringRef()));
    if (optimizer) {
      torch::serialize::InputArchive optim_archive;
      archive.read("optim", optim_archive);
      optimizer->load(optim_archive);
      torch::Tensor rng;
      archive.read("rng", rng);
      at::Generator generator = at::detail::getDefaultCPUGenerator();  // shares the global one
      generator.set_state(rng);
    }
    return info;
  } catch (const c10::Error& e) {
    throw std::runtime_error(path + ": unreadable checkpoint: " + e.what_without_backtrace());
  }
}

}  // namespace curio::train
