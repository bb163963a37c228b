#!/usr/bin/env python3
"""meridian.gravity's deflection against the C++ batch path on the same 10^6 points
(docs/benchmarks.md): the binding must add no per-point overhead (issue 13: within 10 %).

    MERIDIAN_BENCH_MODEL=../shared/data/gravity/egm96.egm \
    PYTHONPATH=build-bench/python /usr/bin/python3 bench/python_deflection_timing.py \
        build-bench/bench/bench_gravity [rounds]

Alternates the two, `rounds` times each (default 3), C++ first in even rounds and
Python first in odd ones, so a change in the machine's load hits both alike; prints every wall-clock and process CPU time (all threads: Google
Benchmark's MeasureProcessCPUTime, Python's time.process_time) and the medians. Both evaluate ξ, η only
(Quantities::Deflection / geoid=False) on all cores, the model loaded beforehand.
"""

import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import meridian.gravity as mg


def main():
    bench = sys.argv[1]
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    model_name = os.environ["MERIDIAN_BENCH_MODEL"]
    n = 1_000_000
    i = np.arange(n, dtype=np.float64)
    lat = -89.9 + 179.8 * i / (n - 1)  # as BM_Meridian_DeflectionModelFile
    lon = np.fmod(i * 137.508, 360.0)
    model = mg.GravityModel.open(model_name)
    py, cpp, py_cpu, cpp_cpu = [], [], [], []
    def run_cpp():
        r = subprocess.run([bench, "--benchmark_filter=BM_Meridian_DeflectionModelFile",
                            "--benchmark_format=json"], capture_output=True, text=True, check=True)
        b = json.loads(r.stdout)["benchmarks"][0]
        cpp.append(b["real_time"])  # seconds (Unit kSecond)
        cpp_cpu.append(b["cpu_time"])

    def run_py():
        t, c = time.perf_counter(), time.process_time()
        model.deflection(lat, lon, 0.0, geoid=False)
        py.append(time.perf_counter() - t)
        py_cpu.append(time.process_time() - c)

    for k in range(rounds):
        # Counterbalanced: C++ first in even rounds, Python first in odd ones.
        first, second = (run_cpp, run_py) if k % 2 == 0 else (run_py, run_cpp)
        first()
        second()
        print(f"round {k + 1} ({'C++' if k % 2 == 0 else 'Python'} first): C++ batch {cpp[-1]:.2f} s "
              f"(CPU {cpp_cpu[-1]:.2f} s)   meridian.gravity {py[-1]:.2f} s (CPU {py_cpu[-1]:.2f} s)   "
              f"load {os.getloadavg()[0]:.1f}", flush=True)
    print(f"model {model.name} degree {model.max_degree}, {n} points; median C++ {statistics.median(cpp):.2f} s, "
          f"Python {statistics.median(py):.2f} s, ratio {statistics.median(py) / statistics.median(cpp):.3f}; "
          f"CPU median C++ {statistics.median(cpp_cpu):.2f} s, Python {statistics.median(py_cpu):.2f} s, "
          f"ratio {statistics.median(py_cpu) / statistics.median(cpp_cpu):.3f}")


if __name__ == "__main__":
    main()
