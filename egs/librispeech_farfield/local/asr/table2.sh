#!/usr/bin/env bash
# Table 2 of the proxy experiment from asr-decode's per-utterance errors:
#   <exp>/<set>_seed<k>/decode_test_real/utt_errors
# CER and WER per training set (mean and sample standard deviation over seeds), the relative CER
# change against --baseline, and a paired sign-flip permutation test over test utterances (each
# utterance's character errors averaged over seeds; 20000 random sign flips, seeded, two-sided
# p = (#{|S*| >= |S|} + 1) / (20000 + 1)). Also the sensitivity check: real (oracle) vs clean.
# Usage: table2.sh [--sets "..."] [--seeds "0 1 2"] [--baseline gas] <exp-asr-dir>
set -euo pipefail
sets="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq"
seeds="0"
baseline=gas
while [ $# -gt 1 ] && [[ "$1" == --* ]]; do
  case $1 in --sets) sets=$2 ;; --seeds) seeds=$2 ;; --baseline) baseline=$2 ;; *) echo "$0: unknown option $1" >&2; exit 1 ;; esac
  shift 2
done
[ $# -eq 1 ] || { echo "Usage: $0 [--sets S] [--seeds S] [--baseline B] <exp-asr-dir>" >&2; exit 1; }
exp=$1
files=()
for s in $sets; do for k in $seeds; do
  f=$exp/${s}_seed$k/decode_test_real/utt_errors
  [ -s "$f" ] || { echo "table2.sh: missing $f (train and decode $s, seed $k first)" >&2; exit 1; }
  files+=("$s" "$k" "$f")
done; done
printf '%s\n' "${files[@]}" | paste - - - | awk -v sets="$sets" -v base="$baseline" -v nseeds="$(wc -w <<<"$seeds")" '
function label(s) {
  if (s == "gas") return "GAS"; if (s == "gas_eq") return "GAS+EQ"; if (s == "gas_gsr") return "G(GAS)"
  if (s == "gas_eq_gsr") return "G(GAS+EQ)"; if (s == "gas_gsr_eq") return "G(GAS)+EQ"; if (s == "real") return "real (oracle)"
  if (s == "clean") return "clean (no RIR)"; if (s == "gas_ext") return "GAS-ext"; return s }
function fmt_p(p) { return p < 0.0001 ? "< 0.0001" : sprintf("%.4f", p) }
function perm_p(a, b,    i, n, S, cnt, r, T, d) {   # paired sign-flip test of mean(a - b) over utts
  n = 0; S = 0
  for (i in utt) { d[++n] = ce[a, i] - ce[b, i]; S += d[n] }
  srand(12345); cnt = 0
  for (r = 0; r < 20000; r++) { T = 0; for (i = 1; i <= n; i++) T += (rand() < 0.5 ? -d[i] : d[i]); if ((T < 0 ? -T : T) >= (S < 0 ? -S : S) - 1e-9) cnt++ }
  return (cnt + 1) / 20001 }
{ s = $1; k = $2; f = $3
  while ((getline line < f) > 0) {
    if (line ~ /^#/) continue
    split(line, x, " "); u = x[1]; utt[u] = 1
    we[s, k] += x[3]; wr[s, k] += x[2]; cerr[s, k] += x[8]; cr[s, k] += x[7]
    ce[s, u] += x[8] / nseeds; crf[u] = x[7]
  }
  close(f); seedlist[s] = seedlist[s] " " k }
END {
  n = split(sets, S, " "); nu = 0; for (u in utt) nu++
  printf "| training RIR set | CER %% | WER %% | CER vs %s | p (paired, %d utts) |\n|---|---|---|---|---|\n", label(base), nu
  for (j = 1; j <= n; j++) {
    s = S[j]; m = split(seedlist[s], K, " "); mc = mw = 0
    for (i = 1; i <= m; i++) { c[i] = 100 * cerr[s, K[i]] / cr[s, K[i]]; w[i] = 100 * we[s, K[i]] / wr[s, K[i]]; mc += c[i] / m; mw += w[i] / m }
    sc = sw = 0; for (i = 1; i <= m; i++) { sc += (c[i] - mc)^2; sw += (w[i] - mw)^2 }
    sd_c = m > 1 ? sprintf(" ± %.2f", sqrt(sc / (m - 1))) : ""; sd_w = m > 1 ? sprintf(" ± %.2f", sqrt(sw / (m - 1))) : ""
    meanc[s] = mc
    rel = (s == base || !(base in seedlist)) ? "—" : sprintf("%+.1f %%", 0)
    row[j] = sprintf("| %s | %.2f%s | %.2f%s |", label(s), mc, sd_c, mw, sd_w)
  }
  for (j = 1; j <= n; j++) {
    s = S[j]
    if (s == base || !(base in seedlist)) { printf "%s — | — |\n", row[j]; continue }
    printf "%s %+.1f %% | %s |\n", row[j], 100 * (meanc[s] - meanc[base]) / meanc[base], fmt_p(perm_p(s, base))
  }
  printf "\nCER/WER: mean%s over %d seed(s); test: test voices ⊛ held-out real RIRs + real noise.\n", (nseeds > 1 ? " ± sd" : ""), nseeds
  if (("real" in seedlist) && ("clean" in seedlist)) {
    rel = 100 * (meanc["clean"] - meanc["real"]) / meanc["clean"]; p = perm_p("real", "clean")
    printf "Sensitivity: real (oracle) vs clean: CER %.2f vs %.2f %%, %.1f %% relative reduction, paired p %s (%s: >= 25 %% with p < 0.01).\n",
      meanc["real"], meanc["clean"], rel, (p < 0.0001 ? "< 0.0001" : "= " fmt_p(p)), (rel >= 25 && p < 0.01) ? "PASS" : "FAIL"
  }
}'
