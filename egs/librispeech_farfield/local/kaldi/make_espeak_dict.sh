#!/usr/bin/env bash
# A Kaldi dict dir (lexicon.txt, nonsilence_phones.txt, silence_phones.txt, optional_silence.txt,
# extra_questions.txt) for the words of <word-list> (one word a line), pronounced by espeak-ng:
# for a corpus without a pronunciation dictionary (run_asr.sh --lm-text).
#   - `espeak-ng -q -x --sep=' ' -v <voice>`: espeak's ASCII phoneme mnemonics, one token per
#     phoneme, words separated by two spaces; stress marks (' ,) and pauses/modifiers (_: _! ;)
#     are dropped.
#   - pronunciations in context: with --sentences <file> (one sentence a line, e.g. the LM text and
#     the transcripts), each sentence is spoken by each voice and, where espeak's output has one
#     group per word, every (word, phones) pair is a lexicon entry. Running speech gives the weak
#     forms the TTS corpus really contains ("a" -> a#, "the" -> D @2 / D i:), which the isolated
#     word does not ("a" -> eI).
#   - words with no pronunciation in context get their isolated pronunciation from each voice.
#   - voices: --voices (default: en-us and en-gb): one variant per distinct output.
#   - phone names are made Kaldi-safe: @ -> ax, : -> long, # -> red, - -> syl, ? -> glot (e.g.
#     'i:' -> 'ilong', 'r-' -> 'rsyl'); no name ends in _B/_E/_I/_S or starts with #.
#   - SIL (optional silence) and SPN (for the OOV word, --oov) are the silence phones.
# espeak-ng is the synthesiser of the TTS corpus (local/asr/make_tts_corpus.sh), so for that corpus
# the lexicon is what was spoken, up to the voice's dialect.
set -euo pipefail

voices="en-us en-gb"
oov="<unk>"
sentences=""        # text file, one sentence a line: pronunciations in context
help_message="Usage: $0 [--voices \"en-us en-gb\"] [--oov '<unk>'] [--sentences <text>] <word-list> <dict-dir>
e.g.: $0 --sentences data/local/lm_text.txt data/local/words.txt data/local/dict_nosp"

. "$(dirname "$0")/../parse_options.sh"
[ $# -eq 2 ] || { echo "$help_message" >&2; exit 1; }
words=$1
dir=$2
command -v espeak-ng >/dev/null || { echo "$0: espeak-ng is not installed" >&2; exit 1; }
[ -s "$words" ] || { echo "$0: empty or missing word list $words" >&2; exit 1; }
mkdir -p "$dir"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# espeak-ng speaks each paragraph (text between blank lines) as one output line.
speak() {  # <voice> <file, one item a line> -> the phones, one line per input line (or fails)
  awk 'NF {print; print ""}' "$2" | espeak-ng -q -x --sep=' ' -v "$1" | grep -v '^ *$' >"$tmp/out" || true
  [ "$(wc -l <"$tmp/out")" -eq "$(grep -c . "$2")" ] && cat "$tmp/out"
}
clean_phones='{
    n = split($0, t, " "); out = ""
    for (i = 1; i <= n; i++) {
      p = t[i]; gsub(/[\047,;]/, "", p)              # stress marks, palatalisation modifier
      if (p == "" || p ~ /^_/) continue                # pauses
      gsub(/@/, "ax", p); gsub(/:/, "long", p); gsub(/#/, "red", p); gsub(/-/, "syl", p); gsub(/\?/, "glot", p)
      out = out " " p
    }
    print substr(out, 2)
  }'
grep -v -x -F -e "$oov" -e "" "$words" | sort -u >"$tmp/words"
: >"$tmp/lex"
for v in $voices; do
  if [ -n "$sentences" ]; then
    grep . "$sentences" | sort -u >"$tmp/sent"
    if speak "$v" "$tmp/sent" >"$tmp/sent.ph"; then
      # words of a sentence <-> its espeak groups (two spaces apart); sentences whose counts differ
      # (espeak merged or split words) are skipped.
      paste -d'|' "$tmp/sent" "$tmp/sent.ph" | awk -F'|' '{
          nw = split($1, w, " "); ng = split($2, g, "  ")
          if (nw != ng) { skipped++; next }
          for (i = 1; i <= nw; i++) print w[i] "\t" g[i]
        } END { if (skipped) print skipped " sentences skipped (words != espeak groups)" > "/dev/stderr" }' \
        >"$tmp/pairs"
      cut -f1 "$tmp/pairs" >"$tmp/w"; cut -f2 "$tmp/pairs" | awk "$clean_phones" >"$tmp/p"
      paste -d' ' "$tmp/w" "$tmp/p" | awk 'NF > 1' >>"$tmp/lex"
    else
      echo "$0: espeak-ng -v $v gave a different number of lines for the sentences: none used" >&2
    fi
  fi
done
sort -u "$tmp/lex" -o "$tmp/lex"
cut -d' ' -f1 "$tmp/lex" | sort -u | join -v1 "$tmp/words" - >"$tmp/isolated"
if [ -s "$tmp/isolated" ]; then
  for v in $voices; do
    if speak "$v" "$tmp/isolated" >"$tmp/iso.ph"; then
      awk "$clean_phones" "$tmp/iso.ph" | paste -d' ' "$tmp/isolated" - | awk 'NF > 1' >>"$tmp/lex"
    else
      while read -r w; do  # one call per word (slow: espeak-ng loads the voice each time)
        printf '%s\n' "$w" | espeak-ng -q -x --sep=' ' -v "$v" | tr '\n' ' ' | awk "$clean_phones" | sed "s/^/$w /"
      done <"$tmp/isolated" | awk 'NF > 1' >>"$tmp/lex"
    fi
  done
fi
sort -u "$tmp/lex" -o "$tmp/lex"

missing=$(cut -d' ' -f1 "$tmp/lex" | sort -u | join -v1 "$tmp/words" - | wc -l)
[ "$missing" -eq 0 ] || echo "$0: warning: $missing words got no pronunciation from espeak-ng" >&2
{ echo "$oov SPN"; cat "$tmp/lex"; } | sort -u >"$dir/lexicon.txt"
cut -d' ' -f2- "$tmp/lex" | tr ' ' '\n' | grep -v '^$' | sort -u >"$dir/nonsilence_phones.txt"
printf 'SIL\nSPN\n' >"$dir/silence_phones.txt"
echo SIL >"$dir/optional_silence.txt"
: >"$dir/extra_questions.txt"
echo "$0: $(wc -l <"$dir/lexicon.txt") lexicon entries ($(cut -d' ' -f1 "$tmp/lex" | sort -u | wc -l) words, $(wc -l <"$tmp/isolated") of them isolated, voices: $voices)," \
  "$(wc -l <"$dir/nonsilence_phones.txt") non-silence phones -> $dir" >&2
