#!/usr/bin/env python3
"""Table 2 of the proxy experiment, with statistics at the level of training runs.

Reads asr-decode's outputs <exp>/<set>_seed<k>/decode_<test>/utt_errors and, per test set, prints
one row per training RIR set: CER and WER (each run's corpus-level rate, then the mean over runs
with a 95 % t interval), and against --baseline the CER difference paired by seed with its 95 %
interval, the relative change, the paired effect size d_z (mean difference / SD of the per-seed
differences), a paired t-test over seeds and, for reference, Welch's unpaired test over runs.

Why runs and not utterances: every model decodes the same test utterances, so utterance effects
cancel in a difference of run means, and what is left to judge a difference against is how much
a whole training run moves; a test over utterances alone ignores that run-to-run variance and
called a 1-LSB corpus change significant (docs/results/downstream.md).
Why paired by seed: the runs of every set with seed k share their initial weights, batch order,
SpecAugment masks and copy choices (common random numbers), and the far-field data of every set
are drawn with one reverberate-data seed, so a run's seed effect (e.g. a slow start that leaves it
several points behind) is shared by all sets and cancels in the per-seed difference. This is the
test of the set effect in a mixed model with a random run (seed) effect and utterance effects
(balanced: every run decodes every test utterance); with n seeds it has n - 1 degrees of freedom.

Controls (--dose "real ctl1 ctl2 ..."): a chain of training sets of growing mismatch; the
instrument is valid on a test set when the chain's mean CER rises at every step and the last set
is worse than the first by a one-sided paired t-test over seeds at p < --alpha (Welch printed
beside it). --resolution prints the smallest CER difference the design can detect (two-sided
alpha 0.05, power 0.8, n seeds, the pooled SD of the per-seed differences against the baseline).

Usage: table2.py [--sets "..."] [--seeds "0 1 2 3 4"] [--baseline gas] [--tests "test_real"]
                 [--titles "TTS test voices"] [--dose "real t60x0.5 t60x0.33"] [--alpha 0.01]
                 [--labels "set=label ..."] <exp-asr-dir>
Exit status 0; with --require-dose, 3 when a dose check fails (so CI can assert it).
"""
import argparse
import math
import os
import sys

LABELS = {
    "clean": "clean (no RIR)", "real": "real (oracle)", "gas": "GAS", "gas_eq": "GAS+EQ",
    "gas_gsr": "G(GAS)", "gas_eq_gsr": "G(GAS+EQ)", "gas_gsr_eq": "G(GAS)+EQ", "gas_ext": "GAS-ext",
    "gas_gsrp": "G_paper(GAS)", "gas_eq_gsrp": "G_paper(GAS+EQ)", "gas_gsrp_eq": "G_paper(GAS)+EQ",
    "gas_gsrt": "G_demo(GAS)", "gas_eq_gsrt": "G_demo(GAS+EQ)", "gas_gsrt_eq": "G_demo(GAS)+EQ",
}


def control_label(s):
    """Labels of the positive controls made by rir-perturb (bench/asr/run_table2.sh names them)."""
    if s.startswith("ctl_t60x"):
        return "control: real, T60 x" + s[len("ctl_t60x"):]
    if s.startswith("ctl_drr"):
        return "control: real, DRR " + s[len("ctl_drr"):] + " dB"
    if s.startswith("ctl_lf"):
        return "control: real + LF ringing " + s[len("ctl_lf"):] + " dB"
    return None


# ---- Student's t distribution (no scipy on a bare Debian) ----
def _betacf(a, b, x):
    """Continued fraction of the regularised incomplete beta (Numerical Recipes, modified Lentz)."""
    tiny, eps = 1e-300, 3e-16
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 400):
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        h *= d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < eps:
            break
    return h


def betainc(a, b, x):
    if x <= 0:
        return 0.0
    if x >= 1:
        return 1.0
    lbeta = math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log(1 - x)
    if x < (a + 1) / (a + b + 2):
        return math.exp(lbeta) * _betacf(a, b, x) / a
    return 1.0 - math.exp(lbeta) * _betacf(b, a, 1 - x) / b


def t_sf(t, df):
    """P(T > t) for Student's t with df degrees of freedom."""
    x = df / (df + t * t)
    tail = 0.5 * betainc(df / 2.0, 0.5, x)
    return tail if t >= 0 else 1.0 - tail


def t_quantile(p, df):
    """The t with P(T <= t) = p, by bisection."""
    lo, hi = -1e3, 1e3
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if 1.0 - t_sf(mid, df) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


# ---- run-level statistics ----
def mean(v):
    return sum(v) / len(v)


def sd(v):
    if len(v) < 2:
        return float("nan")
    m = mean(v)
    return math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))


NAN = float("nan")


