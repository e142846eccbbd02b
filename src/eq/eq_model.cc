#include "eq/eq_model.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <utility>

#include "io/atomic_output.h"
#include "util/commented_lines.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {

RelativeGainsDb EqModel::mean_db() const {
  RelativeGainsDb m{};
  for (const GaussianComponent& c : mixture.components) {
    for (int k = 0; k < kEqNumPoints; ++k) m[k] += c.weight * c.mean(k);
  }
  return m;
}

RelativeGainsDb EqModel::std_db() const {
  const RelativeGainsDb m = mean_db();
  RelativeGainsDb s{};
  for (const GaussianComponent& c : mixture.components) {
    for (int k = 0; k < kEqNumPoints; ++k) {
      const double dm = c.mean(k) - m[k];
      s[k] += c.weight * (c.covariance(k, k) + dm * dm);  // law of total variance
    }
  }
  for (double& v : s) v = std::sqrt(v);
  return s;
}

EqModel fit_eq_model(const std::vector<RelativeGainsDb>& gains, double sample_rate_hz, GainMethod method,
                     const GmmFitOptions& options) {
  Eigen::MatrixXd data(static_cast<long>(gains.size()), kEqNumPoints);
  for (size_t i = 0; i < gains.size(); ++i) {
    for (int k = 0; k < kEqNumPoints; ++k) data(static_cast<long>(i), k) = gains[i][k];
  }
  EqModel model;
  model.sample_rate_hz = sample_rate_hz;
  model.gain_method = method;
  model.fitted_rirs = static_cast<long>(gains.size());
  try {
    model.mixture = fit_gaussian_mixture(data, options);
  } catch (const Error& e) {
    throw Error(std::string("fitting the EQ model on ") + std::to_string(gains.size()) + " real RIRs: " + e.what());
  }
  return model;
}

RelativeGainsDb draw_target_gains(const EqModel& model, Rng& rng) {
  const Eigen::VectorXd x = model.mixture.sample(rng);
  RelativeGainsDb t{};
  for (int k = 0; k < kEqNumPoints; ++k) t[k] = x(k);
  return t;
}

namespace {

void write_row(std::ostream& out, const char* key, const Eigen::VectorXd& v) {
  out << key;
  for (int i = 0; i < v.size(); ++i) out << ' ' << format_double(v(i), 17);
  out << '\n';
}

}  // namespace

void write_eq_model(const EqModel& model, std::ostream& out) {
  out << "# rir-eq model: distribution of sub-band relative gains in dB re 1000 Hz\n";
  const RelativeGainsDb m = model.mean_db(), s = model.std_db();
  out << "# per-point mean/std (dB):";
  for (int k = 0; k < kEqNumPoints; ++k) {
    out << ' ' << format_double(kEqPointsHz[k]) << ':' << format_double(m[k], 3) << '/' << format_double(s[k], 3);
  }
  out << '\n';
  out << "tsrir-eq-model " << kEqModelVersion << '\n';
  out << "sample_rate_hz " << format_double(model.sample_rate_hz, 17) << '\n';
  out << "gain_method " << gain_method_name(model.gain_method) << '\n';
  out << "points_hz";
  for (double f : kEqPointsHz) out << ' ' << format_double(f);
  out << '\n';
  out << "reference_hz " << format_double(kEqReferenceHz) << '\n';
  out << "fitted_rirs " << model.fitted_rirs << '\n';
  out << "covariance " << covariance_type_name(model.mixture.covariance_type) << '\n';
  out << "components " << model.mixture.components.size() << '\n';
  for (size_t k = 0; k < model.mixture.components.size(); ++k) {
    const GaussianComponent& c = model.mixture.components[k];
    out << "component " << k + 1 << '\n';
    out << "weight " << format_double(c.weight, 17) << '\n';
    write_row(out, "mean", c.mean);
    if (model.mixture.covariance_type == CovarianceType::kDiagonal) {
      write_row(out, "variance", c.covariance.diagonal());
    } else {
      for (int r = 0; r < c.covariance.rows(); ++r) write_row(out, "covariance_row", c.covariance.row(r).transpose());
    }
  }
  out << "end\n";
}

void save_eq_model(const EqModel& model, const std::string& path) {
  model.mixture.validate("EQ model");
  AtomicTextFile file(path);
  write_eq_model(model, file.stream());
  file.commit();
}

namespace {

// Reads the keyword lines one at a time, skipping comments and blanks.
class ModelLines {
 public:
  ModelLines(const std::string& text, const std::string& source) : in_(text), lines_(in_), source_(source) {}

