// A model dir's settings.txt is written and read through GanSettings' Register calls
// (util/settings_file.h). The fixtures below are files written by the hand-written writer that came
// before (copied from model dirs it wrote): they must read and be written back byte for byte, and
// the older ones, written before some keys existed, must read with the paper's values for those.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "gan/gan_settings.h"
#include "util/error.h"
#include "util/options.h"

namespace tsrir {
namespace {

// ts-rirgan-train's defaults with the band-gain generator (tests/gan's fidelity runs, 2026-11-27).
const char kBandGainFile[] =
    "format tsrir-ts-rirgan-settings-v1\nwidth 8\nkernel_length 25\nslice_length 16384\nsample_rate_hz 16000\n"
    "batch_size 4\nseed 101\nlearning_rate 3.0000000000000001e-05\ndisc_learning_rate 0.0001\ndisc_updates 1\n"
    "init he\ncycle_weight 25\nidentity_weight 0\ngain_weight 1\nrmsprop_initial_ms 0\ndecoder light\n"
    "generator band-gain\ncorrection_max_hz 500\ngenerator_activation relu\ngenerator_update joint\n"
    "disc_augment none\nprecision float32\nwarmup_steps 100\nreal_list /tmp/h34_v2w8_direct_101/train_real/rir.scp\n"
    "synthetic_list /tmp/h34_v2w8_direct_101/train_syn/rir.scp\n";

// gan_cli_test's light-decoder bfloat16 model.
const char kBfloat16File[] =
    "format tsrir-ts-rirgan-settings-v1\nwidth 2\nkernel_length 25\nslice_length 16384\nsample_rate_hz 16000\n"
    "batch_size 2\nseed 3\nlearning_rate 3.0000000000000001e-05\ndisc_learning_rate 0.0001\ndisc_updates 1\n"
    "init he\ncycle_weight 25\nidentity_weight 0\ngain_weight 1\nrmsprop_initial_ms 0\ndecoder light\n"
    "generator residual\ncorrection_max_hz 500\ngenerator_activation relu\ngenerator_update joint\n"
    "disc_augment none\nprecision bfloat16\nwarmup_steps 100\nreal_list /tmp/m/real/rir.scp\n"
    "synthetic_list /tmp/m/syn/rir.scp\n";

// The Table 2 bench's translator, written before gain_weight existed.
const char kBeforeGainWeightFile[] =
    "format tsrir-ts-rirgan-settings-v1\nwidth 16\nkernel_length 25\nslice_length 16384\nsample_rate_hz 16000\n"
    "batch_size 4\nseed 0\nlearning_rate 3.0000000000000001e-05\ndisc_learning_rate 0.0001\ndisc_updates 1\n"
    "init he\ncycle_weight 25\nidentity_weight 0\nrmsprop_initial_ms 0\ndecoder light\ngenerator residual\n"
    "correction_max_hz 500\ngenerator_activation relu\ngenerator_update joint\ndisc_augment none\n"
    "precision float32\nwarmup_steps 100\nreal_list /b/real_train/rir_list\nsynthetic_list /b/gas_train/rir_list\n";

// The first format: the paper's model, before any departure had a key.
const char kFirstFormatFile[] =
    "format tsrir-ts-rirgan-settings-v1\nwidth 64\nkernel_length 25\nslice_length 16384\nsample_rate_hz 16000\n"
    "batch_size 64\nseed 7\nlearning_rate 3.0000000000000001e-05\ndisc_updates 2\nreal_list r.scp\n"
    "synthetic_list s.scp\n";

std::string error_of(const std::string& text) {
  try {
    parse_gan_settings(text, "m/settings.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The names a Register call declares.
struct NameRecorder : OptionsItf {
  std::set<std::string> names;
  void RegisterSpec(OptionSpec spec) override { names.insert(spec.name); }
  void RegisterAlias(const std::string&, const std::string&) override {}
};

TEST(GanSettingsFile, FilesOfTheHandWrittenWriterReadAndAreWrittenBackByteForByte) {
  for (const char* file : {kBandGainFile, kBfloat16File}) {
    EXPECT_EQ(gan_settings_text(parse_gan_settings(file, "fixture")), file);
  }
  const GanSettings s = parse_gan_settings(kBandGainFile, "fixture");
  EXPECT_EQ(s.width, 8);
  EXPECT_EQ(s.seed, 101u);
  EXPECT_EQ(s.learning_rate, 3e-5);
  EXPECT_EQ(s.generator, GanGenerator::kBandGain);
  EXPECT_EQ(s.decoder, GanDecoder::kLight);
  EXPECT_EQ(s.init, GanInit::kHe);
  EXPECT_EQ(s.warmup_steps, 100);
  EXPECT_EQ(s.real_list, "/tmp/h34_v2w8_direct_101/train_real/rir.scp");
  EXPECT_EQ(parse_gan_settings(kBfloat16File, "fixture").precision, GanPrecision::kBfloat16);
}

TEST(GanSettingsFile, KeysAFileLacksKeepThePapersValues) {
  const GanSettings paper;
  const GanSettings before_gain = parse_gan_settings(kBeforeGainWeightFile, "fixture");
  EXPECT_EQ(before_gain.gain_weight, paper.gain_weight);
  EXPECT_EQ(before_gain.generator, GanGenerator::kResidual);
  EXPECT_EQ(before_gain.correction_max_hz, 500.0);

  const GanSettings first = parse_gan_settings(kFirstFormatFile, "fixture");
  EXPECT_EQ(first.width, 64);
  EXPECT_EQ(first.seed, 7u);
  EXPECT_EQ(first.disc_learning_rate, paper.disc_learning_rate);
  EXPECT_EQ(first.generator, GanGenerator::kOriginal);
  EXPECT_EQ(first.decoder, GanDecoder::kOriginal);
  EXPECT_EQ(first.init, GanInit::kGlorot);
  EXPECT_EQ(first.cycle_weight, 250.0);
  EXPECT_EQ(first.identity_weight, 175.0);
  EXPECT_EQ(first.rmsprop_initial_ms, 1.0);
  EXPECT_EQ(first.generator_activation, GanActivation::kRelu);
  EXPECT_EQ(first.generator_update, GanGeneratorUpdate::kSequential);
  EXPECT_EQ(first.disc_augment, GanDiscAugment::kNone);
  EXPECT_EQ(first.warmup_steps, 0);
  EXPECT_EQ(first.generator_average_decay, 0.0);  // no average: the last weights translate
  EXPECT_EQ(first.envelope_map.reference, GanEnvelopeReference::kLoudestCell);  // the first envelope map
  EXPECT_EQ(first.envelope_map.floor_db, -80.0);
}

// A new option in GanSettings::Register is a new key of the file with no other edit.
TEST(GanSettingsFile, EveryRegisteredOptionIsAKeyAndEveryValueReadsBack) {
  NameRecorder recorder;
  GanSettings s = default_training_settings();
  s.Register(&recorder);
  s.correction_weight = 0.5;  // written only away from its default (added after files were written)
  s.disc_view = GanDiscView::kWaveformEnvelope;  // likewise
  s.envelope_map = {GanEnvelopeReference::kDirectSound, -60.0};  // likewise
  s.identity_gain_weight = 2;  // likewise
  s.identity_direct_bands = 0, s.identity_direct_weight = 0.5;  // likewise
  s.generator_average_decay = 0.99;  // likewise
  const SettingsValues values = gan_settings_values(s);
  ASSERT_GE(recorder.names.size(), 19u);
  for (std::string name : recorder.names) {
    for (char& c : name) c = c == '-' ? '_' : c;
    EXPECT_TRUE(values.count(name)) << name << " is an option but not a setting";
  }
  // Every field away from its default, every enum at each of its values.
  for (size_t k = 0; k < std::max(kGanGeneratorNames.size(), kGanDiscViewNames.size()); ++k) {
    s.width = 3 + int(k), s.batch_size = 5, s.seed = 18446744073709551615ull, s.learning_rate = 1.0 / 3;
    s.disc_learning_rate = 2e-7, s.disc_updates = 4, s.cycle_weight = 0.1, s.identity_weight = 1e300;
    s.gain_weight = 0.25, s.rmsprop_initial_ms = 1, s.correction_max_hz = 7999.5, s.warmup_steps = 1LL << 40;
    s.correction_weight = 0.125, s.identity_gain_weight = k % 2 ? 0.0 : 1.5;
    s.identity_direct_bands = k % 2 ? 1 : 3;
    s.identity_direct_weight = k % 2 ? 0.0 : 0.75;
    s.generator_average_decay = k % 2 ? 0.0 : 0.9995;
    s.generator = kGanGeneratorNames[k % kGanGeneratorNames.size()].second;
    s.init = kGanInitNames[k % 2].second, s.decoder = kGanDecoderNames[k % 2].second;
    s.generator_activation = kGanActivationNames[k % 2].second;
    s.generator_update = kGanGeneratorUpdateNames[k % 2].second;
    s.disc_augment = kGanDiscAugmentNames[k % 2].second, s.precision = kGanPrecisionNames[k % 2].second;
    s.disc_view = kGanDiscViewNames[k % kGanDiscViewNames.size()].second;
    // A map away from the first form only with an envelope view (check_gan_settings).
    s.envelope_map = s.disc_view == GanDiscView::kWaveform
                         ? GanEnvelopeMap{}
                         : GanEnvelopeMap{kGanEnvelopeReferenceNames[k % 2].second, k % 2 ? -80.0 : -60.25};
    s.real_list = "a b/real.scp", s.synthetic_list = "";
    const std::string text = gan_settings_text(s);
    const GanSettings back = parse_gan_settings(text, "written");
    EXPECT_EQ(gan_settings_text(back), text);
    EXPECT_EQ(back.learning_rate, 1.0 / 3);
    EXPECT_EQ(back.seed, 18446744073709551615ull);
    EXPECT_EQ(back.warmup_steps, 1LL << 40);
    EXPECT_EQ(back.correction_weight, 0.125);
    EXPECT_EQ(back.generator, s.generator);
    EXPECT_EQ(back.precision, s.precision);
    EXPECT_EQ(back.disc_view, s.disc_view);
    EXPECT_EQ(text.find("disc_view") != std::string::npos, s.disc_view != GanDiscView::kWaveform);
    EXPECT_EQ(back.envelope_map.reference, s.envelope_map.reference);
    EXPECT_EQ(back.envelope_map.floor_db, s.envelope_map.floor_db);
    EXPECT_EQ(text.find("envelope_reference") != std::string::npos,
              s.envelope_map.reference != GanEnvelopeReference::kLoudestCell);
    EXPECT_EQ(text.find("envelope_floor_db") != std::string::npos, s.envelope_map.floor_db != -80.0);
    EXPECT_EQ(back.identity_gain_weight, s.identity_gain_weight);
    EXPECT_EQ(text.find("identity_gain_weight") != std::string::npos, s.identity_gain_weight != 0.0);
    EXPECT_EQ(back.identity_direct_bands, s.identity_direct_bands);
    EXPECT_EQ(text.find("identity_direct_bands") != std::string::npos, s.identity_direct_bands != 1);
    EXPECT_EQ(back.identity_direct_weight, s.identity_direct_weight);
    EXPECT_EQ(text.find("identity_direct_weight") != std::string::npos, s.identity_direct_weight != 0.0);
    EXPECT_EQ(back.generator_average_decay, s.generator_average_decay);
    EXPECT_EQ(text.find("generator_average_decay") != std::string::npos, s.generator_average_decay != 0.0);
    EXPECT_EQ(back.real_list, "a b/real.scp");
    EXPECT_EQ(back.synthetic_list, "");
  }
}

TEST(GanSettingsFile, ErrorsNameTheFileAndLine) {
  const std::string head = "format tsrir-ts-rirgan-settings-v1\n";
  EXPECT_NE(error_of(head + "width 8\nwidth_x 3\n").find("m/settings.txt:3"), std::string::npos);
  EXPECT_NE(error_of(head + "width eight\n").find("m/settings.txt:2"), std::string::npos);
  const std::string bad_choice = error_of(head + "\n# a comment\ngenerator wavenet\n");
  EXPECT_NE(bad_choice.find("m/settings.txt:4"), std::string::npos) << bad_choice;
  EXPECT_NE(bad_choice.find("band-gain"), std::string::npos) << bad_choice;  // the choices are listed
  EXPECT_NE(error_of(head + "width 8\nwidth 9\n").find("given twice"), std::string::npos);
  EXPECT_NE(error_of("width 8\n").find("no 'format"), std::string::npos);
  EXPECT_NE(error_of("format tsrir-ts-rirgan-settings-v2\n").find("m/settings.txt:1"), std::string::npos);
  EXPECT_NE(error_of(head + "correction_max_hz 8000\n").find("correction_max_hz"), std::string::npos);
  EXPECT_NE(error_of(head + "warmup_steps -1\n").find("warmup_steps"), std::string::npos);
  EXPECT_NE(error_of(head + "identity_gain_weight -1\n").find("identity_gain_weight"), std::string::npos);
  EXPECT_NE(error_of(head + "identity_direct_bands 12\n").find("identity_direct_bands"), std::string::npos);
  const std::string envelope = head + "disc_view waveform+envelope\n";
  EXPECT_NE(error_of(envelope + "envelope_floor_db -10\n").find("envelope_floor_db"), std::string::npos);
  EXPECT_NE(error_of(envelope + "envelope_reference direct\n").find("direct-sound"), std::string::npos);
  // A map no critic reads is refused, not stored for nothing.
  EXPECT_NE(error_of(head + "envelope_reference direct-sound\n").find("envelope_reference"), std::string::npos);
  EXPECT_NE(error_of(head + "envelope_floor_db -60\n").find("envelope_reference"), std::string::npos);
  EXPECT_NE(error_of(head + "identity_direct_weight -1\n").find("identity_direct_weight"), std::string::npos);
  EXPECT_NE(error_of(head + "generator_average_decay 1\n").find("generator_average_decay must be in [0, 1)"), std::string::npos);
  EXPECT_NE(error_of(head + "generator_average_decay -0.5\n").find("generator_average_decay"), std::string::npos);
  EXPECT_NE(error_of(head + "slice_length 8192\n").find("unsupported"), std::string::npos);
  EXPECT_EQ(error_of(kFirstFormatFile), "");
}

// One range check serves ts-rirgan-train's command line and the settings file: the same rule,
// named as each source spells it.
TEST(GanSettingsFile, OneRangeCheckNamesTheOptionOrTheFileKey) {
  auto message = [](GanSettings s, const std::string& file) {
    try {
      check_gan_settings(s, file);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(GanSettings(), ""), "");
  GanSettings bad;
  bad.warmup_steps = -1;
  EXPECT_EQ(message(bad, ""), "--warmup-steps must be >= 0");
  EXPECT_EQ(message(bad, "m/settings.txt"), "m/settings.txt: warmup_steps must be >= 0");
  bad = GanSettings();
  bad.disc_learning_rate = -1e-4;
  EXPECT_EQ(message(bad, "m/settings.txt"), "m/settings.txt: disc_learning_rate must be >= 0");
  bad = GanSettings();
  bad.correction_max_hz = 8000;
  EXPECT_EQ(message(bad, ""), "--correction-max-hz must be in (0, 8000) or 0");
  bad = GanSettings();
  bad.width = 1025;
  EXPECT_EQ(message(bad, "f"), "f: width must be in [1, 1024]");
}

}  // namespace
}  // namespace tsrir
