// asr-decode: greedy CTC decoding and scoring with a model made by asr-train.
#include <string>

#include "asr/asr.h"
#include "io/owned_output.h"
#include "util/cli.h"
#include "util/strings.h"

int main(int argc, char** argv) {
  return tsrir::run_program("asr-decode", [&]() {
    tsrir::AsrDecodeOptions o;
    tsrir::CommandLine cli(
        "asr-decode",
        "Decodes a Kaldi data dir with an asr-train model (greedy CTC: the best character per frame,\n"
        "repeats merged, blanks removed) into <out-dir>/hyp (Kaldi text). When the data dir has a\n"
        "text file, the normalised transcripts are the reference and it also writes <out-dir>/wer\n"
        "(words) and <out-dir>/cer (characters, the space between words counted as one) in Kaldi\n"
        "compute-wer's format (%WER 12.34 [ 56 / 454, 3 ins, 20 del, 33 sub ], %SER, Scored ...),\n"
        "and <out-dir>/utt_errors (per utterance: reference length, errors, ins, del, sub for words\n"
        "then characters). Only these four files are created or replaced, all four at once; <out-dir>\n"
        "is marked as the toolkit's (.tsrir-owned) and may lie inside <model-dir> (Kaldi's exp/<model>/decode_*).\n"
        "\n"
        "Usage: asr-decode [options] <model-dir> <data-dir> <out-dir>\n"
        "Example:\n"
        "  asr-decode --num-threads=2 exp/asr/real data/test_farfield exp/asr/real/decode_test_farfield\n");
    o.Register(&cli);
    tsrir::OutputPolicy policy(cli.program());
    policy.Register(&cli);
    const auto args = cli.parse(argc, argv, 3, 3);
    tsrir::install_output_policy(policy);
    o.model_dir = args[0];
    o.data_dir = args[1];
    o.out_dir = args[2];
    const tsrir::AsrDecodeResult r = tsrir::decode_asr(o);
    std::string summary = "decoded " + std::to_string(r.num_utterances) + " utterances in " +
                          tsrir::format_double(r.decode_s, 4) + " s";
    if (r.scored) {
      const auto rate = [](const tsrir::EditCounts& c) {
        return tsrir::format_double(c.ref_length ? 100.0 * c.errors() / c.ref_length : 0.0, 4);
      };
      summary += ": WER " + rate(r.words) + " %, CER " + rate(r.characters) + " %";
    }
    tsrir::log_info(summary + " (" + o.out_dir + ")");
    return 0;
  });
}