  // The fields of the next line, whose first field must be `key`.
  std::vector<std::string> expect(const std::string& key, size_t num_values) {
    if (!next()) throw Error(located(source_, line_, "file ends before '" + key + "' (truncated model?)"));
    if (fields_[0] != key) {
      throw Error(located(source_, line_, "expected '" + key + "', got '" + fields_[0] + "'"));
    }
    if (fields_.size() != num_values + 1) {
      throw Error(located(source_, line_, "'" + key + "' needs " + std::to_string(num_values) + " value(s), got " +
                                              std::to_string(fields_.size() - 1)));
    }
    return {fields_.begin() + 1, fields_.end()};
  }
  double number(const std::string& text) { return parse_double(text, where()); }
  long long integer(const std::string& text) { return parse_int(text, where()); }
  std::string where() const { return source_ + ":" + std::to_string(line_); }
  Eigen::VectorXd vector(const std::string& key) {
    const std::vector<std::string> v = expect(key, kEqNumPoints);
    Eigen::VectorXd out(kEqNumPoints);
    for (int i = 0; i < kEqNumPoints; ++i) {
      out(i) = number(v[i]);
      if (!std::isfinite(out(i))) throw Error(located(source_, line_, "non-finite value in '" + key + "'"));
    }
    return out;
  }
  Error error(const std::string& message) const { return Error(located(source_, line_, message)); }
  bool at_end() {
    return !next();
  }

 private:
  bool next() {
    std::string line;
    const bool more = lines_.next(&line);
    // At the end, errors name the line after the last one.
    line_ = lines_.lines_read() + (more ? 0 : 1);
    fields_ = split_whitespace(line);
    return more;
  }
  std::istringstream in_;
  CommentedLines lines_;
  std::string source_;
  int line_ = 0;
  std::vector<std::string> fields_;
};

}  // namespace

EqModel parse_eq_model(const std::string& text, const std::string& source) {
  ModelLines lines(text, source);
  EqModel model;
  {
    const std::vector<std::string> v = lines.expect("tsrir-eq-model", 1);
    if (lines.integer(v[0]) != kEqModelVersion) {
      throw lines.error("unsupported model version " + v[0] + " (this program reads version " +
                        std::to_string(kEqModelVersion) + ")");
    }
  }
  model.sample_rate_hz = lines.number(lines.expect("sample_rate_hz", 1)[0]);
  try {
    check_eq_sample_rate(model.sample_rate_hz, "sample_rate_hz");
  } catch (const Error& e) {
    throw lines.error(e.what());
  }
  const std::string method = lines.expect("gain_method", 1)[0];
  try {
    model.gain_method = parse_gain_method(method);
  } catch (const Error& e) {
    throw lines.error(e.what());
  }
  {
    const std::vector<std::string> v = lines.expect("points_hz", kEqNumPoints);
    for (int k = 0; k < kEqNumPoints; ++k) {
      if (lines.number(v[k]) != kEqPointsHz[k]) throw lines.error("points_hz must be 62.5 125 250 500 2000 4000 8000");
    }
  }
  if (lines.number(lines.expect("reference_hz", 1)[0]) != kEqReferenceHz) throw lines.error("reference_hz must be 1000");
  model.fitted_rirs = static_cast<long>(lines.integer(lines.expect("fitted_rirs", 1)[0]));
  if (model.fitted_rirs < 1) throw lines.error("fitted_rirs must be positive");
  const std::string covariance = lines.expect("covariance", 1)[0];
  try {
    model.mixture.covariance_type = parse_covariance_type(covariance);
  } catch (const Error& e) {
    throw lines.error(e.what());
  }
  const long long k_count = lines.integer(lines.expect("components", 1)[0]);
  if (k_count < 1 || k_count > 1000) throw lines.error("components must be in [1, 1000]");
  for (long long k = 1; k <= k_count; ++k) {
    if (lines.integer(lines.expect("component", 1)[0]) != k) {
      throw lines.error("expected 'component " + std::to_string(k) + "'");
    }
    GaussianComponent c;
    c.weight = lines.number(lines.expect("weight", 1)[0]);
    if (!(c.weight > 0 && c.weight <= 1)) throw lines.error("weight must be in (0, 1]");
    c.mean = lines.vector("mean");
    c.covariance = Eigen::MatrixXd::Zero(kEqNumPoints, kEqNumPoints);
    if (model.mixture.covariance_type == CovarianceType::kDiagonal) {
      const Eigen::VectorXd var = lines.vector("variance");
      if ((var.array() <= 0).any()) throw lines.error("variances must be positive");
      c.covariance.diagonal() = var;
    } else {
      for (int r = 0; r < kEqNumPoints; ++r) c.covariance.row(r) = lines.vector("covariance_row").transpose();
    }
    try {
      GaussianMixture one;
      one.covariance_type = model.mixture.covariance_type;
      one.components.push_back({1.0, c.mean, c.covariance});
      one.validate("component " + std::to_string(k));
    } catch (const Error& e) {
      throw lines.error(e.what());
    }
    model.mixture.components.push_back(std::move(c));
  }
  lines.expect("end", 0);
  if (!lines.at_end()) throw lines.error("unexpected content after 'end'");
  try {
    model.mixture.validate("model");
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  return model;
}

EqModel load_eq_model(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open EQ model file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": error reading EQ model file");
  return parse_eq_model(text.str(), path);
}

}  // namespace tsrir
