#include "io/resampler.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <mutex>

#include "io/sox_api.h"
#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

// The signal travels through the chain in 32-bit fixed point; source and sink convert.
struct SoxSource {
  const float* data;
  size_t n, pos;
  double scale;
};
struct SoxSink {
  std::vector<float>* out;
  double scale;
};

int sox_source_drain(sox_effect_t* effp, sox_sample_t* obuf, size_t* osamp) {
  auto* src = *static_cast<SoxSource**>(effp->priv);
  size_t n = std::min(*osamp, src->n - src->pos);
  for (size_t i = 0; i < n; ++i) {
    double v = src->data[src->pos + i] * src->scale;
    obuf[i] = static_cast<sox_sample_t>(std::lround(std::clamp(v, -1.0, 1.0) * 2147483647.0));
  }
  src->pos += n;
  *osamp = n;
  return n ? SOX_SUCCESS : SOX_EOF;
}

int sox_sink_flow(sox_effect_t* effp, const sox_sample_t* ibuf, sox_sample_t*, size_t* isamp, size_t* osamp) {
  auto* sink = *static_cast<SoxSink**>(effp->priv);
  for (size_t i = 0; i < *isamp; ++i) sink->out->push_back(static_cast<float>(ibuf[i] / 2147483648.0 * sink->scale));
  *osamp = 0;
  return SOX_SUCCESS;
}

const sox_effect_handler_t* source_handler() {
  static sox_effect_handler_t h = {"tsrir_source", nullptr, SOX_EFF_MCHAN, nullptr, nullptr, nullptr,
                                   sox_source_drain, nullptr, nullptr, sizeof(SoxSource*)};
  return &h;
}
const sox_effect_handler_t* sink_handler() {
  static sox_effect_handler_t h = {"tsrir_sink", nullptr, SOX_EFF_MCHAN, nullptr, nullptr, sox_sink_flow,
                                   nullptr, nullptr, nullptr, sizeof(SoxSink*)};
  return &h;
}

// libsox cannot be used from two threads at once: concurrent FIRST calls of a process corrupted the
// heap (Debian's OpenMP build, libsox3 14.4.2; tests/io
// Resampler.ConcurrentFirstCallsOfAProcessEqualSerialCalls aborts without this lock), while calls
// after a serial warm-up of the same conversions never did. The likely culprit is process-global
// state that the rate effect sets up on first use (the shared FFT cache of effects_i_dsp.c); it was
// not pinned down further. Every chain runs under this lock; callers resample each RIR or noise
// once and cache it, so the serialisation costs little.
std::mutex g_sox_mutex;

// sox_init() once per process (it sets up libsox's globals and its FFT cache).
void init_sox() {
  static std::once_flag once;
  static bool ok = false;
  std::call_once(once, [] {
    ok = sox().init() == SOX_SUCCESS;
    if (ok) sox().get_globals()->verbosity = 1;
  });
  if (!ok) throw Error("cannot initialise libsox");
}

struct ChainDeleter {
  void operator()(sox_effects_chain_t* c) const { sox().delete_effects_chain(c); }
};
// sox_add_effect copies the effect; the caller still frees the one it created.
struct EffectDeleter {
  void operator()(sox_effect_t* e) const { std::free(e); }
};
using Effect = std::unique_ptr<sox_effect_t, EffectDeleter>;

Effect make_effect(const sox_effect_handler_t* handler, const char* what) {
  if (!handler) throw Error(std::string("libsox: no '") + what + "' effect");
  Effect e(sox().create_effect(handler));
  if (!e) throw Error(std::string("libsox: cannot create the '") + what + "' effect");
  return e;
}

void add_effect(sox_effects_chain_t* chain, const Effect& e, sox_signalinfo_t* in, const sox_signalinfo_t* out,
                const char* what) {
  if (sox().add_effect(chain, e.get(), in, out) != SOX_SUCCESS) {
    throw Error(std::string("libsox: cannot add the '") + what + "' effect");
  }
}

}  // namespace

std::vector<float> resample(const std::vector<float>& samples, double from_hz, double to_hz) {
  if (!(from_hz > 0) || !(to_hz > 0)) throw Error("resample: sample rates must be positive");
  if (!(to_hz / from_hz <= kMaxResampleRatio && from_hz / to_hz <= kMaxResampleRatio)) {
    throw Error("resample: " + format_double(from_hz) + " Hz to " + format_double(to_hz) + " Hz is beyond the ratio " +
                format_double(kMaxResampleRatio));
  }
  if (std::fabs(from_hz - to_hz) < 1e-9 || samples.empty()) return samples;
  std::lock_guard<std::mutex> sox_lock(g_sox_mutex);
  init_sox();
  double peak = 0.0;
  for (float v : samples) peak = std::max(peak, static_cast<double>(std::fabs(v)));
  // Keep headroom for the filter's overshoot: sox works in 32-bit fixed point.
  const double scale = peak > 0 ? 0.5 / peak : 1.0;
  std::vector<float> out;
  out.reserve(static_cast<size_t>(samples.size() * to_hz / from_hz) + 64);
  SoxSource src{samples.data(), samples.size(), 0, scale};
  SoxSink sink{&out, 1.0 / scale};

  sox_signalinfo_t in_sig{from_hz, 1, 32, 0, nullptr};
  sox_signalinfo_t out_sig{to_hz, 1, 32, 0, nullptr};
  sox_encodinginfo_t enc{};
  enc.encoding = SOX_ENCODING_SIGN2;
  enc.bits_per_sample = 32;
  std::unique_ptr<sox_effects_chain_t, ChainDeleter> chain(sox().create_effects_chain(&enc, &enc));
  if (!chain) throw Error("libsox: cannot create an effects chain");
  sox_signalinfo_t interm = in_sig;

  Effect source = make_effect(source_handler(), "source");
  *static_cast<SoxSource**>(source->priv) = &src;
  add_effect(chain.get(), source, &interm, &in_sig, "source");

  Effect rate = make_effect(sox().find_effect("rate"), "rate");
  char opt_v[] = "-v";
  char* args[] = {opt_v};
  if (sox().effect_options(rate.get(), 1, args) != SOX_SUCCESS) throw Error("libsox: bad rate options");
  add_effect(chain.get(), rate, &interm, &out_sig, "rate");

  Effect sink_effect = make_effect(sink_handler(), "sink");
  *static_cast<SoxSink**>(sink_effect->priv) = &sink;
  add_effect(chain.get(), sink_effect, &interm, &out_sig, "sink");

  const int status = sox().flow_effects(chain.get(), nullptr, nullptr);
  if (status != SOX_SUCCESS) {
    throw Error("libsox: resampling " + format_double(from_hz) + " Hz to " + format_double(to_hz) + " Hz failed");
  }
  const size_t expected = static_cast<size_t>(std::llround(samples.size() * to_hz / from_hz));
  out.resize(expected, 0.0f);
  return out;
}

Signal resample(const Signal& signal, double to_hz) {
  Signal out = signal;
  out.samples = resample(signal.samples, signal.sample_rate_hz, to_hz);
  out.sample_rate_hz = to_hz;
  return out;
}

}  // namespace tsrir
