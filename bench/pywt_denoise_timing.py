#!/usr/bin/env python3
"""PyWavelets timing of the denoising that bench_maglev's Denoise1M measures.

10^6 samples (white 1e-5 + AR(1) 0.8/2e-6 around 0.01, numpy's generator: the
same statistics, not the same numbers), pywt.wavedec(db4, level 6,
mode symmetric) -> universal soft threshold on every detail array
(sigma = median(|d1|)/0.6745, lambda = sigma*sqrt(2 ln n)) -> pywt.waverec.
Prints the mean and minimum of REPEAT runs in ms, wall-clock and CPU time\n(the CPU time is comparable with Google Benchmark's CPU column on a loaded machine).

Usage: /usr/bin/python3 bench/pywt_denoise_timing.py [REPEAT]
"""
import sys
import time

import numpy as np
import pywt


def series(n=1_000_000):
    rng = np.random.default_rng(42)
    e = rng.standard_normal(n) * 2e-6
    u = np.empty(n)
    acc = 0.0
    # AR(1) by a plain loop: only the input is made here, it is not timed.
    phi = 0.8
    for i in range(n):
        acc = phi * acc + e[i]
        u[i] = acc
    return 0.01 + 1e-5 * rng.standard_normal(n) + u


def denoise(x):
    c = pywt.wavedec(x, "db4", mode="symmetric", level=6)
    sigma = np.median(np.abs(c[-1])) / 0.6745
    lam = sigma * np.sqrt(2.0 * np.log(len(x)))
    c = [c[0]] + [pywt.threshold(d, lam, mode="soft") for d in c[1:]]
    return pywt.waverec(c, "db4", mode="symmetric")[: len(x)]


def main():
    repeat = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    x = series()
    denoise(x)  # warm-up
    wall, cpu = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        denoise(x)
        wall.append((time.perf_counter() - t0) * 1e3)
        cpu.append((time.process_time() - c0) * 1e3)
    print("pywt %s numpy %s: denoise 1e6 samples db4 level 6 soft universal (%d runs): "
          "wall mean %.2f ms min %.2f ms; CPU mean %.2f ms min %.2f ms"
          % (pywt.__version__, np.__version__, repeat, sum(wall) / repeat, min(wall), sum(cpu) / repeat, min(cpu)))


if __name__ == "__main__":
    main()
