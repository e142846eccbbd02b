#include "gan/gan_settings.h"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "io/atomic_output.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {
constexpr const char* kFormatTag = "tsrir-ts-rirgan-settings-v1";

// Seeds are unsigned 64-bit (any --seed the command line accepts must read back).
uint64_t parse_seed(const std::string& text, const std::string& context) {
  if (text.empty() || text.size() > 20 || text.find_first_not_of("0123456789") != std::string::npos) {
    throw Error(context + ": expected an unsigned integer, got '" + text + "'");
  }
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) throw Error(context + ": seed out of range: '" + text + "'");
  return uint64_t(v);
}
}  // namespace

void throw_bad_choice_name(const std::string& context, const std::string& text, const std::string& listed) {
  throw Error(context + ": expected one of " + listed + ", got '" + text + "'");
}

std::string gan_settings_text(const GanSettings& s) {
  std::ostringstream os;
  os << "format " << kFormatTag << "\n"
     << "width " << s.width << "\n"
     << "kernel_length " << s.kernel_length << "\n"
     << "slice_length " << s.slice_length << "\n"
     << "sample_rate_hz " << format_double(s.sample_rate_hz, 17) << "\n"
     << "batch_size " << s.batch_size << "\n"
     << "seed " << s.seed << "\n"
     << "learning_rate " << format_double(s.learning_rate, 17) << "\n"
     << "disc_learning_rate " << format_double(s.disc_learning_rate, 17) << "\n"
     << "disc_updates " << s.disc_updates << "\n"
     << "init " << choice_name(kGanInitNames, s.init) << "\n"
     << "cycle_weight " << format_double(s.cycle_weight, 17) << "\n"
     << "identity_weight " << format_double(s.identity_weight, 17) << "\n"
     << "gain_weight " << format_double(s.gain_weight, 17) << "\n"
     << "rmsprop_initial_ms " << format_double(s.rmsprop_initial_ms, 17) << "\n"
     << "decoder " << choice_name(kGanDecoderNames, s.decoder) << "\n"
     << "generator " << choice_name(kGanGeneratorNames, s.generator) << "\n"
     << "correction_max_hz " << format_double(s.correction_max_hz, 17) << "\n"
     << "generator_activation " << choice_name(kGanActivationNames, s.generator_activation) << "\n"
     << "generator_update " << choice_name(kGanGeneratorUpdateNames, s.generator_update) << "\n"
     << "disc_augment " << choice_name(kGanDiscAugmentNames, s.disc_augment) << "\n"
     << "precision " << choice_name(kGanPrecisionNames, s.precision) << "\n"
     << "warmup_steps " << s.warmup_steps << "\n"
     << "real_list " << s.real_list << "\n"
     << "synthetic_list " << s.synthetic_list << "\n";
  return os.str();
}

