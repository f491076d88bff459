// curio.Encoder: the int8 encoder of a learned goal space as the controller runs it
// (firmware/nn/encoder.hpp with the weights compiled into this build), batch encodes on
// threads with the GIL released; and the float decoder (host_tools/model_io) for
// reconstructions.
#include <memory>
#include <mutex>

#include "firmware/nn/encoder_arch.hpp"
#include "host_tools/experiment/batch_encode.hpp"
#include "host_tools/experiment/representations.hpp"
#include "host_tools/model_io/float_decoder.hpp"
#include "host_tools/python/bindings.hpp"

namespace curio::python {

namespace {

class PyEncoder {
 public:
  PyEncoder(const std::string& name, int threads) : threads_(threads) {
    rep_ = lab::find_representation(name);
    if (rep_ == nullptr) {
      std::string known;
      for (const auto& r : lab::available_representations()) known += (known.empty() ? "" : ", ") + r;
      value_error("name", "no int8 weights for '" + name + "' in this build (available: " +
                              (known.empty() ? "none" : known) + ")");
    }
    if (threads < 1) value_error("threads", "expected a number >= 1");
  }

  py::tuple encode(const py::object& images) const {
    bool single = false;
    const auto a = camera_images(images, "images", &single);
    const auto n = single ? 1 : static_cast<int32_t>(a.shape(0));
    py::array_t<float> mu({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(nn::kLatents)});
    py::array_t<float> log_var({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(nn::kLatents)});
    std::string error;
    {
      float* m = mu.mutable_data();
      float* l = log_var.mutable_data();
      const uint8_t* frames = a.data();
      py::gil_scoped_release release;
      error = lab::encode_frames(*rep_->model, frames, n, threads_, m, l);
    }
    if (!error.empty()) throw py::value_error("images: " + error);
    if (single) return py::make_tuple(mu[py::int_(0)], log_var[py::int_(0)]);
    return py::make_tuple(mu, log_var);
  }

  py::array_t<float> decode(const py::object& z, const std::string& path) {
    auto zs = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(z);
    if (!zs || (zs.ndim() != 1 && zs.ndim() != 2) || zs.shape(zs.ndim() - 1) != nn::kLatents)
      value_error("z", "expected 10 latents or an (N, 10) array");
    const bool single = zs.ndim() == 1;
    const py::ssize_t n = single ? 1 : zs.shape(0);
    {
      std::lock_guard lock(decoder_mutex_);
      if (!decoder_) {
        try {
          decoder_ = std::make_unique<model_io::FloatDecoder>(model_io::read_float_model(path));
        } catch (const std::exception& e) {
          value_error("decoder_path", e.what());
        }
      }
    }
    py::array_t<float> out({n, py::ssize_t{64}, py::ssize_t{64}, py::ssize_t{3}});
    const float* zp = zs.data();
    float* o = out.mutable_data();
    {
      py::gil_scoped_release release;
      for (py::ssize_t i = 0; i < n; ++i) {
        std::array<float, model_io::kLatents> v{};
        for (int j = 0; j < nn::kLatents; ++j) v[static_cast<size_t>(j)] = zp[i * nn::kLatents + j];
        const auto img = decoder_->image(v);
        std::copy(img.begin(), img.end(), o + i * 64 * 64 * 3);
      }
    }
    if (single) return out[py::int_(0)].cast<py::array_t<float>>();
    return out;
  }

  const lab::Representation& rep() const { return *rep_; }
  int threads() const { return threads_; }

 private:
  const lab::Representation* rep_ = nullptr;
  int threads_ = 1;
  std::mutex decoder_mutex_;
  std::unique_ptr<model_io::FloatDecoder> decoder_;
};

}  // namespace

void bind_encoder(py::module_& m) {
  py::class_<PyEncoder>(m, "Encoder", R"doc(
The int8 encoder of a learned goal space, exactly as the controller runs it.

Encoder(name="beta_vae", threads=1): "beta_vae" or "vae", the weights compiled into this
build (firmware/nn/models/<name>_weights.hpp). encode(images) takes uint8 camera images,
(64, 64, 3) or (N, 64, 64, 3), and returns (mu, log_var), float32 (10,) or (N, 10): the 10
latents dequantized from the int8 network's last int32 sums, bit for bit what the
controller archives. kl_order lists the latents by decreasing KL; modules(2) gives the goal
modules MGE uses (consecutive pairs in KL order). decode(z) is the float decoder: the
reconstructed image, float32 in [0, 1].
)doc")
      .def(py::init<const std::string&, int>(), py::arg("name") = "beta_vae", py::arg("threads") = 1)
      .def("encode", &PyEncoder::encode, py::arg("images"),
           "(mu, log_var) of uint8 images (64, 64, 3) or (N, 64, 64, 3); the GIL is released.")
      .def("_decode", &PyEncoder::decode, py::arg("z"), py::arg("decoder_path"))
      .def_property_readonly("name", [](const PyEncoder& e) { return e.rep().name; })
      .def_property_readonly("threads", &PyEncoder::threads)
      .def_property_readonly(
          "kl_order",
          [](const PyEncoder& e) {
            py::array_t<int64_t> a(nn::kLatents);
            for (int j = 0; j < nn::kLatents; ++j) a.mutable_at(j) = e.rep().kl_order[static_cast<size_t>(j)];
            return a;
          },
          "Latent indices by decreasing KL (SPEC §2.4).")
      .def_property_readonly(
          "kl_per_latent",
          [](const PyEncoder& e) {
            py::array_t<float> a(nn::kLatents);
            for (int j = 0; j < nn::kLatents; ++j) a.mutable_at(j) = e.rep().kl_per_latent[static_cast<size_t>(j)];
            return a;
          },
          "KL of each latent (nats), measured by the trainer.")
      .def_property_readonly("ball_latents", [](const PyEncoder& e) { return lab::ball_latents(e.rep().name); },
                             "The latents that encode the ball, from the trainer's factor report.")
      .def_property_readonly("inputs_sha256", [](const PyEncoder& e) { return e.rep().inputs_sha256; })
      .def(
          "modules",
          [](const PyEncoder& e, int group_size) {
            if (group_size < 1 || nn::kLatents % group_size != 0)
              value_error("group_size", "expected a divisor of 10 (1, 2, 5 or 10)");
            std::vector<std::vector<int>> mods;
            for (int k = 0; k < nn::kLatents / group_size; ++k) {
              std::vector<int> d;
              for (int j = 0; j < group_size; ++j)
                d.push_back(e.rep().kl_order[static_cast<size_t>(k * group_size + j)]);
              mods.push_back(d);
            }
            return mods;
          },
          py::arg("group_size") = 2,
          "Goal modules in KL order: consecutive groups of group_size latents (2: MGE's 5 pairs).");
  m.attr("_MODELS_DIR") = CURIO_MODELS_DIR;
}

}  // namespace curio::python
