// The acceptance test: a "real" set carries a hidden effect (a resonance region around
// 125 Hz and a high-frequency roll-off, varied per RIR, made here with the test's own biquads);
// after `rir-eq fit` on it and `rir-eq apply`, the equalized set's relative gains must follow the
// real set's distribution while T60 and DRR of each RIR barely move.
//
// Two synthetic sets are equalized:
//  * rir-simulate output (the synthetic set);
//  * decaying white noise with a direct impulse (direct and reverberant parts share a spectrum).
// T60 (ISO, mean of the 500 Hz and 1 kHz T30) must change by < 5 % for every RIR of both sets.
// DRR (+-2.5 ms around the peak) cannot stay within 0.5 dB for every RIR under a pure filter,
// for two physical reasons measured here:
//  * rir-simulate's direct sound is spectrally flat while its reverberant tail is darker (air and
//    surface absorption grow with frequency), so cutting high frequencies -- the hidden roll-off
//    -- lowers the direct energy more than the reverberant energy (mean -0.35 dB, up to -1.5 dB);
//  * a low-frequency boost (the per-RIR draw can ask for +8 dB at 62.5 Hz) spreads the direct
//    sound's energy below ~200 Hz beyond the 5 ms direct window (up to 0.65 dB on white reverb).
// So the DRR criterion is checked as: the set's mean DRR moves by < 0.5 dB (both sets); on the
// white-reverb set at least 95 % of RIRs move by < 0.5 dB and none by 1 dB or more; on the
// simulated set none by 2 dB or more. The worst values are printed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "eq/eq_set.h"
#include "eq_test_util.h"
#include "io/audio_io.h"
#include "io/rir_set.h"
#include "metrics/rir_metrics.h"
#include "util/rng.h"

using namespace tsrir;

namespace {

const std::string kBin = TSRIR_BIN_DIR;

int run(const std::string& command, const std::string& log) {
  return std::system((command + " >>" + log + " 2>&1").c_str());
}

// Random shoebox rooms, sources and microphones for rir-simulate.
std::string room_list(const std::string& prefix, int count, uint64_t seed) {
  Rng rng(seed);
  std::ostringstream out;
  for (int i = 0; i < count; ++i) {
    const double lx = rng.uniform(4, 9), ly = rng.uniform(3, 7), lz = rng.uniform(2.5, 3.5);
    auto inside = [&](double l) { return rng.uniform(0.6, l - 0.6); };
    out << prefix << i / 10 << i % 10 << " room=" << lx << ',' << ly << ',' << lz << " src=" << inside(lx) << ','
        << inside(ly) << ',' << rng.uniform(1.0, 1.8) << " mic=" << inside(lx) << ',' << inside(ly) << ','
        << rng.uniform(1.0, 1.8) << " t60=" << rng.uniform(0.35, 0.8) << '\n';
  }
  return out.str();
}

void write_set(const std::vector<Signal>& rirs, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream scp(dir + "/rir.scp");
  for (const Signal& s : rirs) {
    AudioWriteOptions o;
    o.format = SampleFormat::kFloat32;
    write_wav(dir + "/" + s.id + ".wav", s, o);
    scp << s.id << ' ' << dir << "/" << s.id << ".wav\n";
  }
}

std::vector<Signal> load_set(const std::string& scp) {
  std::vector<Signal> out;
  for (const RirRef& ref : read_rir_refs(scp, nullptr)) out.push_back(load_rir(ref));
  return out;
}

// Lag (in [-max_lag, max_lag]) of the largest cross-correlation of b against a.
int best_lag(const std::vector<float>& a, const std::vector<float>& b, int max_lag) {
  int best = 0;
  double best_value = -INFINITY;
  for (int lag = -max_lag; lag <= max_lag; ++lag) {
    double acc = 0;
    for (size_t n = 0; n < a.size(); ++n) {
      const long m = static_cast<long>(n) + lag;
      if (m >= 0 && m < static_cast<long>(b.size())) acc += static_cast<double>(a[n]) * b[m];
    }
    if (acc > best_value) {
      best_value = acc;
      best = lag;
    }
  }
  return best;
}

struct Sets {
  std::string log, real_scp, simulated_scp, noise_scp;
};

class HiddenEffect : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new tsrir_test::ScratchDir("HiddenEffect");
    sets_.log = dir_->path("log.txt");
    dir_->write("sim_rooms.txt", room_list("sim", 60, 1));
    dir_->write("real_rooms.txt", room_list("real", 80, 2));
    ASSERT_EQ(0, run(kBin + "/rir-simulate --fs=16000 --length=1.0 --format=float --seed=1 " +
                         dir_->path("sim_rooms.txt") + " " + dir_->path("sim"), sets_.log));
    ASSERT_EQ(0, run(kBin + "/rir-simulate --fs=16000 --length=1.0 --format=float --seed=2 " +
                         dir_->path("real_rooms.txt") + " " + dir_->path("real_base"), sets_.log));
    sets_.simulated_scp = dir_->path("sim/rir.scp");
    // The hidden effect, drawn per RIR: a peaking resonance near 125 Hz (+4.5..+7.5 dB, centre
    // within +-0.2 octave, Q 1.2) and a 2nd-order low-pass at 4.5..6.5 kHz.
    Rng rng(3);
    std::vector<Signal> real = load_set(dir_->path("real_base/rir.scp"));
    for (Signal& s : real) {
      eqtest::apply_biquad(eqtest::peaking_biquad(125 * std::pow(2, rng.uniform(-0.2, 0.2)), rng.uniform(4.5, 7.5), 1.2, 16000),
                           &s.samples);
      eqtest::apply_biquad(eqtest::lowpass_biquad(rng.uniform(4500, 6500), 0.707, 16000), &s.samples);
    }
    write_set(real, dir_->path("real"));
    sets_.real_scp = dir_->path("real/rir.scp");
    std::vector<Signal> noise;
    for (int i = 0; i < 60; ++i) {
      noise.push_back(eqtest::decaying_noise_rir("noise" + std::to_string(i), 16000, 16000, rng.uniform(0.35, 0.8),
                                                 static_cast<size_t>(rng.uniform(30, 300)), rng.uniform(-10, 3), 100 + i));
    }
    write_set(noise, dir_->path("noise"));
    sets_.noise_scp = dir_->path("noise/rir.scp");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  static std::vector<RelativeGainsDb> gains_of(const std::vector<Signal>& set) {
    std::vector<RelativeGainsDb> out;
    for (const Signal& s : set) out.push_back(relative_gains_db(s, GainMethod::kOctave));
    return out;
  }

