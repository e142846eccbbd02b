#!/usr/bin/env bash
# Table 2 of the proxy experiment from asr-decode's per-utterance errors:
#   <exp>/<set>_seed<k>/decode_<test>/utt_errors
# One column group per test set: CER and WER per training set (mean and sample standard deviation
# over seeds), the relative CER change against --baseline, and a paired sign-flip permutation
# test over test utterances (each utterance's character errors averaged over seeds; 20000 random
# sign flips, seeded, two-sided p = (#{|S*| >= |S|} + 1) / (20000 + 1)). Then, per test set, the
# sensitivity check: real (oracle) vs clean.
# Usage: table2.sh [--sets "..."] [--seeds "0 1 2"] [--baseline gas]
#                  [--tests "test_real test_realspeech"] [--titles "TTS test voices|real speech"]
#                  <exp-asr-dir>
set -euo pipefail
sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext"
seeds="0"
baseline=gas
tests=test_real
titles=""
while [ $# -gt 1 ] && [[ "$1" == --* ]]; do
  case $1 in
    --sets) sets=$2 ;; --seeds) seeds=$2 ;; --baseline) baseline=$2 ;; --tests) tests=$2 ;; --titles) titles=$2 ;;
    *) echo "$0: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
[ $# -eq 1 ] || { sed -n '2,11p' "$0" >&2; exit 1; }
exp=$1
files=()
for t in $tests; do for s in $sets; do for k in $seeds; do
  f=$exp/${s}_seed$k/decode_$t/utt_errors
  [ -s "$f" ] || { echo "table2.sh: missing $f (train and decode $s, seed $k first)" >&2; exit 1; }
  files+=("$t" "$s" "$k" "$f")
done; done; done
printf '%s\n' "${files[@]}" | paste - - - - |
  awk -v sets="$sets" -v base="$baseline" -v tests="$tests" -v titles="$titles" -v nseeds="$(wc -w <<<"$seeds")" '
function label(s) {
  if (s == "gas") return "GAS"; if (s == "gas_eq") return "GAS+EQ"; if (s == "gas_gsr") return "G(GAS)"
  if (s == "gas_eq_gsr") return "G(GAS+EQ)"; if (s == "gas_gsr_eq") return "G(GAS)+EQ"; if (s == "real") return "real (oracle)"
  if (s == "clean") return "clean (no RIR)"; if (s == "gas_ext") return "GAS-ext"; return s }
function fmt_p(p) { return p < 0.0001 ? "< 0.0001" : sprintf("%.4f", p) }
function perm_p(t, a, b,    i, n, S, cnt, r, T, d, u) {   # paired sign-flip test of mean(a - b) over utts of t
  n = 0; S = 0
  for (u in utt) { split(u, key, SUBSEP); if (key[1] != t) continue; d[++n] = ce[t, a, key[2]] - ce[t, b, key[2]]; S += d[n] }
  srand(12345); cnt = 0
  for (r = 0; r < 20000; r++) { T = 0; for (i = 1; i <= n; i++) T += (rand() < 0.5 ? -d[i] : d[i]); if ((T < 0 ? -T : T) >= (S < 0 ? -S : S) - 1e-9) cnt++ }
  return (cnt + 1) / 20001 }
{ t = $1; s = $2; k = $3; f = $4
  while ((getline line < f) > 0) {
    if (line ~ /^#/) continue
    split(line, x, " "); u = x[1]; utt[t, u] = 1
    we[t, s, k] += x[3]; wr[t, s, k] += x[2]; cerr[t, s, k] += x[8]; cr[t, s, k] += x[7]
    ce[t, s, u] += x[8] / nseeds
  }
  close(f); if (t == first_test || first_test == "") { first_test = t; seedlist[s] = seedlist[s] " " k } }
END {
  n = split(sets, S, " "); nt = split(tests, TT, " "); split(titles, TI, "|")
  for (j = 1; j <= nt; j++) { nu[j] = 0; for (u in utt) { split(u, key, SUBSEP); if (key[1] == TT[j]) nu[j]++ } }
  hdr = "| training RIR set |"; sep = "|---|"
  for (j = 1; j <= nt; j++) {
    tl = (TI[j] != "" ? TI[j] : TT[j])
    hdr = hdr sprintf(" CER %% (%s) | WER %% | CER vs %s | p (paired, %d utts) |", tl, label(base), nu[j]); sep = sep "---|---|---|---|"
  }
  print hdr; print sep
  for (i = 1; i <= n; i++) {
    s = S[i]; m = split(seedlist[s], K, " ")
    for (j = 1; j <= nt; j++) {
      t = TT[j]; mc = mw = 0
      for (q = 1; q <= m; q++) { c[q] = 100 * cerr[t, s, K[q]] / cr[t, s, K[q]]; w[q] = 100 * we[t, s, K[q]] / wr[t, s, K[q]]; mc += c[q] / m; mw += w[q] / m }
      sc = sw = 0; for (q = 1; q <= m; q++) { sc += (c[q] - mc)^2; sw += (w[q] - mw)^2 }
      sd_c = m > 1 ? sprintf(" ± %.2f", sqrt(sc / (m - 1))) : ""; sd_w = m > 1 ? sprintf(" ± %.2f", sqrt(sw / (m - 1))) : ""
      meanc[t, s] = mc
      rates[i, j] = sprintf(" %.2f%s | %.2f%s |", mc, sd_c, mw, sd_w)
    }
  }
  for (i = 1; i <= n; i++) {
    s = S[i]; out = "| " label(s) " |"
    for (j = 1; j <= nt; j++) {
      t = TT[j]
      # The baseline row, and every row when the baseline was not trained, has no comparison.
      if (s == base || !(base in seedlist)) cmp = " — | — |"
      else cmp = sprintf(" %+.1f %% | %s |", 100 * (meanc[t, s] - meanc[t, base]) / meanc[t, base], fmt_p(perm_p(t, s, base)))
      out = out rates[i, j] cmp
    }
    print out
  }
  printf "\nCER/WER: mean%s over %d seed(s).", (nseeds > 1 ? " ± sd" : ""), nseeds
  printf " Tests:"; for (j = 1; j <= nt; j++) printf " %s%s", (TI[j] != "" ? TI[j] : TT[j]), (j < nt ? ";" : ".\n")
  if (("real" in seedlist) && ("clean" in seedlist)) {
    for (j = 1; j <= nt; j++) {
      t = TT[j]; rel = 100 * (meanc[t, "clean"] - meanc[t, "real"]) / meanc[t, "clean"]; p = perm_p(t, "real", "clean")
      printf "Sensitivity (%s): real (oracle) vs clean: CER %.2f vs %.2f %%, %.1f %% relative reduction, paired p %s (%s: >= 25 %% with p < 0.01).\n",
        (TI[j] != "" ? TI[j] : t), meanc[t, "real"], meanc[t, "clean"], rel, (p < 0.0001 ? "< 0.0001" : "= " fmt_p(p)),
        (rel >= 25 && p < 0.01) ? "PASS" : "FAIL"
    }
  }
}'
