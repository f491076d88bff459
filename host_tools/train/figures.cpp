#include "host_tools/train/figures.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "host_tools/common/atomic_file.hpp"
#include "host_tools/common/gnuplot.hpp"
#include "sim/render.hpp"

namespace curio::train {
namespace {

constexpr int kTile = 64;
constexpr int kGap = 2;

// A grid of CHW tiles on a dark-grey HWC canvas (the grey gap separates black images).
class Canvas {
 public:
  Canvas(int rows, int cols)
      : w_(cols * (kTile + kGap) + kGap), h_(rows * (kTile + kGap) + kGap),
        px_(static_cast<size_t>(w_ * h_ * 3), 0.25f) {}

  void put(int row, int col, const torch::Tensor& chw) {
    const auto t = chw.to(torch::kFloat32).clamp(0.0, 1.0).contiguous();
    const float* p = t.data_ptr<float>();
    const int x0 = kGap + col * (kTile + kGap), y0 = kGap + row * (kTile + kGap);
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x)
          px_[static_cast<size_t>(((y0 + y) * w_ + x0 + x) * 3 + c)] = p[(c * kTile + y) * kTile + x];
  }

  bool write(const std::string& path, std::string* error) const {
    // To a temporary file, then renamed: a kill leaves the old figure or the new one.
    const std::string tmp = host::temp_path_for(path);
    if (!sim::write_png(tmp, px_.data(), w_, h_, error)) {
      host::remove_temp(tmp);
      return false;
    }
    return host::commit_temp(tmp, path, error);
  }

 private:
  int w_, h_;
  std::vector<float> px_;
};

}  // namespace

bool write_kl_plot(const std::string& csv_path, const std::string& png_path, std::string* error) {
  std::string plot = "plot ";
  for (int l = 0; l < kLatents; ++l)
    plot += fmt::format("{}{} using 1:{} with lines lw 2 title 'z{}'", l ? ", " : "",
                        host::gnuplot_quote(csv_path), 9 + l, l);
  // Columns: 1 iteration, 2 loss, 3 recon, 4 kl, 5 beta, 6 capacity, 7 lr, 8 it/s, 9.. kl_z*.
  plot += fmt::format(", {} using 1:6 with lines dt 2 lc 'black' title 'capacity C'",
                      host::gnuplot_quote(csv_path));
  const std::string script = fmt::format(
      "set terminal pngcairo size 900,540\nset output {}\nset datafile separator ','\n"
      "set key autotitle columnhead outside right\nset xlabel 'iteration'\n"
      "set ylabel 'KL per latent (nats)'\nset grid\nset title 'Per-latent KL over training'\n{}\n",
      host::gnuplot_quote(png_path), plot);
  return host::run_gnuplot(png_path + ".gp", script, error);
}

bool write_traversal_png(Vae& model, const torch::Tensor& image, const std::vector<int>& order,
                         const std::string& png_path, std::string* error) {
  torch::NoGradGuard no_grad;
  constexpr int kSteps = 10;
  const auto mu = model->enc->forward(image.unsqueeze(0)).first;  // [1,10]
  Canvas canvas(static_cast<int>(order.size()), kSteps + 1);
  const auto values = torch::linspace(-3.0, 3.0, kSteps);
  for (size_t r = 0; r < order.size(); ++r) {
    canvas.put(static_cast<int>(r), 0, image);
    auto z = mu.repeat({kSteps, 1});
    z.select(1, order[r]).copy_(values);
    const auto decoded = torch::sigmoid(model->dec->forward(z));
    for (int s = 0; s < kSteps; ++s) canvas.put(static_cast<int>(r), s + 1, decoded[s]);
  }
  return canvas.write(png_path, error);
}

bool write_reconstruction_png(Vae& model, const torch::Tensor& images, const std::string& png_path,
                              std::string* error) {
  torch::NoGradGuard no_grad;
  const auto recon = torch::sigmoid(model->dec->forward(model->enc->forward(images).first));
  Canvas canvas(2, static_cast<int>(images.size(0)));
  for (int64_t i = 0; i < images.size(0); ++i) {
    canvas.put(0, static_cast<int>(i), images[i]);
    canvas.put(1, static_cast<int>(i), recon[i]);
  }
  return canvas.write(png_path, error);
}

}  // namespace curio::train
