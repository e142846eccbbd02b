#include "eq/eq_set.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/atomic_output.h"
#include "io/owned_output.h"
#include "io/rir_set.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"
#include "util/rng.h"
#include "util/strings.h"

namespace tsrir {

GainStats summarize_gains(const std::vector<RelativeGainsDb>& gains) {
  GainStats s;
  s.count = gains.size();
  if (gains.empty()) return s;
  for (const auto& g : gains)
    for (int k = 0; k < kEqNumPoints; ++k) s.mean_db[k] += g[k];
  for (double& m : s.mean_db) m /= static_cast<double>(gains.size());
  if (gains.size() < 2) return s;
  for (const auto& g : gains)
    for (int k = 0; k < kEqNumPoints; ++k) s.std_db[k] += (g[k] - s.mean_db[k]) * (g[k] - s.mean_db[k]);
  for (double& v : s.std_db) v = std::sqrt(v / static_cast<double>(gains.size() - 1));
  return s;
}

std::string format_gain_stats(const std::vector<std::string>& names, const std::vector<GainStats>& stats) {
  std::ostringstream out;
  out << std::left << std::setw(10) << "point_hz";
  for (const std::string& n : names) out << std::setw(22) << (n + " mean/std");
  out << '\n';
  for (int k = 0; k < kEqNumPoints; ++k) {
    out << std::setw(10) << format_double(kEqPointsHz[k]);
    for (const GainStats& s : stats) {
      std::ostringstream cell;
      cell << std::fixed << std::setprecision(2) << s.mean_db[k] << " / " << s.std_db[k];
      out << std::setw(22) << cell.str();
    }
    out << '\n';
  }
  return out.str();
}

namespace {

// Loads one RIR at the requested rate, counting resampled ones; with rate 0 the first RIR's
// rate becomes the set's rate and any other rate is an error.
class RateGuard {
 public:
  explicit RateGuard(double target_hz) : target_hz_(target_hz) {}
  // Every channel of the RIR (a microphone array's: one measured response per microphone).
  std::vector<Signal> load(const RirRef& ref) {
    std::vector<Signal> channels = load_rir_channels(ref);
    const double rate_hz = channels.front().sample_rate_hz;
    if (target_hz_ > 0) {
      if (rate_hz != target_hz_) {
        ++resampled_;
        source_rate_hz_.store(rate_hz);
        for (Signal& s : channels) s = resample(s, target_hz_);
      }
      return channels;
    }
    double expected = 0.0;
    if (!first_rate_hz_.compare_exchange_strong(expected, rate_hz) && expected != rate_hz) {
      throw Error(ref.where + ": RIR '" + ref.id + "' is at " + format_double(rate_hz) +
                  " Hz but other RIRs of the set are at " + format_double(expected) +
                  " Hz; pass --sample-rate to resample them to one rate");
    }
    return channels;
  }
  double rate_hz() const { return target_hz_ > 0 ? target_hz_ : first_rate_hz_.load(); }
  void log_resampling(const std::string& set_path, size_t total) const {
    if (resampled_ > 0) {
      log_info(set_path + ": resampled " + std::to_string(resampled_.load()) + " of " + std::to_string(total) +
               " RIRs (e.g. from " + format_double(source_rate_hz_.load()) + " Hz) to " + format_double(target_hz_) +
               " Hz");
    }
  }

