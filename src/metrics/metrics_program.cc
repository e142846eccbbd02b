#include "metrics/metrics_program.h"

#include <chrono>
#include <exception>

#include "io/atomic_output.h"
#include "metrics/metric_columns.h"
#include "io/common_options.h"
#include "io/owned_output.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"

namespace tsrir {

void MetricsRunOptions::Register(OptionsItf* opts) {
  metrics.Register(opts);
  opts->Register("channel", &channel, "channel to measure (0-based; -1 = mean of all channels)");
  opts->Register("all-channels", &all_channels,
                 "measure every channel of multichannel RIRs (microphone arrays): rows <id>-ch<c> (c from 0) and "
                 "<id>-mean (the channels' mean of each value); set statistics use the channel rows");
  CommonOptions(opts).threads(&num_threads, "RIRs are measured in parallel");
  opts->Register("skip-errors", &skip_errors, "report unreadable or unmeasurable RIRs and go on");
}

void RirMetricsCommand::Register(OptionsItf* opts) {
  opts->RegisterEnum("format", &format, metrics_format_choices(),
                     "output format");
  opts->Register("bands", &bands, "table format: add T20, T30 and EDT columns per octave band");
  run.Register(opts);
  opts->Register("reference", &reference, "reference set: print Table 1 (means, |mean - reference|) of the inputs");
  opts->Register("output", &output, "output file ('-' = stdout), written atomically");
}

namespace {

double mean_of(const std::vector<RirMetrics>& channels, const std::function<double(const RirMetrics&)>& get) {
  double sum = 0.0;
  for (const RirMetrics& c : channels) sum += get(c);
  return sum / channels.size();
}

BandMetrics band_mean(const std::vector<RirMetrics>& channels, const std::function<const BandMetrics*(const RirMetrics&)>& get) {
  BandMetrics out = *get(channels.front());
  const auto field = [&](double BandMetrics::*v) {
    return mean_of(channels, [&](const RirMetrics& m) { return get(m) ? get(m)->*v : kMetricsNaN; });
  };
  for (double BandMetrics::*v : {&BandMetrics::t20_s, &BandMetrics::t30_s, &BandMetrics::edt_s, &BandMetrics::rt_s,
                                 &BandMetrics::level_db, &BandMetrics::dynamic_range_db}) {
    out.*v = field(v);
  }
  return out;
}

// Every channel of one RIR, measured on its own.
std::vector<RirMetrics> measure_channels(const RirRef& ref, const MetricsOptions& options) {
  AudioInfo info;
  const std::vector<std::vector<float>> channels =
      read_audio_channels(ref.rxfilename, &info, ref.where + " (RIR '" + ref.id + "')");
  std::vector<RirMetrics> out;
  for (size_t c = 0; c < channels.size(); ++c) {
    Signal s{ref.id + "-ch" + std::to_string(c), info.sample_rate_hz, channels[c]};
    out.push_back(measure_rir(s, options));
  }
  return out;
}

}  // namespace

RirMetrics channel_mean(const std::vector<RirMetrics>& channels, const std::string& id) {
  if (channels.empty()) throw Error("channel_mean: no channels");
  RirMetrics out = channels.front();
  out.id = id;
  for (const MetricColumn& c : metric_columns()) {
    out.*c.value = mean_of(channels, [&](const RirMetrics& m) { return m.*c.value; });
  }
  for (BandMetrics& b : out.bands) {
    const double fc = b.center_hz;
    b = band_mean(channels, [fc](const RirMetrics& m) { return m.band(fc); });
  }
  out.broadband = band_mean(channels, [](const RirMetrics& m) { return &m.broadband; });
  out.warnings.clear();
  for (const RirMetrics& m : channels) {
    for (const std::string& w : m.warnings) out.warnings.push_back(m.id + ": " + w);
  }
  return out;
}

void measure_rir_refs(const std::vector<RirRef>& refs, const MetricsRunOptions& options,
                      const std::function<void(const MetricsOutcome&)>& on_result) {
  if (options.all_channels && options.channel != 0) throw Error("--all-channels measures every channel: drop --channel");
  const int threads = std::max(1, options.num_threads);
  const size_t chunk = options.chunk_size > 0 ? options.chunk_size : 32 * (size_t)threads;
  AudioReadOptions read;
  read.channel = options.channel;
  std::vector<MetricsOutcome> results;
  auto last_log = std::chrono::steady_clock::now();
  for (size_t start = 0; start < refs.size(); start += chunk) {
    const size_t count = std::min(chunk, refs.size() - start);
    results.assign(count, MetricsOutcome());
    parallel_for(count, threads, [&](size_t i) {
      const RirRef& ref = refs[start + i];
      MetricsOutcome& out = results[i];
      out.id = ref.id;
      Signal rir;
      try {
        if (options.all_channels) {
          out.channels = measure_channels(ref, options.metrics);
          out.metrics = channel_mean(out.channels, ref.id + "-mean");
          out.ok = true;
          return;
        }
        rir = load_rir(ref, read);  // its errors name the list line and the id
      } catch (const std::exception& e) {
        out.error = e.what();
        return;
      }
      try {
        out.metrics = measure_rir(rir, options.metrics);
        out.ok = true;
      } catch (const std::exception& e) {
        out.error = ref.where + ": " + e.what();
      }
    });
    for (const MetricsOutcome& r : results) {
      if (!r.ok && !options.skip_errors) throw Error(r.error);
      on_result(r);
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - last_log > std::chrono::seconds(5)) {
      log_info("measured " + std::to_string(start + count) + " of " + std::to_string(refs.size()) + " RIRs");
      last_log = now;
    }
  }
}

namespace {

std::vector<RirRef> read_inputs(const std::vector<std::string>& paths) {
  std::vector<RirRef> all;
  for (const std::string& p : paths) {
    std::vector<RirRef> refs = read_rir_refs(p, run_inputs());
    all.insert(all.end(), std::make_move_iterator(refs.begin()), std::make_move_iterator(refs.end()));
  }
  return all;
}

struct RunCounts {
  size_t ok = 0, failed = 0;
};

RunCounts summarise_set(const std::string& path, const MetricsRunOptions& run, MetricsSummary* summary) {
  RunCounts c;
  measure_rir_refs(read_rir_refs(path, run_inputs()), run, [&](const MetricsOutcome& r) {
    if (r.ok) {
      if (r.channels.empty()) summary->add(r.metrics);
      for (const RirMetrics& m : r.channels) summary->add(m);
      ++c.ok;
    } else {
      log_warning("skipping: " + r.error);
      ++c.failed;
    }
  });
  return c;
}

}  // namespace

int run_rir_metrics(const RirMetricsCommand& command) {
  AtomicTextFile output(command.output);
  RunCounts total;
  if (!command.reference.empty()) {
    const std::string definition = metrics_definition_name(command.run.metrics.definition);
    NamedSummary reference{command.reference, {}};
    RunCounts c = summarise_set(command.reference, command.run, &reference.summary);
    total.ok += c.ok;
    total.failed += c.failed;
    std::vector<NamedSummary> sets;
    for (const std::string& input : command.inputs) {
      sets.push_back({input, {}});
      c = summarise_set(input, command.run, &sets.back().summary);
      total.ok += c.ok;
      total.failed += c.failed;
    }
    if (command.format == MetricsFormat::kJson) {
      write_reference_json(output.stream(), reference, sets, definition);
    } else {
      write_reference_table(output.stream(), reference, sets, definition);
    }
  } else {
    const std::vector<RirRef> refs = read_inputs(command.inputs);
    MetricsReport report(output.stream(), command.format, command.bands);
    measure_rir_refs(refs, command.run, [&](const MetricsOutcome& r) {
      if (r.ok) {
        for (const RirMetrics& m : r.channels) report.add(m);
        report.add(r.metrics, /*in_summary=*/r.channels.empty());
        ++total.ok;
      } else {
        log_warning("skipping: " + r.error);
        report.add_error(r.id, r.error);
        ++total.failed;
      }
    });
    report.finish();
  }
  output.commit();
  if (total.failed > 0) {
    log_warning(std::to_string(total.failed) + " RIR(s) skipped because of errors, " + std::to_string(total.ok) +
                " measured");
  }
  return total.ok == 0 && total.failed > 0 ? 1 : 0;
}

}  // namespace tsrir