def ci95(v):
    """Half-width of the 95 % t interval of the mean."""
    if len(v) < 2:
        return float("nan")
    return t_quantile(0.975, len(v) - 1) * sd(v) / math.sqrt(len(v))


def welch(a, b):
    """(difference a - b, its 95 % half-width, two-sided p, one-sided p for a > b, df); NaN statistics
    when either set has fewer than two runs (no run-level variance to test against)."""
    if min(len(a), len(b)) < 2:
        return mean(a) - mean(b), NAN, NAN, NAN, NAN
    va, vb = sd(a) ** 2 / len(a), sd(b) ** 2 / len(b)
    diff = mean(a) - mean(b)
    se = math.sqrt(va + vb)
    if se == 0:
        return diff, 0.0, (0.0 if diff != 0 else 1.0), (0.0 if diff > 0 else 1.0), float("inf")
    df = (va + vb) ** 2 / (va ** 2 / (len(a) - 1) + vb ** 2 / (len(b) - 1))
    t = diff / se
    return diff, t_quantile(0.975, df) * se, 2 * t_sf(abs(t), df), t_sf(t, df), df


def paired(a, b):
    """Per-seed differences a[k] - b[k]: (mean, 95 % half-width, two-sided p, one-sided p for a > b,
    d_z = mean / SD of the differences)."""
    d = [x - y for x, y in zip(a, b)]
    n = len(d)
    m, s = mean(d), sd(d)
    if n < 2:  # one seed: a difference, but no test
        return m, NAN, NAN, NAN, NAN
    if not s > 0:
        return m, 0.0, (0.0 if m != 0 else 1.0), (0.0 if m > 0 else 1.0), float("nan")
    t = m / (s / math.sqrt(n))
    return m, t_quantile(0.975, n - 1) * s / math.sqrt(n), 2 * t_sf(abs(t), n - 1), t_sf(t, n - 1), m / s


def fmt_mean(v):
    """Mean ± 95 % half-width, or the mean alone for one run."""
    return "%.2f" % mean(v) if len(v) < 2 else "%.2f ± %.2f" % (mean(v), ci95(v))


def fmt_diff(d, hw):
    """A difference with its 95 % interval, or with 'n/a' where one seed gives no interval."""
    if math.isnan(hw):
        return "%+.2f (n/a)" % d
    return "%+.2f (%+.2f .. %+.2f)" % (d, d - hw, d + hw)


def fmt_ci(d, hw):
    return "no interval from one seed" if math.isnan(hw) else "95 %% CI %+.2f .. %+.2f" % (d - hw, d + hw)


def fmt_dz(dz):
    return "n/a" if math.isnan(dz) else "%+.2f" % dz


def fmt_p(p):
    if math.isnan(p):
        return "n/a"
    return "< 0.0001" if p < 0.0001 else "%.4f" % p


# ---- reading the decodes ----
def read_run(path):
    """Corpus-level (CER, WER) in % of one decode's utt_errors."""
    words = word_err = chars = char_err = 0
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            x = line.split()
            words += int(x[1]); word_err += int(x[2]); chars += int(x[6]); char_err += int(x[7])
    if chars == 0:
        raise ValueError("%s: no reference characters" % path)
    return 100.0 * char_err / chars, 100.0 * word_err / max(words, 1)


def collect(exp, sets, seeds, test):
    runs = {}
    for s in sets:
        cer, wer = [], []
        for k in seeds:
            path = os.path.join(exp, "%s_seed%s" % (s, k), "decode_" + test, "utt_errors")
            if not os.path.isfile(path):
                sys.exit("table2.py: missing %s (train and decode %s, seed %s first)" % (path, s, k))
            c, w = read_run(path)
            cer.append(c); wer.append(w)
        runs[s] = (cer, wer)
    return runs


def label_of(s, extra):
    return extra.get(s) or LABELS.get(s) or control_label(s) or s


def table(runs, sets, base, labels, title):
    n = len(next(iter(runs.values()))[0])
    out = ["### %s" % title, "",
           "| training RIR set | CER %% (mean of %d runs, 95 %% CI) | WER %% | CER vs %s, paired by seed (95 %% CI) "
           "| relative | d_z | p (paired t, seeds) | p (Welch, unpaired) |" % (n, label_of(base, labels)),
           "|---|---|---|---|---|---|---|---|"]
    bc = runs[base][0] if base in runs else None
    for s in sets:
        cer, wer = runs[s]
        row = "| %s | %s | %s |" % (label_of(s, labels), fmt_mean(cer), fmt_mean(wer))
        if bc is None or s == base:
            row += " — | — | — | — | — |"
        else:
            d, hw, p2, _, dz = paired(cer, bc)
            row += " %s | %+.1f %% | %s | %s | %s |" % (
                fmt_diff(d, hw), 100 * d / mean(bc), fmt_dz(dz), fmt_p(p2), fmt_p(welch(cer, bc)[2]))
        out.append(row)
    out.append("")
    out.append("Per-run CER (seeds in order): " + "; ".join(
        "%s %s" % (label_of(s, labels), " ".join("%.2f" % c for c in runs[s][0])) for s in sets))
    return out


