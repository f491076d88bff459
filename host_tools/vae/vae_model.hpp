// The SPEC §3 network in LibTorch: convolutional encoder to 10 Gaussian latents and the
// transposed decoder to Bernoulli logits over 3×64×64 pixels. Submodule names give the
// state-dict names the exporter writes ("enc.conv0.weight", …, "dec.deconv3.bias").
#pragma once
#include <array>
#include <utility>

#include <torch/torch.h>

namespace curio::train {

inline constexpr int64_t kLatents = 10;

struct EncoderImpl : torch::nn::Module {
  EncoderImpl();
  // x: [B,3,64,64] in [0,1] → (μ, log σ²), each [B,10].
  std::pair<torch::Tensor, torch::Tensor> forward(const torch::Tensor& x);

  torch::nn::Conv2d conv0{nullptr}, conv1{nullptr}, conv2{nullptr}, conv3{nullptr};
  torch::nn::Linear fc1{nullptr}, fc2{nullptr}, fc_out{nullptr};
};
TORCH_MODULE(Encoder);

struct DecoderImpl : torch::nn::Module {
  DecoderImpl();
  // z: [B,10] → logits [B,3,64,64].
  torch::Tensor forward(const torch::Tensor& z);

  torch::nn::Linear fc1{nullptr}, fc2{nullptr};
  torch::nn::ConvTranspose2d deconv0{nullptr}, deconv1{nullptr}, deconv2{nullptr},
      deconv3{nullptr};
};
TORCH_MODULE(Decoder);

// true for each latent held at the prior (see VaeImpl::hold_latents).
using LatentMask = std::array<bool, kLatents>;

struct VaeImpl : torch::nn::Module {
  VaeImpl();
  // Kaiming-normal weights (fan-in, ReLU gain) and zero biases: with PyTorch's default
  // init the encoder output barely varies between images and training sticks at the
  // mean image (measured here on Arm-2-Balls scenes).
  // out_scale multiplies the encoder's last layer (μ, log σ²) weights afterwards: a small
  // value starts training with KL ≈ 0 instead of a large random KL.
  void kaiming_init(double out_scale = 1.0);
  // enc.fc_out weights × out_scale, nothing else (keeps whatever init the layers have).
  void scale_encoder_output(double out_scale);
  // Kaiming re-init of only enc.fc_out (× out_scale) and dec.fc1, the layers that touch z.
  void reinit_latent_layers(double out_scale);
  // Kaiming re-init of enc.fc_out (× out_scale) and every decoder layer.
  void reinit_decoder(double out_scale);
  // Held latents sit at the prior: their rows of enc.fc_out (μ and log σ²) and their column
  // of dec.fc1 are zero, so z = ε ~ N(0,1), KL = 0 and the decoder ignores them.
  void hold_latents(const LatentMask& held);
  // Zero the gradients of the held latents' weights (call after backward) so they stay zero.
  void mask_held_gradients(const LatentMask& held);
  // Freeze the encoder's feature layers for this step (call after backward): their gradients
  // become undefined, so Adam leaves them exactly as they are (a zeroed gradient would still
  // move them by the momentum). convs_only: only the 4 convs; fc1 and fc2 keep training.
  void drop_encoder_feature_gradients(bool convs_only);
  // The same for the decoder's layers after dec.fc1 (fc2 and the 4 transposed convs).
  void drop_decoder_feature_gradients();
  // Fresh weights for the marked latents (fc_out rows Kaiming × out_scale, dec.fc1 columns
  // Kaiming): from here on they train like the others.
  void release_latents(const LatentMask& which, double out_scale);
  // Dormant-unit recycling of the encoder's feature layers (conv0..3 channels, fc1 and fc2
  // units): a unit whose mean activation on x is at most `threshold` × its layer's mean gets
  // fresh Kaiming incoming weights, zero bias and zero outgoing weights, so the network's
  // output is unchanged but the unit reads the image afresh. Units that only the ball's code
  // used lose the distractor for good otherwise (docs/training.md, trials r1/r2).
  // outgoing_scale > 0: the outgoing weights become Kaiming × outgoing_scale instead of zero,
  // so the fresh unit reaches the next layer at once (with zero outgoing weights a chain of
  // recycled layers passes no signal and no gradient: every link is zero).
  // Returns how many units each of the six layers recycled.
  std::array<int, 6> recycle_dormant_encoder_units(const torch::Tensor& x, double threshold,
                                                   double outgoing_scale = 0.0);
  // The same for the decoder's hidden layers (fc1 units, fc2's 32 channels of 4×4, the
  // channels of deconv0..2), measured on decoding z. Returns the counts per layer.
  std::array<int, 5> recycle_dormant_decoder_units(const torch::Tensor& z, double threshold,
                                                   double outgoing_scale);
  // One-shot revival of a code stuck on one object (docs/training.md, trials R1/V): recycle the
  // encoder's dormant units with live outgoing weights (outgoing_scale), give the decoder
  // fresh Kaiming weights (fresh_decoder) or recycle its dormant units the same way (keeps the
  // path the active latents use), and give every latent whose mean KL on x is below collapsed_kl fresh
  // read-out weights (enc.fc_out rows × out_scale). Active latents keep their read-out, so the
  // code they carry survives. Returns the latents revived; `recycled` gets the unit counts.
  LatentMask revive(const torch::Tensor& x, double threshold, double outgoing_scale,
                    double out_scale, double collapsed_kl, bool fresh_decoder,
                    std::array<int, 11>& recycled);
  // For each latent l: how many nats per image the reconstruction of x loses when z_l alone
  // is set to the prior mean (0) and the others to μ (noise-free). A latent that carries a
  // whole object scores high even when its KL is low.
  std::array<double, kLatents> reconstruction_cost_of_each_latent(const torch::Tensor& x);
  // The latents whose weights are all zero (held), read back from the weights (for --resume).
  LatentMask held_latents() const;

  Encoder enc{nullptr};
  Decoder dec{nullptr};
};
TORCH_MODULE(Vae);

// Per-latent KL(q(z|x) ‖ N(0,1)) averaged over the batch: [10].
torch::Tensor kl_per_latent(const torch::Tensor& mu, const torch::Tensor& logvar);

}  // namespace curio::train
