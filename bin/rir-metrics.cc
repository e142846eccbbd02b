// rir-metrics: acoustic parameters (T60, EDT, DRR, C50, per-band T20/T30/EDT) of RIR sets, and
// the TS-RIR paper's Table 1 comparing sets against a reference set.
#include "metrics/metric_columns.h"
#include "metrics/metrics_program.h"
#include "util/cli.h"

int main(int argc, char** argv) {
  return tsrir::run_program("rir-metrics", [&]() {
    tsrir::CommandLine cli(
        "rir-metrics",
        "Measures room impulse responses: T60, EDT, DRR and C50 (the paper's CTE) per RIR, and\n"
        "T20/T30/EDT per octave band (62.5 Hz .. 8 kHz, the bands below Nyquist).\n"
        "Inputs are Kaldi scp files (<id> <rxfilename>), Kaldi rir_lists, or single audio files.\n"
        "\n"
        "Definitions (--definition):\n"
        "  iso      ISO 3382-1: onset 20 dB below the peak; octave bands filtered time-reversed;\n"
        "           noise floor: subtraction + Lundeby truncation + compensation (--lundeby=false\n"
        "           integrates the raw squared response);\n"
        "           T60 = mean T30 of 500 Hz and 1 kHz (T20 when the dynamic range is too small,\n"
        "           with a warning); DRR over [peak - pre, peak + post] ms; C50 from the onset.\n"
        "  irstats  IoSR irStats as used for the TS-RIR paper's Table 1: peak as t0, causal\n"
        "           Butterworth octaves, direct 0..-60 dB fit, DRR +-2.5 ms, CTE from -2.5..+50 ms\n"
        "           (--direct-*-ms are ignored).\n"
        "\n"
        "Usage: rir-metrics [options] <rir-scp-or-wav-file>...\n"
        "  e.g.: rir-metrics --bands data/rirs/rir.scp > metrics.txt\n"
        "        rir-metrics --format=json --num-threads=4 real.scp > metrics.json\n"
        "        rir-metrics --definition=irstats --reference=real/rir.scp gas/rir.scp gas_eq/rir.scp\n"
        "\n"
        "Parameters (columns of the table and JSON; Table 1 shows the paper's T60, DRR, EDT, C50):\n"
        "iso:\n" +
            tsrir::metric_columns_help(tsrir::MetricsDefinition::kIso) + "irstats:\n" +
            tsrir::metric_columns_help(tsrir::MetricsDefinition::kIrstats));
    tsrir::RirMetricsCommand c;
    c.Register(&cli);
    c.inputs = cli.parse(argc, argv, 1, -1);
    return tsrir::run_rir_metrics(c);
  });
}
