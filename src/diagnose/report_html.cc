#include "diagnose/report_html.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "diagnose/set_statistics.h"
#include "diagnose/svg_plot.h"
#include "dsp/fft.h"
#include "util/strings.h"

namespace tsrir::diagnose {
namespace {

std::string num(double v, int digits = 3) { return std::isfinite(v) ? format_double(v, digits) : "n/a"; }

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Spectrogram in dB: 12.5 ms Hann frames (hop = frame) over up to 0.8 s from the onset region,
// 48 linear frequency rows up to Nyquist.
std::vector<std::vector<double>> spectrogram_db(const Signal& s, double* peak_db) {
  const double fs = s.sample_rate_hz;
  const size_t frame = static_cast<size_t>(0.025 * fs), hop = static_cast<size_t>(0.8 / 48 * fs);
  const size_t nfft = next_fast_fft_size(frame);
  const size_t frames = std::min<size_t>(48, s.size() > frame ? (s.size() - frame) / hop + 1 : 0);
  const int rows = 36;
  std::vector<std::vector<double>> out(rows, std::vector<double>(frames, -300.0));
  *peak_db = -300.0;
  std::vector<float> buf(frame);
  for (size_t t = 0; t < frames; ++t) {
    for (size_t i = 0; i < frame; ++i) {
      buf[i] = s.samples[t * hop + i] * static_cast<float>(0.5 - 0.5 * std::cos(2.0 * 3.14159265358979 * i / frame));
    }
    const std::vector<double> p = power_spectrum(buf, nfft);
    for (int r = 0; r < rows; ++r) {
      const size_t k0 = p.size() * r / rows, k1 = std::max(k0 + 1, p.size() * (r + 1) / rows);
      double e = 0.0;
      for (size_t k = k0; k < k1 && k < p.size(); ++k) e += p[k];
      out[r][t] = 10.0 * std::log10(std::max(e / (k1 - k0), 1e-30));
      *peak_db = std::max(*peak_db, out[r][t]);
    }
  }
  return out;
}

void write_findings_section(const Diagnosis& d, std::ostream& out) {
  out << "<h2>Findings</h2>\n<p>Each decision is a test over the whole set of paired differences (measured minus "
         "simulated), calibrated against the same statistic between two simulation seeds (null).</p>"
         "<table><tr><th>effect</th><th>detected</th><th>confidence</th><th>statistic (null)</th><th>evidence</th>"
         "<th>fitted parameters</th><th>held-out check</th></tr>\n";
  std::vector<Finding> all = d.findings;
  all.push_back(d.unexplained);
  for (const Finding& f : all) {
    out << "<tr><td>" << f.effect << "</td><td class='" << (f.detected ? "yes'>yes" : "no'>no") << "</td><td>"
        << num(f.confidence, 2) << "</td><td>" << num(f.statistic) << " (" << num(f.null_statistic) << ") "
        << html_escape(f.statistic_unit) << "</td><td>" << html_escape(f.evidence) << "</td><td>";
    int k = 0;
    for (const auto& [name, v] : f.parameters) {
      if (k++ == 24) { out << "..."; break; }
      out << html_escape(name) << " = " << num(v, 4) << "<br>";
    }
    out << "</td><td>" << html_escape(f.held_out) << "</td></tr>\n";
  }
  out << "</table>\n";
}

// The gain table against both baselines, the metrics made worse, and what each effect adds beyond
// the band refit.
void write_gain_section(const Diagnosis& d, std::ostream& out) {
  out << "<h2>Gain on held-out RIRs</h2>\n<p>Mean absolute error over the eval ids (lower is better); gain = baseline "
         "- extended with the standard error of the paired per-RIR differences. Extended model";
  std::map<std::string, int> distinct;
  for (const auto& [room, spec] : d.extended_model_by_room) distinct[spec]++;
  if (distinct.size() == 1) {
    out << ": <code>" << html_escape(distinct.begin()->first) << "</code>";
  } else {
    out << " per room:<br>";
    for (const auto& [room, spec] : d.extended_model_by_room) {
      out << html_escape(room) << ": <code>" << html_escape(spec) << "</code><br>";
    }
  }
  out << "</p><p>Two baselines: the baseline model as stated, and the same with every band's absorption refitted per "
         "room to the measured decay on the fit RIRs (the cheap fix any user would try first). Green: a significant "
         "gain (p &lt; " << num(kGainAlpha) << "), red: significantly worse.</p>"
         "<table><tr><th>metric</th><th>baseline</th><th>band-refitted</th><th>extended</th><th>gain over baseline "
         "&plusmn; s.e.</th><th>paired t</th><th>p</th><th>gain over band-refitted &plusmn; s.e.</th><th>p</th><th>n</th></tr>\n";
  auto colour = [](const PairedGain& g) { return g.better() ? "#070" : g.worse() ? "#b00" : "#555"; };
  for (const MetricGain& g : d.gains) {
    const PairedGain vs_base{g.gain, g.gain_se, g.t, g.p, g.n};
    out << "<tr><td>" << g.name << "</td><td>" << num(g.baseline) << " " << g.unit << "</td><td>" << num(g.refitted) << " "
        << g.unit << "</td><td>" << num(g.extended) << " " << g.unit << "</td><td style='color:" << colour(vs_base) << "'>"
        << num(g.gain) << " &plusmn; " << num(g.gain_se, 2) << "</td><td>" << num(g.t, 3) << "</td><td>" << num(g.p, 2)
        << "</td><td style='color:" << colour(g.vs_refitted) << "'>" << num(g.vs_refitted.gain) << " &plusmn; "
        << num(g.vs_refitted.gain_se, 2) << "</td><td>" << num(g.vs_refitted.p, 2) << "</td><td>" << g.n << "</td></tr>\n";
  }
  out << "</table>\n";
  out << "<h3>Metrics the extended model makes worse</h3>\n";
  if (d.regressions.empty()) out << "<p>None: no metric is significantly worse than with the baseline.</p>\n";
  for (const Regression& r : d.regressions) {
    out << "<p class='yes'>" << html_escape(r.metric) << ": " << num(r.baseline) << " &rarr; " << num(r.extended) << " "
        << html_escape(r.unit) << " (t = " << num(r.vs_baseline.t, 3) << ", p = " << num(r.vs_baseline.p, 2) << "); "
        << (r.caused_by.empty() ? std::string("no single extension's removal undoes it")
                                : "caused by the extension of " + html_escape(join_names(r.caused_by)))
        << ".</p>\n";
  }
  out << "<h3>What each effect adds beyond the band refit</h3>\n<p>The band-refitted baseline plus one effect's "
         "extension, against the band-refitted baseline, on the effect's gain metric (effects whose extension only "
         "changes decay rates are the refit's own).</p><table><tr><th>effect</th><th>metric</th><th>band-refitted</th>"
         "<th>+ effect</th><th>gain &plusmn; s.e.</th><th>p</th><th>made worse</th></tr>\n";
  for (const EffectGain& g : d.effect_gains) {
    out << "<tr><td>" << g.effect << "</td><td>" << g.metric << "</td><td>" << num(g.refitted) << " " << html_escape(g.unit)
        << "</td><td>" << num(g.with_effect) << " " << html_escape(g.unit) << "</td><td style='color:" << colour(g.gain)
        << "'>" << num(g.gain.gain) << " &plusmn; " << num(g.gain.gain_se, 2) << "</td><td>" << num(g.gain.p, 2)
        << "</td><td>" << html_escape(join_names(g.worse)) << "</td></tr>\n";
  }
  out << "</table>\n";
}

void write_examples_section(const Diagnosis& d, const std::vector<std::unique_ptr<Effect>>& effects, std::ostream& out) {
  for (const ExampleCurves& ex : d.examples) {
    out << "<h2>Held-out example <code>" << html_escape(ex.id) << "</code></h2><div class='plots'>\n";
    double pm, pb, pe;
    const auto sm = spectrogram_db(ex.measured, &pm), sb = spectrogram_db(ex.baseline, &pb), se = spectrogram_db(ex.extended, &pe);
    const double dur = 0.8 / 48 * (sm.empty() ? 0 : sm[0].size());
    const std::string level = "level, dB re its maximum";
    out << svg_heatmap("measured", sm, pm - 70, pm, "time, s", dur, "Hz", ex.measured.sample_rate_hz / 2, 380, 220, level, pm);
    out << svg_heatmap("baseline simulation", sb, pb - 70, pb, "time, s", dur, "Hz", ex.baseline.sample_rate_hz / 2, 380,
                       220, level, pb);
    out << svg_heatmap("extended simulation", se, pe - 70, pe, "time, s", dur, "Hz", ex.extended.sample_rate_hz / 2, 380,
                       220, level, pe);
    out << "<br>";
    {
      PlotSpec p;
      p.title = "Energy decay curve (from the onset)";
      p.x_label = "time, s";
      p.y_label = "dB";
      std::vector<double> t;
      for (size_t i = 0; i < ex.edc_meas_db.size(); ++i) t.push_back(0.005 * i);
      p.x_min = 0;
      p.x_max = t.empty() ? 1.0 : t.back();
      p.y_min = -90;
      p.y_max = 0;
      Series base{"baseline", "#ff7f0e", t, ex.edc_base_db};
      base.dashed = true;
      p.series = {{"measured", "#1f77b4", t, ex.edc_meas_db}, base, {"extended", "#2ca02c", t, ex.edc_ext_db}};
      out << svg_plot(p);
    }
    for (const auto& effect : effects) effect->report_example(ex, out);
    out << "</div>\n";
  }
  out << "</body></html>\n";
}

}  // namespace

void write_report_html(const Diagnosis& d, const std::string& command_line, std::ostream& out) {
  out << "<!DOCTYPE html><html><head><meta charset='utf-8'><title>rir-diagnose report</title><style>"
         "body{font-family:sans-serif;margin:24px;max-width:1150px;color:#222}"
         "table{border-collapse:collapse;margin:8px 0 18px}td,th{border:1px solid #ccc;padding:4px 8px;font-size:13px;"
         "vertical-align:top}th{background:#f3f3f3}.yes{color:#b00;font-weight:bold}.no{color:#777}"
         "code{background:#f5f5f5;padding:1px 4px;font-size:12px;word-break:break-all}.plots svg{margin:4px}"
         "</style></head><body>\n";
  out << "<h1>rir-diagnose report</h1>\n<p>" << d.num_rirs << " measured RIRs analysed at " << num(d.sample_rate_hz, 6)
      << " Hz against the baseline model <code>" << html_escape(d.baseline_model) << "</code>; fit on " << d.fit_ids.size()
      << " RIRs, evaluated on " << d.eval_ids.size() << " held-out RIRs; " << num(d.seconds, 3) << " s.</p>\n";
  out << "<p>Command: <code>" << html_escape(command_line) << "</code></p>\n";

  write_findings_section(d, out);
  write_gain_section(d, out);
  // Each effect's plots over the set, in catalog order.
  const auto& effects = (d.registry ? *d.registry : effect_registry()).effects();
  out << "<h2>Per-band departures (fit RIRs)</h2><div class='plots'>\n";
  for (size_t k = 0; k < effects.size() && k < d.findings.size(); ++k) effects[k]->report_set(d.findings[k], d, out);
  out << "</div>\n";
  write_examples_section(d, effects, out);
  out << "</body></html>\n";
}

}  // namespace tsrir::diagnose
