#!/usr/bin/env python3
"""Reference vectors for tests/maglev/test_wavelet_reference.cpp from PyWavelets.

Usage: pywt_reference.py OUT_FILE

Writes, for deterministic test signals, pywt.wavedec coefficients, the
pywt.waverec reconstruction, and the universal-threshold denoising
(wavedec -> pywt.threshold(soft|hard) on every detail array -> waverec) as
text blocks:

    case <name> <wavelet> <mode> <level> <threshold|->
    x <values>
    c<k> <values>          (k = 0 … level, pywt.wavedec order)
    rec <values>
    den <values>           (only when a threshold is named)
    end

and SURE cases (threshold sure-soft | sure-hard): per detail level the SURE
threshold, computed here by brute force over t in {0, |d_i/sigma|} up to
sqrt(2 ln n_j), is the chosen coefficient's own |d_i| (so one coefficient
sits exactly on it: pywt.threshold 'hard' keeps |d| >= lambda), then
pywt.threshold and pywt.waverec.

Exits non-zero (so the CTest test fails) when pywt or numpy is missing.
Run with Debian's python3 (python3-pywt, python3-numpy; scripts/setup.sh).
"""
import sys

import numpy as np
import pywt


def fmt(v):
    return " ".join(repr(float(x)) for x in v)


def signals():
    rng = np.random.default_rng(20261201)
    t = np.arange(1000) / 50.0
    yield "sine_noise_1000", 0.3 + 0.01 * np.sin(0.7 * t) + 1e-4 * rng.standard_normal(1000)
    yield "random_odd_777", rng.standard_normal(777)
    yield "steps_513", np.where(np.arange(513) < 200, 1.0, -0.5) + 0.05 * rng.standard_normal(513)
    yield "short_64", rng.standard_normal(64)


def sure_lambda(d, sigma):
    a = np.abs(np.asarray(d))
    z = a / sigma
    n = len(z)
    limit = np.sqrt(2.0 * np.log(max(n, 2)))
    best_t, best_risk, best_i = 0.0, float(n), -1
    for i in np.argsort(z, kind="stable"):
        t = z[i]
        if t > limit:
            break
        risk = n - 2.0 * np.count_nonzero(z <= t) + np.sum(np.minimum(z * z, t * t))
        if risk < best_risk:
            best_t, best_risk, best_i = t, risk, i
    return 0.0 if best_i < 0 else float(a[best_i])


def sure_cases(out):
    rng = np.random.default_rng(301)
    t = np.arange(301) / 20.0
    signals = [("sine_301", np.sin(0.9 * t) + 0.3 * rng.standard_normal(301)),
               ("sine_1000", 0.5 * np.sin(0.2 * np.arange(1000)) + 0.2 * rng.standard_normal(1000))]
    for name, x in signals:
        for n in (2, 4, 10):
            w = pywt.Wavelet("db%d" % n)
            for mode in ("symmetric", "periodization"):
                for thr in ("soft", "hard"):
                    level = 3
                    c = pywt.wavedec(x, w, mode=mode, level=level)
                    sigma = np.median(np.abs(c[-1])) / 0.6745
                    d = [c[0]] + [pywt.threshold(a, sure_lambda(a, sigma), mode=thr) for a in c[1:]]
                    out.write("case %s db%d %s %d sure-%s\n" % (name, n, mode, level, thr))
                    out.write("x %s\n" % fmt(x))
                    out.write("den %s\n" % fmt(pywt.waverec(d, w, mode=mode)[: len(x)]))
                    out.write("end\n")


def main():
    out = open(sys.argv[1], "w")
    out.write("# pywt %s numpy %s\n" % (pywt.__version__, np.__version__))
    for name, x in signals():
        for n in range(2, 11):
            w = pywt.Wavelet("db%d" % n)
            top = pywt.dwt_max_level(len(x), w.dec_len)
            for mode in ("symmetric", "periodization"):
                for level in sorted({1, top}):
                    if level < 1:
                        continue
                    thr = "soft" if (n + level) % 2 == 0 else "hard"
                    c = pywt.wavedec(x, w, mode=mode, level=level)
                    out.write("case %s db%d %s %d %s\n" % (name, n, mode, level, thr))
                    out.write("x %s\n" % fmt(x))
                    for k, a in enumerate(c):
                        out.write("c%d %s\n" % (k, fmt(a)))
                    out.write("rec %s\n" % fmt(pywt.waverec(c, w, mode=mode)))
                    sigma = np.median(np.abs(c[-1])) / 0.6745
                    lam = sigma * np.sqrt(2.0 * np.log(len(x)))
                    d = [c[0]] + [pywt.threshold(a, lam, mode=thr) for a in c[1:]]
                    out.write("den %s\n" % fmt(pywt.waverec(d, w, mode=mode)[: len(x)]))
                    out.write("end\n")
    sure_cases(out)
    out.close()


if __name__ == "__main__":
    main()
