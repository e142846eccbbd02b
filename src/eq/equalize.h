// Equalization matching (TS-RIR sec. 3.2, stage 2) for one RIR: given a target relative-gain
// vector, design the linear-phase EQ FIR, filter, put the direct sound back in place and keep
// the RIR's length and level convention.
//
// The first filter uses the literal correction (target - measured) at the nodes. Because the
// curve is interpolated smoothly between nodes, each octave band also sees part of its
// neighbours' corrections (and the 1 kHz reference band moves too), so the measured gains of
// the result would miss the target by a fraction of the neighbouring corrections. With
// refine_iterations > 0 the node corrections are then adjusted by Newton steps on the
// predicted gains of the filtered RIR (its power spectrum times the FIR's), which converges in
// 2-3 steps (the first ones on the ideal curve, without designing a filter). Cropping the result
// to the input length removes the filter's ringing before sample 0 (of a direct sound near the
// start) and after the end, which the prediction cannot see, so the written RIR is measured and,
// if it still misses the target by > 0.1 dB, corrected by up to two more Newton steps on the
// measured gains. refine_iterations = 0 is the paper's single design.
#pragma once
#include <string>

#include "eq/eq_fir.h"
#include "eq/relative_gain.h"
#include "io/signal.h"

namespace tsrir {

// Output level convention.
enum class EqLevel {
  kPeak,    // max |y| = max |x| (a peak-normalised set stays peak-normalised)
  kEnergy,  // sum y^2 = sum x^2
  kNone,    // the filter's own gain (0 dB at 1 kHz)
};
const Choices<EqLevel>& eq_level_choices();      // "peak" | "energy" | "none"
EqLevel parse_eq_level(const std::string& name);
std::string eq_level_name(EqLevel level);

struct EqApplyOptions {
  GainMethod gain_method = GainMethod::kOctave;
  EqFirOptions fir;
  int refine_iterations = 3;
  // Node corrections are clamped to [-max_cut_db, max_boost_db]. Boosts are limited harder: they
  // raise whatever noise the RIR has in that band. A steep real roll-off needs deep cuts (a band
  // level is a power mean, dominated by its loudest part, so the node goes well below the band).
  double max_boost_db = 24.0;
  double max_cut_db = 60.0;
  double tolerance_db = 0.05;       // refinement stops when every predicted gain is this close
  EqLevel level = EqLevel::kPeak;
  bool measure_output = false;      // also measure the output's gains (EqResult::after_db)
};

struct EqResult {
  Signal rir;                        // same id, rate and length as the input
  RelativeGainsDb before_db{};       // measured on the input
  RelativeGainsDb target_db{};
  RelativeGainsDb predicted_db{};    // of the final filter applied to the input spectrum
  RelativeGainsDb after_db{};        // measured on the output (only if measure_output)
  EqNodeGainsDb node_gains_db{};     // the final filter's node gains
  bool clamped = false;              // some final node gain sits at a clamp
  int filters_designed = 0;
};

// Errors name rir.id: silent RIR, a band without energy, an unsupported rate.
EqResult equalize_rir(const Signal& rir, const RelativeGainsDb& target_db, const EqApplyOptions& options);

// A microphone array's RIR (channels[c] = microphone c, channel 0 the reference): the EQ is
// designed on channel 0 by equalize_rir() (result.rir is its output) and the same final filter and
// level factor are applied to every other channel (*others, in order), so the channels keep their
// arrival-time and level differences.
EqResult equalize_rir_channels(const std::vector<Signal>& channels, const RelativeGainsDb& target_db,
                               const EqApplyOptions& options, std::vector<Signal>* others);

// Filters with a linear-phase FIR and removes its (taps-1)/2 delay: y[n] = (x * h)[n + (taps-1)/2]
// for n in [0, x.size()).
std::vector<float> filter_zero_delay(const std::vector<float>& x, const std::vector<float>& taps);

}  // namespace tsrir
