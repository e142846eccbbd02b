#!/usr/bin/env python3
"""Table of the Kaldi GMM runs of local/kaldi/run_asr.sh --stop-after gmm in <root>/<set> (issue 19 item 6,
docs/results/kaldi_gmm.md): best WER/CER (Kaldi's scoring), WER at a
fixed LM weight 10 / penalty 0.0, and a paired sign-flip permutation test over test utterances of
the per-utterance errors of each set vs the baseline (at each set's best operating point)."""
import os, re, random, sys
# Usage: bench/asr/kaldi_gmm_table.py <root> "<sets>" [baseline set (gas)]
root = sys.argv.pop(1)
sets = sys.argv[1].split()
base = sys.argv[2] if len(sys.argv) > 2 else 'gas'
def best(d, kind):
    f = os.path.join(d, 'scoring_kaldi', 'best_' + kind)
    if not os.path.exists(f): return None
    m = re.search(r'%WER ([\d.]+) \[ (\d+) / (\d+)', open(f).read()); return float(m.group(1))
def fixed(d, name='wer_10_0.0'):
    f = os.path.join(d, name)
    if not os.path.exists(f): return None
    m = re.search(r'%WER ([\d.]+)', open(f).read()); return float(m.group(1))
def per_utt(d, kind='wer'):
    f = os.path.join(d, 'scoring_kaldi', kind + '_details', 'per_utt')
    e = {}
    for l in open(f):
        t = l.split()
        if len(t) == 6 and t[1] == '#csid': e[t[0]] = int(t[3]) + int(t[4]) + int(t[5])
    return e
def perm_p(a, b, n=20000, seed=0):
    d = [a[u] - b[u] for u in a]; obs = abs(sum(d)); r = random.Random(seed); c = 0
    for _ in range(n):
        if abs(sum(x if r.random() < 0.5 else -x for x in d)) >= obs - 1e-9: c += 1
    return (c + 1) / (n + 1)
fp = lambda p: '< 0.0001' if p < 0.0001 else f'{p:.4f}'
dec = lambda s, m, x: f'{root}/{s}/exp/{m}/decode_small_{x}'
rows = []
print('| set | mono WER | tri1 WER | tri2b WER | tri2b CER | tri2b WER (lmwt 10, wip 0) | tri2b WER vs %s | p (paired, words) | p (paired, chars) | tri2b WER real speech | tri2b CER real speech |' % base)
print('|---|---|---|---|---|---|---|---|---|---|---|')
bw = per_utt(dec(base, 'tri2b', 'test_farfield')); bc = per_utt(dec(base, 'tri2b', 'test_farfield'), 'cer')
bwer = best(dec(base, 'tri2b', 'test_farfield'), 'wer')
for s in sets:
    if not os.path.exists(dec(s, 'tri2b', 'test_farfield') + '/scoring_kaldi/best_cer'):
        print(f'| {s} | (not run) |'); continue
    w = {m: best(dec(s, m, 'test_farfield'), 'wer') for m in ('mono', 'tri1', 'tri2b')}
    c = best(dec(s, 'tri2b', 'test_farfield'), 'cer')
    f10 = fixed(dec(s, 'tri2b', 'test_farfield'))
    rw = best(dec(s, 'tri2b', 'test_realspeech'), 'wer'); rc = best(dec(s, 'tri2b', 'test_realspeech'), 'cer')
    if s == base: rel = p1 = p2 = '—'
    else:
        rel = f'{100 * (w["tri2b"] - bwer) / bwer:+.1f} %'
        p1 = fp(perm_p(per_utt(dec(s, "tri2b", "test_farfield")), bw))
        p2 = fp(perm_p(per_utt(dec(s, "tri2b", "test_farfield"), "cer"), bc))
    fm = lambda v: '—' if v is None else f'{v:.2f}'
    print(f'| {s} | {fm(w["mono"])} | {fm(w["tri1"])} | {fm(w["tri2b"])} | {fm(c)} | {fm(f10)} | {rel} | {p1} | {p2} | {fm(rw)} | {fm(rc)} |')
