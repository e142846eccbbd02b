// The model dir's settings.txt ("key value" lines): what a checkpoint needs to be rebuilt and
// what a resumed run must agree with. The same text is stored inside each checkpoint.
#pragma once
#include <cstdint>
#include <string>

#include "util/options.h"
#include "util/settings_file.h"

namespace tsrir {

// The settings' typed choices. Each enum's names (the command line's and the settings file's, one
// table) are listed once, in the k...Names tables below: GanSettings::Register hands them to
// RegisterEnum, and the settings file is written and read through those same Register calls
// (util/settings_file.h), so a value is validated in one place.
// kLoaded is not a setting (no name): a network built only to receive stored weights draws none
// for its convolution layers (a band-gain head's torch::nn::Linear still draws in its constructor).
enum class GanInit { kGlorot, kHe, kLoaded };
enum class GanDecoder { kOriginal, kLight };
enum class GanGenerator { kOriginal, kResidual, kBandGain };
enum class GanActivation { kRelu, kLeakyRelu };
enum class GanGeneratorUpdate { kSequential, kJoint };
enum class GanDiscAugment { kNone, kShiftGainPolarity };
enum class GanDiscView { kWaveform, kWaveformEnvelope, kWaveformSeparableEnvelope };
enum class GanEnvelopeReference { kLoudestCell, kDirectSound };
enum class GanPrecision { kFloat32, kBfloat16 };

inline const Choices<GanInit> kGanInitNames = {{"he", GanInit::kHe}, {"glorot", GanInit::kGlorot}};
inline const Choices<GanDecoder> kGanDecoderNames = {{"light", GanDecoder::kLight}, {"original", GanDecoder::kOriginal}};
inline const Choices<GanGenerator> kGanGeneratorNames = {
    {"band-gain", GanGenerator::kBandGain}, {"residual", GanGenerator::kResidual}, {"original", GanGenerator::kOriginal}};
inline const Choices<GanActivation> kGanActivationNames = {{"relu", GanActivation::kRelu},
                                                           {"leaky_relu", GanActivation::kLeakyRelu}};
inline const Choices<GanGeneratorUpdate> kGanGeneratorUpdateNames = {
    {"joint", GanGeneratorUpdate::kJoint}, {"sequential", GanGeneratorUpdate::kSequential}};
inline const Choices<GanDiscAugment> kGanDiscAugmentNames = {
    {"none", GanDiscAugment::kNone}, {"shift-gain-polarity", GanDiscAugment::kShiftGainPolarity}};
inline const Choices<GanDiscView> kGanDiscViewNames = {
    {"waveform", GanDiscView::kWaveform},
    {"waveform+envelope", GanDiscView::kWaveformEnvelope},
    {"waveform+separable-envelope", GanDiscView::kWaveformSeparableEnvelope}};
inline const Choices<GanEnvelopeReference> kGanEnvelopeReferenceNames = {
    {"loudest-cell", GanEnvelopeReference::kLoudestCell}, {"direct-sound", GanEnvelopeReference::kDirectSound}};
inline const Choices<GanPrecision> kGanPrecisionNames = {{"float32", GanPrecision::kFloat32},
                                                         {"bfloat16", GanPrecision::kBfloat16}};

// How an envelope view's critic maps band energies to levels (gan_band_envelope.h): re what, and
// how far below it the map is floored. What a discriminator computes, so part of the architecture;
// read only when disc_view has an envelope. Settings files without the keys: the first form's
// (the RIR's loudest cell, 80 dB).
struct GanEnvelopeMap {
  GanEnvelopeReference reference = GanEnvelopeReference::kLoudestCell;
  double floor_db = -80.0;
};

struct GanSettings {
  int width = 64;
  int kernel_length = 25;
  long long slice_length = 16384;
  double sample_rate_hz = 16000.0;
  int batch_size = 64;
  uint64_t seed = 0;
  double learning_rate = 3e-5;
  // The discriminators' own learning rate (two time-scale updates, Heusel et al. 2017); 0 = the
  // generators' (the original). Files without the key: 0.
  double disc_learning_rate = 0.0;
  int disc_updates = 2;
  // Departures from the original for small CPU models (defaults = the original): kernel init
  // (used only when a model is created) and the generators' L1 loss weights.
  GanInit init = GanInit::kGlorot;
  double cycle_weight = 250.0;     // per cycle L1 term (10 * 25)
  double identity_weight = 175.0;  // identity L1 (5 * 35)
  // Band-gain generators: weight of an L2 penalty on their predicted log gains (nepers^2, mean
  // over batch, bands and knots) in the generators' loss: a translation changes levels only where
  // the discriminators ask it to (a departure; the paper has no such term). Files without the
  // key: 0.
  double gain_weight = 0.0;
  // Band-gain generators: weight of the same L2 penalty on the log gains a generator predicts
  // after the direct sound (and at it below 250 Hz: gan::identity_held_gains) for RIRs of its own
  // domain (G_SR's for real RIRs, G_RS's for synthetic ones: the identity passes), which should
  // pass unchanged. A gain identity in the gains' own units (nepers), where a quiet band's late
  // level counts as much as its early one; the waveform identity L1 hardly sees a tail 40 dB down
  // (a departure; the paper has only the waveform identity). Issue 34: without it the decay kind's translators changed the 500-1000 Hz decay
  // with the 2-8 kHz one. 0 = none, the paper's (the toolkit's default: 10, gan_options.cc); files without the key: 0.
  double identity_gain_weight = 0.0;
  // Band-gain generators: how many of the lowest bands' direct-sound knots the gain identity
  // holds too (gan::identity_held_gains; 1 = band 0, below 250 Hz; 0 = none, the direct sound is
  // left to --gain-weight in every band). Files without the key: 1, the form before the key.
  int identity_direct_bands = 1;
  // Band-gain generators: weight of the same L2 penalty, for RIRs of their own domain, on the
  // direct-sound log gains of the bands the gain identity leaves out (from identity_direct_bands
  // up; mean over those knots): a weaker hold than the gain identity's on the direct sound, which
  // the direct kind's translators need to move and the low-frequency kind's must keep (issue 34:
  // held at the identity's weight the first moved 0.25-0.50 of the gap, not held the second's
  // mid/high-band DRR drifted 1.7-2.5 dB). 0 = none, the default; files without the key: 0.
  double identity_direct_weight = 0.0;
  // Residual and band-gain generators: weight of an L2 penalty on the waveform correction (its
  // mean square over time after the input's onset, in units of the input's own mean square;
  // mean over the translations) in the generators' loss: the correction adds only what the
  // discriminators ask for, as gain_weight does for the gains (a departure; the paper has no such
  // term; issue 34: without it band-gain's correction added 13-24 dB of low-frequency energy the
  // real domain did not have). 0 = none, the paper's (the toolkit's default: 1); files without the key: 0.
  double correction_weight = 0.0;
  double rmsprop_initial_ms = 1.0;  // RMSProp's initial mean square: 1 (TF, the original) or 0
  // Generator up-path channels: original (16w, 8w, 4w: the original's code, 66.6 M parameters
  // per generator at width 64) or light (4w, 2w, w: what the original's code comments say,
  // 41.4 M parameters and 1/3 of the FLOPs at width 64). Part of the architecture.
  GanDecoder decoder = GanDecoder::kOriginal;
  // original (tanh output, the paper); residual (output = input + a learned correction that
  // starts near zero); band-gain (the residual's correction plus a smooth gain per frequency band
  // and per time knot after the input's direct sound, applied to the input's own band signals:
  // gan_networks.h). Part of the architecture. Settings files without the key: original.
  GanGenerator generator = GanGenerator::kOriginal;
  // Residual and band-gain generators: the waveform correction is low-passed (nothing left from
  // this frequency up, in Hz) before it is added, so it can add only low-frequency structure
  // (room modes, diffraction: where the geometric simulator's ray assumption fails, the paper's
  // sec. 1-2); above it a residual generator's output is its input, a band-gain generator's its
  // input's own band signals times smooth gains. 0 = full band. Part of the architecture.
  // Settings files without the key: 0.
  double correction_max_hz = 0.0;
  // Generator hidden activation: relu (the original) or leaky_relu (slope 0.2, as the original's
  // discriminators). With plain ReLUs the small activations of RIR inputs (~1e-2: most samples are
  // a quiet tail) die under RMSProp's first lr-sized bias updates, after which the generator gets no
  // gradient and a residual one stays the identity for good. Part of the architecture. Files
  // without the key: relu.
  GanActivation generator_activation = GanActivation::kRelu;
  // How the two generators are updated per iteration: sequential (the original: a G_SR step and
  // then a G_RS step, each on fresh batches with its own forward graph, after the discriminator
  // steps) or joint (one forward of both generators on one pair of batches, one summed loss, both
  // stepped; the discriminators then train on those same translations, detached: CycleGAN's
  // reference implementation, about 1.6x fewer generator passes). Files without the key: sequential.
  GanGeneratorUpdate generator_update = GanGeneratorUpdate::kSequential;
  // Discriminator input augmentation (Zhao et al. 2020's DiffAugment, for small data sets): none
  // (the original) or shift-gain-polarity: every RIR a discriminator sees, real or translated, in
  // its own update and in the generators' adversarial terms, is delayed by 0-50 ms, scaled by
  // 0.6-1 and its polarity flipped at random. None of these changes what the translation must learn
  // (a room's spectral and decay character); they stop a discriminator from memorising the few
  // dozen training RIRs, after which its gradient no longer tells a generator where the real domain
  // lies. Files without the key: none.
  GanDiscAugment disc_augment = GanDiscAugment::kNone;
  // What the discriminators read: waveform (the original) or waveform+envelope: also each band's
  // level in dB per 8 ms frame (gan_band_envelope.h), where the quiet late part of an RIR, and with
  // it each band's decay and early energy, weighs as much as its loud start; the two critics'
  // logits are summed. Part of the architecture (the discriminators' weights). Files without the
  // key: waveform.
  GanDiscView disc_view = GanDiscView::kWaveform;
  // --envelope-reference, --envelope-floor-db (issue 34 item 3: on R3VIVAL the loudest cell, the 4 kHz
  // band's first frame, is ~6 dB stronger in GAS than in the measured room, and below 60 dB the
  // measured RIRs reach their noise floor inside the slice; docs/results/ts-rirgan-r3vival-seeds.md).
  GanEnvelopeMap envelope_map;
  // Linear learning-rate warm-up over the first N steps (0: none, the original).
  long long warmup_steps = 0;
  // Both generators also keep an exponential moving average of their weights over the training
  // steps (Polyak averaging, as GANs' generators commonly do: Yazici et al. 2019; Karras et al.
  // 2018), debiased so that step s weighs decay^(t - s) at step t whatever the initial weights:
  // translation uses it (gas-to-real --use-last-weights: the last step's). Training itself is
  // unchanged (the average never feeds back). Issue 34: a band-gain translator's kept parameters
  // swing by more than their bound between checkpoints 250 steps apart (bench/RESULTS.md). 0 = no
  // average, the original; files without the key: 0.
  double generator_average_decay = 0.0;
  GanPrecision precision = GanPrecision::kFloat32;  // training arithmetic (bfloat16: CPU autocast)
  std::string real_list;
  std::string synthetic_list;