def dose_check(runs, chain, alpha, labels):
    """Lines describing the dose-response chain, and whether it passes: the mean CER rises at every
    step, and the last set is worse than the first by a one-sided paired t-test over seeds at
    p < alpha (Welch's unpaired p printed beside it)."""
    means = [mean(runs[s][0]) for s in chain]
    rising = all(b > a for a, b in zip(means, means[1:]))
    last, first = runs[chain[-1]][0], runs[chain[0]][0]
    d, hw, _, p1, _ = paired(last, first)
    ok = rising and p1 < alpha
    steps = " -> ".join("%s %.2f" % (label_of(s, labels), m) for s, m in zip(chain, means))
    return ok, ["Dose-response (%s): %s; CER rises at every step: %s; %s vs %s %+.2f points paired by seed (%s), "
                "one-sided paired t p = %s (Welch, unpaired: %s): **%s** (needs a rise at every step "
                "and p < %g)" % (" -> ".join(chain), steps, "yes" if rising else "NO", label_of(chain[-1], labels),
                                 label_of(chain[0], labels), d, fmt_ci(d, hw), fmt_p(p1), fmt_p(welch(last, first)[3]),
                                 "PASS" if ok else "FAIL", alpha)]


def resolution(runs, base):
    """Smallest detectable CER difference (two-sided alpha 0.05, power 0.8): paired by seed, from
    the pooled SD of every set's per-seed differences against the baseline; and unpaired, from the
    pooled run-level SD."""
    n = len(next(iter(runs.values()))[0])
    if n < 2 or base not in runs:
        return None
    diffs = [[x - y for x, y in zip(c, runs[base][0])] for s, (c, _) in runs.items() if s != base]
    if not diffs:
        return None
    sd_pair = math.sqrt(mean([sd(d) ** 2 for d in diffs]))
    sd_run = math.sqrt(mean([sd(c) ** 2 for c, _ in runs.values()]))
    k = len(diffs)
    mde_pair = (t_quantile(0.975, k * (n - 1)) + t_quantile(0.8, k * (n - 1))) * sd_pair / math.sqrt(n)
    df = len(runs) * (n - 1)
    mde_run = (t_quantile(0.975, df) + t_quantile(0.8, df)) * sd_run * math.sqrt(2.0 / n)
    return mde_pair, sd_pair, mde_run, sd_run


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sets", default="clean real gas gas_eq gas_gsr gas_eq_gsr gas_gsr_eq gas_ext")
    ap.add_argument("--seeds", default="0")
    ap.add_argument("--baseline", default="gas")
    ap.add_argument("--tests", default="test_real")
    ap.add_argument("--titles", default="")
    ap.add_argument("--dose", action="append", default=[], help="a chain of sets of growing mismatch (repeatable)")
    ap.add_argument("--alpha", type=float, default=0.01)
    ap.add_argument("--labels", default="", help="set=label pairs separated by '|'")
    ap.add_argument("--require-dose", action="store_true", help="exit 3 when a dose check fails")
    ap.add_argument("exp")
    a = ap.parse_args()
    sets, seeds, tests = a.sets.split(), a.seeds.split(), a.tests.split()
    titles = a.titles.split("|") if a.titles else tests
    labels = dict(p.split("=", 1) for p in a.labels.split("|") if "=" in p)
    chains = [c.split() for c in a.dose]
    for c in chains:
        missing = [s for s in c if s not in sets]
        if missing or len(c) < 2:
            sys.exit("table2.py: --dose '%s' needs >= 2 sets, all in --sets" % " ".join(c))
    failed = False
    for test, title in zip(tests, titles):
        runs = collect(a.exp, sets, seeds, test)
        print("\n".join(table(runs, sets, a.baseline, labels, title)))
        for c in chains:
            ok, lines = dose_check(runs, c, a.alpha, labels)
            failed |= not ok
            print("\n" + "\n".join(lines))
        r = resolution(runs, a.baseline)
        if r:
            print("\nResolution (two-sided alpha 0.05, power 0.8, %d runs per set): paired by seed, SD of the per-seed "
                  "differences against %s %.2f CER points, smallest detectable difference %.2f points; unpaired, run-level "
                  "SD %.2f, %.2f points." % (len(seeds), label_of(a.baseline, labels), r[1], r[0], r[3], r[2]))
        print()
    return 3 if (failed and a.require_dose) else 0


if __name__ == "__main__":
    sys.exit(main())
