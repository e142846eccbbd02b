// rir-metrics: acoustic parameters (T60, EDT, DRR, C50, per-band T20/T30/EDT) of RIR sets, and
// the TS-RIR paper's Table 1 comparing sets against a reference set.
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
        "        rir-metrics --definition=irstats --reference=real/rir.scp gas/rir.scp gas_eq/rir.scp\n");
    tsrir::RirMetricsCommand c;
    std::string definition = "iso", format = "table";
    cli.option("definition", &definition, "iso | irstats");
    cli.option("format", &format, "table | json");
    cli.flag("bands", &c.bands, "table format: add T20, T30 and EDT columns per octave band");
    cli.flag("lundeby", &c.run.metrics.lundeby, "iso: noise-floor subtraction, Lundeby truncation and compensation");
    cli.option("direct-pre-ms", &c.run.metrics.direct_pre_ms, "iso: direct-sound window before the peak (ms)");
    cli.option("direct-post-ms", &c.run.metrics.direct_post_ms, "iso: direct-sound window after the peak (ms)");
    cli.option("clarity-ms", &c.run.metrics.clarity_time_ms, "early/late limit of the clarity index (ms)");
    cli.option("onset-db", &c.run.metrics.onset_threshold_db, "iso: onset = first sample within this many dB of the peak");
    cli.option("channel", &c.run.channel, "channel to measure (0-based; -1 = mean of all channels)");
    cli.option("num-threads", &c.run.num_threads, "threads (RIRs are measured in parallel)");
    cli.flag("skip-errors", &c.run.skip_errors, "report unreadable or unmeasurable RIRs and go on");
    cli.option("reference", &c.reference, "reference set: print Table 1 (means, |mean - reference|) of the inputs");
    cli.option("output", &c.output, "output file ('-' = stdout), written atomically");
    c.inputs = cli.parse(argc, argv, 1, -1);
    c.run.metrics.definition = tsrir::parse_metrics_definition(definition);
    c.format = tsrir::parse_metrics_format(format);
    return tsrir::run_rir_metrics(c);
  });
}
