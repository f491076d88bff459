#include "host_tools/vae/vae_model.hpp"


namespace curio::train {
namespace {

namespace nn = torch::nn;

nn::Conv2d conv(int64_t in) {
  return nn::Conv2d(nn::Conv2dOptions(in, 32, 4).stride(2).padding(1));
}
nn::ConvTranspose2d deconv(int64_t out) {
  return nn::ConvTranspose2d(nn::ConvTranspose2dOptions(32, out, 4).stride(2).padding(1));
}

// Kaiming-normal weights (fan-in, ReLU gain) and zero biases for every parameter of `m`.
void kaiming_reinit(nn::Module& m) {
  torch::NoGradGuard no_grad;
  for (auto& p : m.named_parameters()) {
    if (p.key().ends_with(".bias"))
      p.value().zero_();
    else
      nn::init::kaiming_normal_(p.value(), 0.0, torch::kFanIn, torch::kReLU);
  }
}

// One hidden layer whose units can be recycled. A unit's incoming weights are slices along
// in_dim of in_w (conv [out, in, k, k] and fc rows: dim 0; transposed conv [in, out, k, k]:
// dim 1) and in_per_unit consecutive entries of in_b; its outgoing weights are out_per_unit
// consecutive slices along out_dim of out_w. A per-unit count above 1 is a channel that a
// flatten spreads over 16 positions (encoder conv3 → fc1, decoder fc2 → deconv0).
struct RecyclableLayer {
  torch::Tensor in_w, in_b;
  int64_t in_dim, in_per_unit;
  torch::Tensor out_w;
  int64_t out_dim, out_per_unit;
};

torch::Tensor expand_units(const torch::Tensor& units, int64_t per_unit) {
  return per_unit == 1 ? units
                       : (units.unsqueeze(1) * per_unit + torch::arange(per_unit)).flatten();
}

// Units whose mean activation is at most threshold × their layer's mean get fresh Kaiming
// incoming weights, zero bias, and outgoing weights Kaiming × outgoing_scale (0: zero, the
// network's output is unchanged). Returns the count per layer.
template <size_t N>
std::array<int, N> recycle_dormant_units(const std::array<RecyclableLayer, N>& layers,
                                         const std::array<torch::Tensor, N>& activity,
                                         double threshold, double outgoing_scale) {
  std::array<int, N> recycled{};
  std::array<torch::Tensor, N> dormant;
  for (size_t l = 0; l < N; ++l) {
    dormant[l] = (activity[l] <= threshold * activity[l].mean()).nonzero().flatten();
    recycled[l] = static_cast<int>(dormant[l].numel());
    if (recycled[l] == 0) continue;
    const auto& L = layers[l];
    const auto rows = expand_units(dormant[l], L.in_per_unit);
    const auto fresh = torch::empty_like(L.in_w);
    nn::init::kaiming_normal_(fresh, 0.0, torch::kFanIn, torch::kReLU);
    L.in_w.index_copy_(L.in_dim, rows, fresh.index_select(L.in_dim, rows));
    L.in_b.index_fill_(0, rows, 0.0);
  }
  // Outgoing weights last, so a fresh incoming slice of the next layer cannot overwrite them.
  for (size_t l = 0; l < N; ++l) {
    if (recycled[l] == 0) continue;
    const auto& L = layers[l];
    const auto cols = expand_units(dormant[l], L.out_per_unit);
    if (outgoing_scale > 0.0) {
      const auto fresh = torch::empty_like(L.out_w);
      nn::init::kaiming_normal_(fresh, 0.0, torch::kFanIn, torch::kReLU);
      L.out_w.index_copy_(L.out_dim, cols, fresh.index_select(L.out_dim, cols).mul_(outgoing_scale));
    } else {
      L.out_w.index_fill_(L.out_dim, cols, 0.0);
    }
  }
  return recycled;
}

}  // namespace

EncoderImpl::EncoderImpl()
    : conv0(register_module("conv0", conv(3))),
      conv1(register_module("conv1", conv(32))),
      conv2(register_module("conv2", conv(32))),
      conv3(register_module("conv3", conv(32))),
      fc1(register_module("fc1", nn::Linear(512, 256))),
      fc2(register_module("fc2", nn::Linear(256, 256))),
      fc_out(register_module("fc_out", nn::Linear(256, 2 * kLatents))) {}

std::pair<torch::Tensor, torch::Tensor> EncoderImpl::forward(const torch::Tensor& x) {
  auto h = torch::relu(conv0(x));
  h = torch::relu(conv1(h));
  h = torch::relu(conv2(h));
  h = torch::relu(conv3(h));
  h = h.flatten(1);  // NCHW order: c*16 + h*4 + w
  h = torch::relu(fc1(h));
  h = torch::relu(fc2(h));
  auto out = fc_out(h);
  return {out.narrow(1, 0, kLatents), out.narrow(1, kLatents, kLatents)};
}

DecoderImpl::DecoderImpl()
    : fc1(register_module("fc1", nn::Linear(kLatents, 256))),
      fc2(register_module("fc2", nn::Linear(256, 512))),
      deconv0(register_module("deconv0", deconv(32))),
      deconv1(register_module("deconv1", deconv(32))),
      deconv2(register_module("deconv2", deconv(32))),
      deconv3(register_module("deconv3", deconv(3))) {}

torch::Tensor DecoderImpl::forward(const torch::Tensor& z) {
  auto h = torch::relu(fc1(z));
  h = torch::relu(fc2(h)).view({-1, 32, 4, 4});
  h = torch::relu(deconv0(h));
  h = torch::relu(deconv1(h));
  h = torch::relu(deconv2(h));
  return deconv3(h);
}

VaeImpl::VaeImpl()
    : enc(register_module("enc", Encoder())), dec(register_module("dec", Decoder())) {}

void VaeImpl::kaiming_init(double out_scale) {
  kaiming_reinit(*this);
  torch::NoGradGuard no_grad;
  enc->fc_out->weight.mul_(out_scale);
}

void VaeImpl::scale_encoder_output(double out_scale) {
  torch::NoGradGuard no_grad;
  enc->fc_out->weight.mul_(out_scale);
}

void VaeImpl::reinit_latent_layers(double out_scale) {
  torch::NoGradGuard no_grad;
  for (auto* layer : {&enc->fc_out, &dec->fc1}) {
    nn::init::kaiming_normal_((*layer)->weight, 0.0, torch::kFanIn, torch::kReLU);
    (*layer)->bias.zero_();
  }
  enc->fc_out->weight.mul_(out_scale);
}

void VaeImpl::hold_latents(const LatentMask& held) {
  torch::NoGradGuard no_grad;
  for (int l = 0; l < kLatents; ++l) {
    if (!held[static_cast<size_t>(l)]) continue;
    for (int64_t row : {int64_t{l}, l + kLatents}) {
      enc->fc_out->weight[row].zero_();
      enc->fc_out->bias[row].zero_();
    }
    dec->fc1->weight.select(1, l).zero_();
  }
}

void VaeImpl::mask_held_gradients(const LatentMask& held) {
  torch::NoGradGuard no_grad;
  for (int l = 0; l < kLatents; ++l) {
    if (!held[static_cast<size_t>(l)]) continue;
    for (int64_t row : {int64_t{l}, l + kLatents}) {
      if (enc->fc_out->weight.grad().defined()) enc->fc_out->weight.grad()[row].zero_();
      if (enc->fc_out->bias.grad().defined()) enc->fc_out->bias.grad()[row].zero_();
    }
    if (dec->fc1->weight.grad().defined()) dec->fc1->weight.grad().select(1, l).zero_();
  }
}

void VaeImpl::drop_encoder_feature_gradients(bool convs_only) {
  for (auto& p : enc->named_parameters()) {
    const bool feature = !p.key().starts_with("fc_out");
    if (feature && (!convs_only || p.key().starts_with("conv")))
      p.value().mutable_grad() = torch::Tensor();
  }
}

void VaeImpl::drop_decoder_feature_gradients() {
  for (auto& p : dec->named_parameters())
    if (!p.key().starts_with("fc1")) p.value().mutable_grad() = torch::Tensor();
}

void VaeImpl::release_latents(const LatentMask& which, double out_scale) {
  torch::NoGradGuard no_grad;
  const auto fresh_out = torch::empty_like(enc->fc_out->weight);
  nn::init::kaiming_normal_(fresh_out, 0.0, torch::kFanIn, torch::kReLU);
  fresh_out.mul_(out_scale);
  const auto fresh_in = torch::empty_like(dec->fc1->weight);
  nn::init::kaiming_normal_(fresh_in, 0.0, torch::kFanIn, torch::kReLU);
  for (int l = 0; l < kLatents; ++l) {
    if (!which[static_cast<size_t>(l)]) continue;
    for (int64_t row : {int64_t{l}, l + kLatents}) enc->fc_out->weight[row].copy_(fresh_out[row]);
    dec->fc1->weight.select(1, l).copy_(fresh_in.select(1, l));
  }
}

std::array<int, 6> VaeImpl::recycle_dormant_encoder_units(const torch::Tensor& x,
                                                          double threshold,
                                                          double outgoing_scale) {
  torch::NoGradGuard no_grad;
  // Per-unit mean activation of each feature layer (ReLU outputs, so ≥ 0).
  std::array<torch::Tensor, 6> activity;
  auto h = torch::relu(enc->conv0(x));
  activity[0] = h.mean({0, 2, 3});
  h = torch::relu(enc->conv1(h));
  activity[1] = h.mean({0, 2, 3});
  h = torch::relu(enc->conv2(h));
  activity[2] = h.mean({0, 2, 3});
  h = torch::relu(enc->conv3(h));
  activity[3] = h.mean({0, 2, 3});
  h = torch::relu(enc->fc1(h.flatten(1)));
  activity[4] = h.mean(0);
  h = torch::relu(enc->fc2(h));
  activity[5] = h.mean(0);

  const std::array<RecyclableLayer, 6> layers{
      RecyclableLayer{enc->conv0->weight, enc->conv0->bias, 0, 1, enc->conv1->weight, 1, 1},
      RecyclableLayer{enc->conv1->weight, enc->conv1->bias, 0, 1, enc->conv2->weight, 1, 1},
      RecyclableLayer{enc->conv2->weight, enc->conv2->bias, 0, 1, enc->conv3->weight, 1, 1},
      // conv3 channel u feeds fc1 inputs u*16 … u*16+15 (NCHW flatten).
      RecyclableLayer{enc->conv3->weight, enc->conv3->bias, 0, 1, enc->fc1->weight, 1, 16},
      RecyclableLayer{enc->fc1->weight, enc->fc1->bias, 0, 1, enc->fc2->weight, 1, 1},
      RecyclableLayer{enc->fc2->weight, enc->fc2->bias, 0, 1, enc->fc_out->weight, 1, 1}};
  return recycle_dormant_units(layers, activity, threshold, outgoing_scale);
}

std::array<int, 5> VaeImpl::recycle_dormant_decoder_units(const torch::Tensor& z,
                                                          double threshold,
                                                          double outgoing_scale) {
  torch::NoGradGuard no_grad;
  std::array<torch::Tensor, 5> activity;
  auto h = torch::relu(dec->fc1(z));
  activity[0] = h.mean(0);
  h = torch::relu(dec->fc2(h)).view({-1, 32, 4, 4});
  activity[1] = h.mean({0, 2, 3});
  h = torch::relu(dec->deconv0(h));
  activity[2] = h.mean({0, 2, 3});
  h = torch::relu(dec->deconv1(h));
  activity[3] = h.mean({0, 2, 3});
  h = torch::relu(dec->deconv2(h));
  activity[4] = h.mean({0, 2, 3});
  const std::array<RecyclableLayer, 5> layers{
      RecyclableLayer{dec->fc1->weight, dec->fc1->bias, 0, 1, dec->fc2->weight, 1, 1},
      // fc2's unit is a channel of its 4×4 output: rows c*16 … c*16+15.
      RecyclableLayer{dec->fc2->weight, dec->fc2->bias, 0, 16, dec->deconv0->weight, 0, 1},
      RecyclableLayer{dec->deconv0->weight, dec->deconv0->bias, 1, 1, dec->deconv1->weight, 0, 1},
      RecyclableLayer{dec->deconv1->weight, dec->deconv1->bias, 1, 1, dec->deconv2->weight, 0, 1},
      RecyclableLayer{dec->deconv2->weight, dec->deconv2->bias, 1, 1, dec->deconv3->weight, 0, 1}};
  return recycle_dormant_units(layers, activity, threshold, outgoing_scale);
}

LatentMask VaeImpl::revive(const torch::Tensor& x, double threshold, double outgoing_scale,
                           double out_scale, double collapsed_kl, bool fresh_decoder,
                           std::array<int, 11>& recycled) {
  LatentMask collapsed{};
  torch::Tensor mu;
  {
    torch::NoGradGuard no_grad;
    auto [m, logvar] = enc->forward(x);
    mu = m;
    const auto kl = kl_per_latent(m, logvar).to(torch::kFloat64).contiguous();
    for (int l = 0; l < kLatents; ++l)
      collapsed[static_cast<size_t>(l)] = kl.data_ptr<double>()[l] < collapsed_kl;
  }
  const auto enc_n = recycle_dormant_encoder_units(x, threshold, outgoing_scale);
  std::copy(enc_n.begin(), enc_n.end(), recycled.begin());
  if (fresh_decoder) {
    kaiming_reinit(*dec);
  } else {
    const auto dec_n = recycle_dormant_decoder_units(mu, threshold, outgoing_scale);
    std::copy(dec_n.begin(), dec_n.end(), recycled.begin() + 6);
  }
  release_latents(collapsed, out_scale);
  return collapsed;
}

std::array<double, kLatents> VaeImpl::reconstruction_cost_of_each_latent(const torch::Tensor& x) {
  torch::NoGradGuard no_grad;
  const auto mu = enc->forward(x).first;
  auto recon = [&](const torch::Tensor& z) {
    return torch::binary_cross_entropy_with_logits(dec->forward(z), x, {}, {},
                                                   at::Reduction::Sum)
               .item<double>() /
           static_cast<double>(x.size(0));
  };
  const double base = recon(mu);
  std::array<double, kLatents> cost{};
  for (int l = 0; l < kLatents; ++l) {
    auto z = mu.clone();
    z.select(1, l).zero_();
    cost[static_cast<size_t>(l)] = recon(z) - base;
  }
  return cost;
}

LatentMask VaeImpl::held_latents() const {
  torch::NoGradGuard no_grad;
  LatentMask held{};
  for (int l = 0; l < kLatents; ++l)
    held[static_cast<size_t>(l)] = dec->fc1->weight.select(1, l).abs().max().item<float>() == 0.0f &&
                                   enc->fc_out->weight[l].abs().max().item<float>() == 0.0f;
  return held;
}

void VaeImpl::reinit_decoder(double out_scale) {
  reinit_latent_layers(out_scale);
  kaiming_reinit(*dec);
}

torch::Tensor kl_per_latent(const torch::Tensor& mu, const torch::Tensor& logvar) {
  return (0.5 * (mu.pow(2) + logvar.exp() - logvar - 1.0)).mean(0);
}

}  // namespace curio::train