GanSettings parse_gan_settings(const std::string& text, const std::string& where) {
  GanSettings s;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool have_format = false;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const size_t space = t.find_first_of(" \t");
    const std::string key = t.substr(0, space);
    const std::string value = space == std::string::npos ? "" : trim(t.substr(space));
    const std::string ctx = located(where, line_no, key);
    if (key == "format") {
      if (value != kFormatTag) throw Error(located(where, line_no, "unknown settings format '" + value + "'"));
      have_format = true;
    } else if (key == "width") {
      s.width = int(parse_int(value, ctx));
    } else if (key == "kernel_length") {
      s.kernel_length = int(parse_int(value, ctx));
    } else if (key == "slice_length") {
      s.slice_length = parse_int(value, ctx);
    } else if (key == "sample_rate_hz") {
      s.sample_rate_hz = parse_double(value, ctx);
    } else if (key == "batch_size") {
      s.batch_size = int(parse_int(value, ctx));
    } else if (key == "seed") {
      s.seed = parse_seed(value, ctx);
    } else if (key == "learning_rate") {
      s.learning_rate = parse_double(value, ctx);
    } else if (key == "disc_learning_rate") {
      s.disc_learning_rate = parse_double(value, ctx);
    } else if (key == "disc_updates") {
      s.disc_updates = int(parse_int(value, ctx));
    } else if (key == "init") {
      s.init = parse_choice(kGanInitNames, value, ctx);
    } else if (key == "cycle_weight") {
      s.cycle_weight = parse_double(value, ctx);
    } else if (key == "identity_weight") {
      s.identity_weight = parse_double(value, ctx);
    } else if (key == "gain_weight") {
      s.gain_weight = parse_double(value, ctx);
    } else if (key == "rmsprop_initial_ms") {
      s.rmsprop_initial_ms = parse_double(value, ctx);
    } else if (key == "decoder") {
      s.decoder = parse_choice(kGanDecoderNames, value, ctx);
    } else if (key == "generator") {
      s.generator = parse_choice(kGanGeneratorNames, value, ctx);
    } else if (key == "correction_max_hz") {
      s.correction_max_hz = parse_double(value, ctx);
      if (!(s.correction_max_hz >= 0 && s.correction_max_hz < 8000)) {
        throw Error(ctx + ": correction_max_hz must be in [0, 8000)");
      }
    } else if (key == "generator_activation") {
      s.generator_activation = parse_choice(kGanActivationNames, value, ctx);
    } else if (key == "disc_augment") {
      s.disc_augment = parse_choice(kGanDiscAugmentNames, value, ctx);
    } else if (key == "generator_update") {
      s.generator_update = parse_choice(kGanGeneratorUpdateNames, value, ctx);
    } else if (key == "warmup_steps") {
      s.warmup_steps = parse_int(value, ctx);
      if (s.warmup_steps < 0) throw Error(ctx + ": warmup_steps must be >= 0");
    } else if (key == "precision") {
      s.precision = parse_choice(kGanPrecisionNames, value, ctx);
    } else if (key == "real_list") {
      s.real_list = value;
    } else if (key == "synthetic_list") {
      s.synthetic_list = value;
    } else {
      throw Error(located(where, line_no, "unknown setting '" + key + "'"));
    }
  }
  if (!have_format) throw Error(located(where, 0, "not a TS-RIRGAN settings file (no 'format' line)"));
  if (s.width < 1 || s.kernel_length < 1 || s.slice_length != 16384 || s.sample_rate_hz != 16000.0) {
    throw Error(located(where, 0, "unsupported model settings (width " + std::to_string(s.width) +
                                      ", slice " + std::to_string(s.slice_length) + ")"));
  }
  return s;
}

void decoder_multipliers(GanDecoder decoder, int multipliers[3]) {
  if (decoder == GanDecoder::kOriginal) {
    multipliers[0] = 16, multipliers[1] = 8, multipliers[2] = 4;
  } else {
    multipliers[0] = 4, multipliers[1] = 2, multipliers[2] = 1;
  }
}

GanSettings read_gan_settings_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read model settings " + path);
  std::ostringstream os;
  os << in.rdbuf();
  return parse_gan_settings(os.str(), path);
}

void write_gan_settings_file(const std::string& path, const GanSettings& settings) {
  AtomicTextFile out(path);
  out.stream() << gan_settings_text(settings);
  out.commit();
}

namespace {
std::string architecture_text(const GanSettings& s) {
  return "width " + std::to_string(s.width) + " (decoder " + choice_name(kGanDecoderNames, s.decoder) + ", generator " +
         choice_name(kGanGeneratorNames, s.generator) + ", correction max " + format_double(s.correction_max_hz, 6) +
         " Hz, activation " + choice_name(kGanActivationNames, s.generator_activation) + ", kernel " +
         std::to_string(s.kernel_length) + ")";
}
}  // namespace

void check_same_architecture(const GanSettings& expected, const GanSettings& found,
                             const std::string& what) {
  if (expected.width != found.width || expected.kernel_length != found.kernel_length ||
      expected.slice_length != found.slice_length || expected.sample_rate_hz != found.sample_rate_hz ||
      expected.decoder != found.decoder || expected.generator != found.generator ||
      expected.correction_max_hz != found.correction_max_hz ||
      expected.generator_activation != found.generator_activation) {
    throw Error(what + ": model " + architecture_text(found) + ", expected " + architecture_text(expected));
  }
}

}  // namespace tsrir
