// The generators' exponential moving average of weights (GanSettings::generator_average_decay):
// translation uses the average of the weights over the last ~1/(1-decay) steps instead of the
// last step's, which in adversarial training swing around the equilibrium from step to step.
// Private to src/gan (and its unit tests), as gan_networks.h.
#pragma once
#include <torch/torch.h>

namespace tsrir {
namespace gan {

struct CycleGan;

// The weight step `step` (1, 2, ...) gives the live weights in the debiased average: (1 - decay) /
// (1 - decay^step), so that after step t the average is sum_s decay^(t-s) w_s / sum_s decay^(t-s)
// over s = 1..t, whatever it started from (at step 1 it is w_1).
double weight_average_rate(double decay, long long step);

// average <- live, parameter by parameter (the same architecture, checked by name and shape).
void start_weight_average(torch::nn::Module& average, torch::nn::Module& live);

// average <- average + rate * (live - average), with weight_average_rate(decay, step).
void update_weight_average(torch::nn::Module& average, torch::nn::Module& live, double decay, long long step);

// Both generators' averages after training step `step`; nothing when the model keeps none.
void update_generator_averages(CycleGan& model, long long step);

}  // namespace gan
}  // namespace tsrir