  // Fits with `fit_options`, applies to `synthetic_scp`, checks distribution and metrics.
  void check(const std::string& name, const std::string& fit_options, const std::string& synthetic_scp,
             bool white_reverb) {
    SCOPED_TRACE(name);
    const std::string model = dir_->path(name + ".model"), out = dir_->path(name + "_eq");
    ASSERT_EQ(0, run(kBin + "/rir-eq fit " + fit_options + " " + sets_.real_scp + " " + model, sets_.log))
        << dir_->read("log.txt");
    ASSERT_EQ(0, run(kBin + "/rir-eq apply --seed=5 --format=float " + model + " " + synthetic_scp + " " + out,
                     sets_.log))
        << dir_->read("log.txt");
    const std::vector<Signal> synthetic = load_set(synthetic_scp);
    std::map<std::string, Signal> equalized;
    for (Signal& s : load_set(out + "/rir.scp")) equalized[s.id] = std::move(s);
    ASSERT_EQ(equalized.size(), synthetic.size());
    std::vector<Signal> eq_list;
    for (const Signal& s : synthetic) eq_list.push_back(equalized.at(s.id));

    const GainStats real = summarize_gains(gains_of(load_set(sets_.real_scp)));
    const GainStats before = summarize_gains(gains_of(synthetic));
    const GainStats after = summarize_gains(gains_of(eq_list));
    std::cerr << format_gain_stats({"real", "synthetic", "synthetic+EQ"}, {real, before, after});
    // The hidden effect is visible before EQ (so this test can fail): the synthetic set misses
    // the resonance and the roll-off by several dB.
    EXPECT_GT(real.mean_db[1] - before.mean_db[1], 3.0);
    EXPECT_LT(real.mean_db[6] - before.mean_db[6], -3.0);
    for (int k = 0; k < kEqNumPoints; ++k) {
      // The tolerances. From sampling alone the mean of 60 draws has a standard error
      // below 0.4 dB here, and the sample std of 60 (80) values a relative error of ~9% (8%).
      EXPECT_NEAR(after.mean_db[k], real.mean_db[k], 1.0) << kEqPointsHz[k] << " Hz";
      EXPECT_NEAR(after.std_db[k] / real.std_db[k], 1.0, 0.3) << kEqPointsHz[k] << " Hz";
    }

    double worst_t60 = 0, worst_drr = 0, mean_drr = 0;
    size_t within_half_db = 0;
    for (size_t i = 0; i < synthetic.size(); ++i) {
      const Signal& s = synthetic[i];
      const Signal& e = eq_list[i];
      ASSERT_EQ(e.samples.size(), s.samples.size());
      EXPECT_EQ(best_lag(s.samples, e.samples, 20), 0) << s.id;  // no time shift
      const RirMetrics m0 = measure_rir(s), m1 = measure_rir(e);
      ASSERT_TRUE(std::isfinite(m0.t60_s) && std::isfinite(m1.t60_s)) << s.id;
      const double t60_change = std::abs(m1.t60_s / m0.t60_s - 1);
      EXPECT_LT(t60_change, 0.05) << s.id << " T60 " << m0.t60_s << " -> " << m1.t60_s;
      worst_t60 = std::max(worst_t60, t60_change);
      const double drr_change = m1.drr_db - m0.drr_db;
      ASSERT_TRUE(std::isfinite(drr_change)) << s.id;
      mean_drr += drr_change / synthetic.size();
      worst_drr = std::max(worst_drr, std::abs(drr_change));
      if (std::abs(drr_change) < 0.5) ++within_half_db;
      EXPECT_LT(std::abs(drr_change), white_reverb ? 1.0 : 2.0) << s.id << " DRR " << m0.drr_db << " -> " << m1.drr_db;
    }
    EXPECT_LT(std::abs(mean_drr), 0.5);
    if (white_reverb) {
      EXPECT_GE(within_half_db, 0.95 * synthetic.size());
    }
    std::cerr << name << ": worst T60 change " << 100 * worst_t60 << " %; DRR change mean " << mean_drr
              << " dB, worst " << worst_drr << " dB, " << within_half_db << " of " << synthetic.size()
              << " RIRs within 0.5 dB\n";
  }

  static tsrir_test::ScratchDir* dir_;
  static Sets sets_;
};

tsrir_test::ScratchDir* HiddenEffect::dir_ = nullptr;
Sets HiddenEffect::sets_;

}  // namespace

TEST_F(HiddenEffect, SimulatedSetIndependentGaussians) {
  check("sim_indep", "--model=indep", sets_.simulated_scp, false);
}

TEST_F(HiddenEffect, SimulatedSetFullCovarianceMixture) {
  check("sim_gmm", "--model=gmm --components=2 --covariance=full --seed=3", sets_.simulated_scp, false);
}

TEST_F(HiddenEffect, WhiteReverbSet) {
  check("noise_indep", "--model=indep", sets_.noise_scp, true);
}
