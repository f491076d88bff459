#include "host_tools/experiment/batch_encode.hpp"

#include <algorithm>
#include <memory>
#include <thread>
#include <vector>

#include "firmware/nn/encoder.hpp"

namespace curio::lab {

std::string encode_frames(const nn::EncoderModel& model, const uint8_t* frames, int32_t count,
                          int threads, float* mu, float* log_var) {
  if (count <= 0) return "";
  const int n_threads = std::max(1, std::min<int>(threads, count));
  std::vector<int32_t> first_failure(static_cast<size_t>(n_threads), -1);
  auto work = [&](int t) {
    const int32_t begin = static_cast<int32_t>(static_cast<int64_t>(count) * t / n_threads);
    const int32_t end = static_cast<int32_t>(static_cast<int64_t>(count) * (t + 1) / n_threads);
    auto encoder = std::make_unique<nn::Encoder>(model);  // ~160 KiB: not on the thread's stack
    int32_t done = 0;
    const nn::Status s = encoder->encode_batch(frames + static_cast<int64_t>(begin) * nn::kImageBytes, end - begin,
                                               mu + static_cast<int64_t>(begin) * nn::kLatents,
                                               log_var != nullptr ? log_var + static_cast<int64_t>(begin) * nn::kLatents : nullptr,
                                               &done);
    if (s != nn::Status::kOk) first_failure[static_cast<size_t>(t)] = begin + done;
  };
  if (n_threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < n_threads; ++t) pool.emplace_back(work, t);
    for (auto& th : pool) th.join();
  }
  for (const int32_t f : first_failure)
    if (f >= 0) return "the int8 encoder refused frame " + std::to_string(f) + " (corrupt weights?)";
  return "";
}

}  // namespace curio::lab
