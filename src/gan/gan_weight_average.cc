#include "gan/gan_weight_average.h"

#include <cmath>
#include <string>

#include "gan/gan_networks.h"
#include "util/error.h"

namespace tsrir {
namespace gan {
namespace {

// The two modules' parameters, paired by name (the same order, since they were built alike);
// visit(average, live) gets tensor handles, so in-place changes reach the module.
template <typename Visit>
void for_each_parameter_pair(torch::nn::Module& average, torch::nn::Module& live, Visit visit) {
  const auto averaged = average.named_parameters();
  const auto current = live.named_parameters();
  if (averaged.size() != current.size()) throw Error("weight average: the two networks differ in their parameters");
  for (size_t i = 0; i < current.size(); ++i) {
    if (averaged[i].key() != current[i].key() || !averaged[i].value().sizes().equals(current[i].value().sizes())) {
      throw Error("weight average: parameter " + current[i].key() + " differs between the two networks");
    }
    visit(averaged[i].value(), current[i].value());
  }
}

}  // namespace

double weight_average_rate(double decay, long long step) {
  if (step < 1) throw Error("weight average: steps count from 1");
  if (decay <= 0) return 1.0;
  // 1 - decay^step without cancellation for decay near 1.
  return (1.0 - decay) / -std::expm1(double(step) * std::log(decay));
}

void start_weight_average(torch::nn::Module& average, torch::nn::Module& live) {
  torch::NoGradGuard no_grad;
  for_each_parameter_pair(average, live, [](torch::Tensor a, const torch::Tensor& w) {
    a.copy_(w);
    a.set_requires_grad(false);
  });
}

void update_weight_average(torch::nn::Module& average, torch::nn::Module& live, double decay, long long step) {
  const double rate = weight_average_rate(decay, step);
  torch::NoGradGuard no_grad;
  for_each_parameter_pair(average, live, [rate](torch::Tensor a, const torch::Tensor& w) { a.lerp_(w, rate); });
}

void update_generator_averages(CycleGan& model, long long step) {
  if (!model.g_real_average) return;
  const double decay = model.settings.generator_average_decay;
  update_weight_average(*model.g_real_average, *model.g_real, decay, step);
  update_weight_average(*model.g_synthetic_average, *model.g_synthetic, decay, step);
}

}  // namespace gan
}  // namespace tsrir