  // The model's and training's options (gan_settings.cc): everything above but the fixed shape
  // (kernel, slice, rate) and the lists, which ts-rirgan-train takes as --real/--synthetic.
  void Register(OptionsItf* opts);
  // The settings file's entries (gan_settings.cc): Register's, then the fixed shape and the lists.
  void RegisterStored(OptionsItf* opts);
};

// The toolkit's training defaults (gan_options.cc), which depart from the paper's where the
// member initialisers above (the paper's, read for keys an older settings file lacks) do not pass
// the translation-fidelity suite.
GanSettings default_training_settings();

// Width multipliers of the generator's first three transposed convs for `decoder`.
void decoder_multipliers(GanDecoder decoder, int multipliers[3]);

// The settings file: one "key value" line per entry of RegisterStored, in the order files have
// always had (files written before a key existed still read: the key keeps the paper's value).
SettingsValues gan_settings_values(const GanSettings& settings);
std::string gan_settings_text(const GanSettings& settings);
// `where` names the file for errors (unknown key, bad value, wrong format version).
GanSettings parse_gan_settings(const std::string& text, const std::string& where);
// The settings' ranges, checked in one place for both of their sources: the command line
// (`file` empty: errors name "--width") and a settings file (errors name "<file>: width").
void check_gan_settings(const GanSettings& settings, const std::string& file);
GanSettings read_gan_settings_file(const std::string& path);
void write_gan_settings_file(const std::string& path, const GanSettings& settings);  // atomic

// Errors with a clear message if a resumed run or a loaded checkpoint does not match the model
// its settings describe (width, decoder, kernel, slice, rate); `what` names the two sides.
void check_same_architecture(const GanSettings& expected, const GanSettings& found,
                             const std::string& what);

}  // namespace tsrir
