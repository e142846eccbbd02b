#include "metrics/metrics_summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "util/json.h"
#include "util/strings.h"

namespace tsrir {

namespace {
constexpr SetParameter kAll[kNumSetParameters] = {SetParameter::kT60, SetParameter::kDrr, SetParameter::kEdt,
                                                  SetParameter::kC50};

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return format_double(v);
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}
}  // namespace

const char* set_parameter_name(SetParameter p) {
  switch (p) {
    case SetParameter::kT60: return "T60";
    case SetParameter::kDrr: return "DRR";
    case SetParameter::kEdt: return "EDT";
    case SetParameter::kC50: return "C50";
  }
  return "";
}

const char* set_parameter_unit(SetParameter p) {
  return p == SetParameter::kT60 || p == SetParameter::kEdt ? "s" : "dB";
}

double set_parameter_value(const RirMetrics& m, SetParameter p) {
  switch (p) {
    case SetParameter::kT60: return m.t60_s;
    case SetParameter::kDrr: return m.drr_db;
    case SetParameter::kEdt: return m.edt_s;
    case SetParameter::kC50: return m.c50_db;
  }
  return kMetricsNaN;
}

void MetricsSummary::add(const RirMetrics& m) {
  ++num_rirs_;
  for (SetParameter p : kAll) {
    const double v = set_parameter_value(m, p);
    if (std::isfinite(v)) values_[(int)p].push_back(v);
  }
}

ParameterStats MetricsSummary::stats(SetParameter p) const {
  ParameterStats s;
  std::vector<double> v = values_[(int)p];
  s.count = v.size();
  if (v.empty()) return s;
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / (double)v.size();
  if (v.size() > 1) {
    double ss = 0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(ss / (double)(v.size() - 1));
  }
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  s.median = v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
  return s;
}

void write_summary_json(JsonWriter& json, const MetricsSummary& summary) {
  json.begin_object();
  json.field("count", summary.num_rirs());
  for (SetParameter p : kAll) {
    const ParameterStats s = summary.stats(p);
    json.key(set_parameter_name(p)).begin_object();
    json.field("mean", s.mean).field("std", s.std).field("median", s.median).field("count", s.count);
    json.end_object();
  }
  json.end_object();
}

int closest_set(const NamedSummary& reference, const std::vector<NamedSummary>& sets, SetParameter p) {
  const double ref = reference.summary.stats(p).mean;
  int best = -1;
  double best_diff = INFINITY;
  for (size_t i = 0; i < sets.size(); ++i) {
    const double d = std::abs(sets[i].summary.stats(p).mean - ref);
    if (std::isfinite(d) && d < best_diff) {
      best_diff = d;
      best = (int)i;
    }
  }
  return best;
}

void write_reference_table(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                           const std::string& definition) {
  size_t name_width = reference.name.size();
  for (const auto& s : sets) name_width = std::max(name_width, s.name.size());
  name_width = std::max<size_t>(name_width, 3) + 2;
  constexpr int kCell = 20;
  out << "# Mean acoustic parameters per RIR set (definition " << definition
      << "); (|mean - reference mean|); * = closest to the reference\n";
  out << std::left << std::setw((int)name_width) << "# set" << std::setw(8) << "n";
  for (SetParameter p : kAll) {
    out << std::setw(kCell) << (std::string(set_parameter_name(p)) + " (" + set_parameter_unit(p) + ")");
  }
  out << "\n";
  out << std::setw((int)name_width) << reference.name << std::setw(8) << reference.summary.num_rirs();
  for (SetParameter p : kAll) out << std::setw(kCell) << fixed(reference.summary.stats(p).mean, 4);
  out << "(reference)\n";
  int closest[kNumSetParameters];
  for (SetParameter p : kAll) closest[(int)p] = closest_set(reference, sets, p);
  for (size_t i = 0; i < sets.size(); ++i) {
    out << std::setw((int)name_width) << sets[i].name << std::setw(8) << sets[i].summary.num_rirs();
    for (SetParameter p : kAll) {
      const double mean = sets[i].summary.stats(p).mean;
      const double diff = std::abs(mean - reference.summary.stats(p).mean);
      std::string cell = fixed(mean, 4) + " (" + fixed(diff, 4) + ")";
      if (closest[(int)p] == (int)i) cell += "*";
      out << std::setw(kCell) << cell;
    }
    out << "\n";
  }
  out << std::right;
}

void write_reference_json(std::ostream& out, const NamedSummary& reference, const std::vector<NamedSummary>& sets,
                          const std::string& definition) {
  JsonWriter json(out);
  json.begin_object();
  json.field("definition", definition);
  json.key("reference").begin_object();
  json.field("name", reference.name).field("count", reference.summary.num_rirs());
  for (SetParameter p : kAll) {
    const ParameterStats s = reference.summary.stats(p);
    json.key(set_parameter_name(p)).begin_object();
    json.field("mean", s.mean).field("std", s.std).field("median", s.median).field("count", s.count);
    json.end_object();
  }
  json.end_object();
  json.key("sets").begin_array();
  for (size_t i = 0; i < sets.size(); ++i) {
    json.begin_object();
    json.field("name", sets[i].name).field("count", sets[i].summary.num_rirs());
    for (SetParameter p : kAll) {
      const ParameterStats s = sets[i].summary.stats(p);
      json.key(set_parameter_name(p)).begin_object();
      json.field("mean", s.mean).field("std", s.std).field("median", s.median).field("count", s.count);
      json.field("diff", std::abs(s.mean - reference.summary.stats(p).mean));
      json.field("closest", closest_set(reference, sets, p) == (int)i);
      json.end_object();
    }
    json.end_object();
  }
  json.end_array();
  json.end_object();
  out << "\n";
}

}  // namespace tsrir
