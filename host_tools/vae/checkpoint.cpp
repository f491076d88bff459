#include "host_tools/vae/checkpoint.hpp"

#include <ATen/CPUGeneratorImpl.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "firmware/journal/crc32.hpp"
#include "host_tools/common/atomic_file.hpp"

namespace curio::train {

namespace {

// "crc32 1a2b3c4d size 1234567": one line per file content the .crc file vouches for.
std::string crc_line_of(const std::string& bytes) {
  const uint32_t crc =
      journal::crc32(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  char line[64];
  std::snprintf(line, sizeof line, "crc32 %08x size %zu", static_cast<unsigned>(crc),
                bytes.size());
  return line;
}

// The whole file, "" when it cannot be read.
std::string file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return f ? std::string{std::istreambuf_iterator<char>(f), {}} : std::string();
}

}  // namespace

std::string checkpoint_path(const std::string& dir) {
  return (std::filesystem::path(dir) / "checkpoint.pt").string();
}

std::string checkpoint_crc_path(const std::string& path) { return path + ".crc"; }

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
  // Serialised in memory, then written by us: LibTorch's file writer throws from its
  // destructor when the disk is full, which no caller can catch (the program aborts).
  std::ostringstream buffer;
  archive.save_to(buffer);
  const std::string bytes = buffer.str();
  const std::string fresh = crc_line_of(bytes) + "\n";
  // What vouches for the checkpoint on disk now: its .crc (read, not recomputed), or for one an
  // older build wrote without a .crc, its CRC.
  const std::string crc_path = checkpoint_crc_path(path);
  std::string prior = file_bytes(crc_path);
  if (prior.empty() && std::filesystem::exists(path)) prior = crc_line_of(file_bytes(path)) + "\n";
  host::write_file_atomically_or_throw(crc_path, prior + fresh);  // either archive is vouched for
  host::write_file_atomically_or_throw(path, bytes);
  host::write_file_atomically_or_throw(crc_path, fresh);
}

CheckpointInfo load_checkpoint(const std::string& path, Vae& model,
                               torch::optim::Adam* optimizer) {
  if (!std::filesystem::exists(path))
    throw std::runtime_error(path + ": no checkpoint (train first, or check --out/--checkpoint)");
  // Read once: checked against its .crc, then loaded from memory.
  const std::string bytes = file_bytes(path);
  bool verified = false;
  if (std::ifstream crc_file(checkpoint_crc_path(path)); crc_file) {
    const std::string actual = crc_line_of(bytes);
    std::string line, recorded;
    while (std::getline(crc_file, line)) {
      if (line == actual) verified = true;
      recorded += (recorded.empty() ? "" : " or ") + line;
    }
    if (!verified)
      throw std::runtime_error(path + ": damaged checkpoint: it has " + actual + ", " +
                               checkpoint_crc_path(path) + " records " + recorded +
                               "; nothing was loaded (use an earlier copy, or train again)");
  }
  torch::serialize::InputArchive archive, model_archive;
  try {
    archive.load_from(bytes.data(), bytes.size());
    archive.read("model", model_archive);
    model->load(model_archive);
    CheckpointInfo info;
    info.verified = verified;
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
