#include "train/vae_model.hpp"

namespace curio::train {
namespace {

namespace nn = torch::nn;

nn::Conv2d conv(int64_t in) {
  return nn::Conv2d(nn::Conv2dOptions(in, 32, 4).stride(2).padding(1));
}
nn::ConvTranspose2d deconv(int64_t out) {
  return nn::ConvTranspose2d(nn::ConvTranspose2dOptions(32, out, 4).stride(2).padding(1));
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
  torch::NoGradGuard no_grad;
  for (auto& p : named_parameters()) {
    if (p.key().ends_with(".bias"))
      p.value().zero_();
    else
      nn::init::kaiming_normal_(p.value(), 0.0, torch::kFanIn, torch::kReLU);
  }
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

  // Incoming weights (rows of these), and where each unit's outgoing weights sit.
  const std::array<torch::Tensor, 6> in_w{enc->conv0->weight, enc->conv1->weight,
                                          enc->conv2->weight, enc->conv3->weight,
                                          enc->fc1->weight,   enc->fc2->weight};
  const std::array<torch::Tensor, 6> in_b{enc->conv0->bias, enc->conv1->bias, enc->conv2->bias,
                                          enc->conv3->bias, enc->fc1->bias,   enc->fc2->bias};
  const std::array<torch::Tensor, 6> out_w{enc->conv1->weight, enc->conv2->weight,
                                           enc->conv3->weight, enc->fc1->weight,
                                           enc->fc2->weight,   enc->fc_out->weight};
  std::array<int, 6> recycled{};
  std::array<torch::Tensor, 6> dormant;
  for (size_t l = 0; l < activity.size(); ++l) {
    dormant[l] = (activity[l] <= threshold * activity[l].mean()).nonzero().flatten();
    recycled[l] = static_cast<int>(dormant[l].numel());
    if (recycled[l] == 0) continue;
    const auto fresh = torch::empty_like(in_w[l]);
    nn::init::kaiming_normal_(fresh, 0.0, torch::kFanIn, torch::kReLU);
    in_w[l].index_copy_(0, dormant[l], fresh.index_select(0, dormant[l]));
    in_b[l].index_fill_(0, dormant[l], 0.0);
  }
  // Outgoing weights last, so a fresh row in the next layer cannot bring them back.
  for (size_t l = 0; l < activity.size(); ++l) {
    if (recycled[l] == 0) continue;
    // conv3 channel u feeds fc1 inputs u*16 … u*16+15 (NCHW flatten).
    const auto inputs = l == 3 ? (dormant[l].unsqueeze(1) * 16 + torch::arange(16)).flatten()
                               : dormant[l];
    if (outgoing_scale > 0.0) {
      const auto fresh = torch::empty_like(out_w[l]);
      nn::init::kaiming_normal_(fresh, 0.0, torch::kFanIn, torch::kReLU);
      out_w[l].index_copy_(1, inputs, fresh.index_select(1, inputs).mul_(outgoing_scale));
    } else {
      out_w[l].index_fill_(1, inputs, 0.0);
    }
  }
  return recycled;
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
  // A unit's incoming weights are slices along in_dim of in_w (fc: rows; transposed conv
  // [in, out, k, k]: dim 1), its outgoing ones along out_dim of out_w. fc2's unit is a channel
  // of its 4×4 output: rows c*16 … c*16+15.
  struct Layer {
    torch::Tensor in_w, in_b;
    int64_t in_dim;
    torch::Tensor out_w;
    int64_t out_dim;
    int64_t rows_per_unit;
  };
  const std::array<Layer, 5> layers{
      Layer{dec->fc1->weight, dec->fc1->bias, 0, dec->fc2->weight, 1, 1},
      Layer{dec->fc2->weight, dec->fc2->bias, 0, dec->deconv0->weight, 0, 16},
      Layer{dec->deconv0->weight, dec->deconv0->bias, 1, dec->deconv1->weight, 0, 1},
      Layer{dec->deconv1->weight, dec->deconv1->bias, 1, dec->deconv2->weight, 0, 1},
      Layer{dec->deconv2->weight, dec->deconv2->bias, 1, dec->deconv3->weight, 0, 1}};
  std::array<int, 5> recycled{};
  std::array<torch::Tensor, 5> dormant;
  for (size_t l = 0; l < layers.size(); ++l) {
    dormant[l] = (activity[l] <= threshold * activity[l].mean()).nonzero().flatten();
    recycled[l] = static_cast<int>(dormant[l].numel());
    if (recycled[l] == 0) continue;
    const auto& L = layers[l];
    const auto rows = L.rows_per_unit == 1
                          ? dormant[l]
                          : (dormant[l].unsqueeze(1) * L.rows_per_unit +
                             torch::arange(L.rows_per_unit))
                                .flatten();
    const auto fresh = torch::empty_like(L.in_w);
    nn::init::kaiming_normal_(fresh, 0.0, torch::kFanIn, torch::kReLU);
    L.in_w.index_copy_(L.in_dim, rows, fresh.index_select(L.in_dim, rows));
    L.in_b.index_fill_(0, rows, 0.0);
  }
  for (size_t l = 0; l < layers.size(); ++l) {
    if (recycled[l] == 0) continue;
    const auto& L = layers[l];
    if (outgoing_scale > 0.0) {
      const auto fresh = torch::empty_like(L.out_w);
      nn::init::kaiming_normal_(fresh, 0.0, torch::kFanIn, torch::kReLU);
      L.out_w.index_copy_(L.out_dim, dormant[l],
                          fresh.index_select(L.out_dim, dormant[l]).mul_(outgoing_scale));
    } else {
      L.out_w.index_fill_(L.out_dim, dormant[l], 0.0);
    }
  }
  return recycled;
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
    torch::NoGradGuard no_grad;
    for (auto& p : dec->named_parameters()) {
      if (p.key().ends_with(".bias"))
        p.value().zero_();
      else
        nn::init::kaiming_normal_(p.value(), 0.0, torch::kFanIn, torch::kReLU);
    }
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
  torch::NoGradGuard no_grad;
  reinit_latent_layers(out_scale);
  for (auto& p : dec->named_parameters()) {
    if (p.key().ends_with(".bias"))
      p.value().zero_();
    else
      nn::init::kaiming_normal_(p.value(), 0.0, torch::kFanIn, torch::kReLU);
  }
}

torch::Tensor kl_per_latent(const torch::Tensor& mu, const torch::Tensor& logvar) {
  return (0.5 * (mu.pow(2) + logvar.exp() - logvar - 1.0)).mean(0);
}

}  // namespace curio::train
