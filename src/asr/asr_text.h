// Characters, CTC greedy decoding and error counting for the recogniser.
// Output alphabet (fixed, so a model dir needs no vocabulary file): 0 = CTC blank, 1 = space,
// 2..27 = 'a'..'z', 28 = apostrophe.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace tsrir {

constexpr int kCtcBlank = 0;
constexpr int kNumCharTokens = 29;  // including the blank

// Lower-cases, maps every character outside [a-z'] to a word boundary, collapses runs of
// spaces, trims. "Hello,  World!" -> "hello world". Digits are dropped (the transcripts are
// expected to spell numbers), so the result may be empty.
std::string normalise_transcript(const std::string& text);
// Token ids of a normalised transcript (every character must be in the alphabet).
std::vector<int> encode_characters(const std::string& normalised);
std::string decode_characters(const std::vector<int>& tokens);

// Greedy CTC: the per-frame best tokens with repeats merged, then blanks removed.
std::vector<int> ctc_collapse(const std::vector<int>& frame_tokens);

// Levenshtein alignment counts of a hypothesis against a reference (minimum total errors; among
// equal totals, fewer substitutions are preferred, then fewer insertions, deterministically).
struct EditCounts {
  size_t ref_length = 0;
  size_t insertions = 0, deletions = 0, substitutions = 0;
  size_t errors() const { return insertions + deletions + substitutions; }
  EditCounts& operator+=(const EditCounts& o);
};
EditCounts count_edits(const std::vector<std::string>& ref, const std::vector<std::string>& hyp);

std::vector<std::string> word_tokens(const std::string& normalised);
// Characters of a normalised transcript, the space between words included ("ab c" -> a b ' ' c).
std::vector<std::string> character_tokens(const std::string& normalised);

// Kaldi compute-wer's summary:
//   %WER 12.34 [ 56 / 454, 3 ins, 20 del, 33 sub ]
//   %SER 50.00 [ 5 / 10 ]
//   Scored 10 sentences, 0 not present in hyp.
// (a 0-length reference prints the rate as 0 errors = 0.00, else 100 * errors / ref_length).
std::string format_compute_wer(const EditCounts& total, size_t sentences_with_errors, size_t num_sentences,
                               size_t missing_hyps);

}  // namespace tsrir
