#include "asr/asr_text.h"

#include <cstdio>
#include <sstream>

#include "util/error.h"

namespace tsrir {

std::string normalise_transcript(const std::string& text) {
  std::string out;
  bool pending_space = false;
  for (unsigned char c : text) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    if ((c >= 'a' && c <= 'z') || c == '\'') {
      if (pending_space && !out.empty()) out += ' ';
      pending_space = false;
      out += char(c);
    } else if (c >= '0' && c <= '9') {
      continue;
    } else {
      pending_space = true;
    }
  }
  return out;
}

std::vector<int> encode_characters(const std::string& s) {
  std::vector<int> ids;
  ids.reserve(s.size());
  for (char c : s) {
    if (c == ' ') ids.push_back(1);
    else if (c >= 'a' && c <= 'z') ids.push_back(2 + (c - 'a'));
    else if (c == '\'') ids.push_back(28);
    else throw Error(std::string("character '") + c + "' is not in the recogniser's alphabet");
  }
  return ids;
}

std::string decode_characters(const std::vector<int>& tokens) {
  std::string s;
  for (int t : tokens) {
    if (t == 1) s += ' ';
    else if (t >= 2 && t <= 27) s += char('a' + (t - 2));
    else if (t == 28) s += '\'';
    else if (t != kCtcBlank) throw Error("token id " + std::to_string(t) + " is outside the alphabet");
  }
  return s;
}

std::vector<int> ctc_collapse(const std::vector<int>& frames) {
  std::vector<int> out;
  int previous = -1;
  for (int t : frames) {
    if (t != previous && t != kCtcBlank) out.push_back(t);
    previous = t;
  }
  return out;
}

EditCounts& EditCounts::operator+=(const EditCounts& o) {
  ref_length += o.ref_length;
  insertions += o.insertions;
  deletions += o.deletions;
  substitutions += o.substitutions;
  return *this;
}

EditCounts count_edits(const std::vector<std::string>& ref, const std::vector<std::string>& hyp) {
  // Each cell holds (errors, substitutions, insertions, deletions); cells compare by
  // (errors, substitutions, insertions).
  struct Cell {
    size_t err = 0, sub = 0, ins = 0, del = 0;
    bool better_than(const Cell& o) const {
      if (err != o.err) return err < o.err;
      if (sub != o.sub) return sub < o.sub;
      return ins < o.ins;
    }
  };
  const size_t R = ref.size(), H = hyp.size();
  std::vector<Cell> prev(H + 1), cur(H + 1);
  for (size_t j = 0; j <= H; ++j) prev[j] = Cell{j, 0, j, 0};
  for (size_t i = 1; i <= R; ++i) {
    cur[0] = Cell{i, 0, 0, i};
    for (size_t j = 1; j <= H; ++j) {
      Cell diag = prev[j - 1];
      if (ref[i - 1] != hyp[j - 1]) {
        ++diag.err;
        ++diag.sub;
      }
      Cell del = prev[j];
      ++del.err;
      ++del.del;
      Cell ins = cur[j - 1];
      ++ins.err;
      ++ins.ins;
      Cell best = diag;
      if (del.better_than(best)) best = del;
      if (ins.better_than(best)) best = ins;
      cur[j] = best;
    }
    std::swap(prev, cur);
  }
  EditCounts c;
  c.ref_length = R;
  c.insertions = prev[H].ins;
  c.deletions = prev[H].del;
  c.substitutions = prev[H].sub;
  return c;
}

std::vector<std::string> word_tokens(const std::string& s) {
  std::vector<std::string> words;
  std::istringstream in(s);
  std::string w;
  while (in >> w) words.push_back(w);
  return words;
}

std::vector<std::string> character_tokens(const std::string& s) {
  std::vector<std::string> chars;
  for (char c : s) chars.emplace_back(1, c);
  return chars;
}

std::string format_compute_wer(const EditCounts& t, size_t sentences_with_errors, size_t num_sentences,
                               size_t missing_hyps) {
  char line[256];
  std::string out;
  const double rate = t.ref_length > 0 ? 100.0 * t.errors() / t.ref_length : 0.0;
  std::snprintf(line, sizeof line, "%%WER %.2f [ %zu / %zu, %zu ins, %zu del, %zu sub ]\n", rate, t.errors(),
                t.ref_length, t.insertions, t.deletions, t.substitutions);
  out += line;
  const double ser = num_sentences > 0 ? 100.0 * sentences_with_errors / num_sentences : 0.0;
  std::snprintf(line, sizeof line, "%%SER %.2f [ %zu / %zu ]\n", ser, sentences_with_errors, num_sentences);
  out += line;
  std::snprintf(line, sizeof line, "Scored %zu sentences, %zu not present in hyp.\n", num_sentences, missing_hyps);
  out += line;
  return out;
}

}  // namespace tsrir