 private:
  double target_hz_;
  std::atomic<double> first_rate_hz_{0.0};
  std::atomic<double> source_rate_hz_{0.0};
  std::atomic<size_t> resampled_{0};
};

// Progress on stderr every ~10 s for long runs.
class Progress {
 public:
  Progress(std::string what, size_t total) : what_(std::move(what)), total_(total), start_(Clock::now()), last_(start_) {}
  void tick() {
    const size_t done = ++done_;
    const auto now = Clock::now();
    std::lock_guard<std::mutex> lock(mutex_);
    if (now - last_ > std::chrono::seconds(10)) {
      last_ = now;
      log_info(what_ + ": " + std::to_string(done) + " / " + std::to_string(total_) + " RIRs");
    }
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_;
  size_t total_;
  std::atomic<size_t> done_{0};
  Clock::time_point start_, last_;
  std::mutex mutex_;
};

}  // namespace

std::vector<RirGains> measure_rir_set(const std::string& set_path, const MeasureSetOptions& options, double* rate_hz) {
  if (options.sample_rate_hz > 0) check_eq_sample_rate(options.sample_rate_hz, "--sample-rate");
  const std::vector<RirRef> refs = read_rir_refs(set_path, run_inputs());
  if (refs.empty()) throw Error(set_path + ": no RIRs listed");
  RateGuard guard(options.sample_rate_hz);
  // One row per RIR, or per channel of a multichannel RIR ("<id>-ch<c>", as rir-metrics
  // --all-channels names them): each microphone's response is one more measurement of the room.
  std::vector<std::vector<RirGains>> per_ref(refs.size());
  Progress progress("measuring " + set_path, refs.size());
  parallel_for(refs.size(), options.num_threads, [&](size_t i) {
    const std::vector<Signal> channels = guard.load(refs[i]);
    for (size_t c = 0; c < channels.size(); ++c) {
      RirGains row;
      row.id = channels.size() == 1 ? refs[i].id : refs[i].id + "-ch" + std::to_string(c);
      try {
        row.gains_db = relative_gains_db(channels[c], options.gain_method);
      } catch (const Error& e) {
        throw Error(refs[i].where + ": " + row.id + ": " + e.what());
      }
      per_ref[i].push_back(std::move(row));
    }
    progress.tick();
  });
  guard.log_resampling(set_path, refs.size());
  if (rate_hz) *rate_hz = guard.rate_hz();
  std::vector<RirGains> out;
  size_t multichannel = 0;
  for (std::vector<RirGains>& rows : per_ref) {
    multichannel += rows.size() > 1;
    for (RirGains& r : rows) out.push_back(std::move(r));
  }
  if (multichannel > 0) {
    log_info(set_path + ": " + std::to_string(multichannel) + " multichannel RIR(s): each channel measured as one RIR (" +
             std::to_string(out.size()) + " in all)");
  }
  return out;
}

void save_gains_table(const std::vector<RirGains>& rows, const std::string& path) {
  AtomicTextFile out(path);
  out.stream() << "# relative gains in dB re 1000 Hz at";
  for (double f : kEqPointsHz) out.stream() << ' ' << format_double(f);
  out.stream() << " Hz\n";
  for (const RirGains& r : rows) {
    out.stream() << r.id;
    for (double g : r.gains_db) out.stream() << ' ' << format_double(g, 5);
    out.stream() << '\n';
  }
  out.commit();
}

EqModel fit_eq_model_on_set(const std::string& real_set_path, const FitSetOptions& options) {
  double rate = 0.0;
  const std::vector<RirGains> rows = measure_rir_set(real_set_path, options.measure, &rate);
  std::vector<RelativeGainsDb> gains;
  for (const RirGains& r : rows) gains.push_back(r.gains_db);
  try {
    return fit_eq_model(gains, rate, options.measure.gain_method, options.mixture);
  } catch (const Error& e) {
    throw Error(real_set_path + ": " + e.what());
  }
}

ApplySetSummary equalize_rir_set(const EqModel& model, const std::string& in_set_path, const std::string& out_dir,
                                 const ApplySetOptions& options) {
  model.mixture.validate("EQ model");
  const std::vector<RirRef> refs = read_rir_refs(in_set_path, run_inputs());
  if (refs.empty()) throw Error(in_set_path + ": no RIRs listed");
  EqApplyOptions eq = options.eq;
  eq.gain_method = model.gain_method;
  eq.measure_output = true;
  RirSetWriter writer(out_dir, options.format);
  std::vector<EqResult> results(refs.size());
  std::atomic<size_t> clamped{0}, capped{0};
  // int16 holds at most 32767/32768: a peak-normalised float input (peak 1.0) is kept just below.
  const double int16_full_scale = 32767.0 / 32768.0;
  Progress progress("equalizing " + in_set_path, refs.size());
  parallel_for(refs.size(), options.num_threads, [&](size_t i) {
    const RirRef& ref = refs[i];
    std::vector<Signal> channels = load_rir_channels(ref);
    if (channels.front().sample_rate_hz != model.sample_rate_hz) {
      if (!options.resample) {
        throw Error(ref.where + ": RIR '" + ref.id + "' is at " + format_double(channels.front().sample_rate_hz) +
                    " Hz but the EQ model was fitted at " + format_double(model.sample_rate_hz) +
                    " Hz; pass --resample to resample the inputs to the model's rate");
      }
      for (Signal& s : channels) s = resample(s, model.sample_rate_hz);
    }
    Rng rng = Rng::for_item(options.seed, ref.id);
    const RelativeGainsDb target = draw_target_gains(model, rng);
    EqResult r;
    std::vector<Signal> out;
    try {
      r = equalize_rir_channels(channels, target, eq, &out);  // out = channels 1..
    } catch (const Error& e) {
      throw Error(ref.where + ": " + e.what());
    }
    out.insert(out.begin(), std::move(r.rir));
    if (options.format == SampleFormat::kInt16) {
      float peak = 0.0f;  // of the whole array: one factor keeps the channels' levels
      for (const Signal& c : out) {
        for (float v : c.samples) peak = std::max(peak, std::abs(v));
      }
      if (peak > int16_full_scale && peak < 1.0001f) {
        const float scale = static_cast<float>(int16_full_scale / peak);
        for (Signal& c : out) {
          for (float& v : c.samples) v *= scale;
        }
        ++capped;
      }
    }
    if (r.clamped) ++clamped;
    writer.add_channels(out, ref.room_id);
    results[i] = std::move(r);
    progress.tick();
  });
  ApplySetSummary summary;
  std::vector<RelativeGainsDb> before, target, achieved;
  for (const EqResult& r : results) {
    before.push_back(r.before_db);
    target.push_back(r.target_db);
    achieved.push_back(r.after_db);
  }
  summary.before = summarize_gains(before);
  summary.target = summarize_gains(target);
  summary.achieved = summarize_gains(achieved);
  summary.clamped = clamped;
  if (clamped > 0) {
    log_warning(std::to_string(clamped.load()) + " of " + std::to_string(refs.size()) + " RIRs needed more than a " +
                format_double(eq.max_boost_db) + " dB boost or " + format_double(eq.max_cut_db) +
                " dB cut at some node; it was clamped (see --max-boost-db, --max-cut-db)");
  }
  if (capped > 0) {
    log_info(std::to_string(capped.load()) + " RIRs with peak 1.0 were scaled to 32767/32768 to fit 16-bit output");
  }
  std::unique_ptr<AtomicTextFile> report;
  if (!options.report_path.empty()) {
    report = std::make_unique<AtomicTextFile>(options.report_path);
    std::ostream& out = report->stream();
    out << "# rir-eq apply report: relative gains in dB re 1000 Hz at";
    for (double f : kEqPointsHz) out << ' ' << format_double(f);
    out << " Hz\n# <id> before <7> target <7> achieved <7>\n";
    for (size_t i = 0; i < refs.size(); ++i) {
      out << refs[i].id;
      for (const RelativeGainsDb* g : {&results[i].before_db, &results[i].target_db, &results[i].after_db}) {
        out << ' ' << (g == &results[i].before_db ? "before" : g == &results[i].target_db ? "target" : "achieved");
        for (double v : *g) out << ' ' << format_double(v, 5);
      }
      out << '\n';
    }
  }
  writer.commit();
  if (report) report->commit();
  return summary;
}

}  // namespace tsrir
