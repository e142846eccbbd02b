// Noise types: how a kind of noise in a Kaldi noise list (--noise-type) is weighted and added to a
// recording. A type decides, per recording, zero or more PlannedNoise entries; everything after
// that (the wav.scp pipe, the in-memory and streaming signal paths) handles a PlannedNoise the
// same way whatever its type. Adding a type = one file with a NoiseType subclass and its factory
// listed in noise_types.cc, plus its test.
#pragma once
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "augment/augment_sources.h"
#include "augment/sampling.h"
#include "util/rng.h"

namespace tsrir {

// One noise added to one recording. The noise signal is first made as Kaldi's nested
// `wav-reverberate [--impulse-response=<rir>] [--duration=<extend_to_s>] <noise> -` would (when
// rir >= 0 or extend_to_s > 0), then added to the reverberant speech at start_time_s and snr_db.
struct PlannedNoise {
  long noise = -1;              // index into AugmentSources::noises
  long rir = -1;                // RIR the noise is convolved with (a point source in the room), -1 none
  double extend_to_s = 0.0;     // > 0: repeated (or cut) to this duration (Kaldi's background noise)
  double start_time_s = 0.0;    // where it enters the speech
  double snr_db = 0.0;
  bool foreground = false;      // drew its SNR from --foreground-snrs
  // tsrir extension (--noise-start=random): start at a random point of the noise and loop it
  // over the whole recording instead of extending it from its start.
  bool loop = false;
  double offset_fraction = 0.0;  // in [0, 1) of the noise's duration
  double offset_s = 0.0;         // resolved from the fraction (resolve_noise_offsets)
  bool needs_nested_reverberation() const { return rir >= 0 || extend_to_s > 0; }
};

struct NoisePlanOptions {
  double isotropic_noise_addition_probability = 1.0;
  double pointsource_noise_addition_probability = 1.0;
  int max_noises_per_minute = 2;       // Kaldi: 1..floor(N * duration / 60) point-source noises
  int max_noises_per_recording = 0;    // extension: > 0 replaces the per-minute cap by this
  bool random_noise_start = false;     // extension: --noise-start=random
  bool point_source_noise_rir = true;  // extension off: point sources added without an RIR
};

struct NoisePlanContext {
  const AugmentSources& sources;
  const std::string& room;       // room of the recording's RIR draw ("" = no RIRs at all)
  double duration_s;             // the recording's duration (reco2dur)
  const NoisePlanOptions& options;
  Rng& rng;                      // this recording's generator
  SnrSequence& foreground_snrs;
  SnrSequence& background_snrs;
};

class NoiseType {
 public:
  virtual ~NoiseType() = default;
  virtual std::string name() const = 0;  // the --noise-type value in noise lists
  // Checks one list entry of this type (errors and warnings name entry.where).
  virtual void check(const NoiseChoice& entry, const std::set<std::string>& rooms) const = 0;
  // Sets NoiseChoice::probability for all entries of this type, given the noise set weights.
  virtual void assign_probabilities(const std::vector<NoiseChoice*>& entries, const std::vector<double>& set_weights,
                                    double smoothing_weight) const = 0;
  // Appends the noises this type adds to one recording.
  virtual void plan(const NoisePlanContext& context, std::vector<PlannedNoise>* out) const = 0;
};

// The registered types, in the order Kaldi adds them to a recording (isotropic, then point-source).
const std::vector<std::unique_ptr<NoiseType>>& noise_types();
const NoiseType* find_noise_type(const std::string& name);

// Helpers for types.
// The index (into sources.noises) among `candidates` drawn by their probabilities, u in [0, 1).
size_t draw_noise(const AugmentSources& sources, const std::vector<size_t>& candidates, double u);
// A background noise as Kaldi adds it: extended to the recording's duration, from time 0, SNR
// from --background-snrs; with --noise-start=random, looped from a random offset instead.
PlannedNoise background_noise(const NoisePlanContext& context, size_t noise, long rir);

}  // namespace tsrir
