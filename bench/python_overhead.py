"""The cost of growing from Python against the C++ call: dla3d.grow() (parsing the keywords,
setting the run up, growing with the GIL released, handing the arrays over) timed around the
call, against the growth time dla3d itself records (timings.grow_seconds) for the same command
line. Runs alternate, on several rng seeds, and the medians are compared (docs/performance.md).

    PYTHONPATH=build/python python3 bench/python_overhead.py --dla3d build/dla3d [-n 100000] [--runs 7]
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time

import dla3d


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--dla3d", default="build/dla3d")
    parser.add_argument("-n", type=int, default=100000)
    parser.add_argument("--runs", type=int, default=7)
    options = parser.parse_args()
    python, cpp = [], []
    with tempfile.TemporaryDirectory() as folder:
        prefix = os.path.join(folder, "run")
        for run in range(options.runs):
            seed = 100 + run
            start = time.perf_counter()
            result = dla3d.grow(particles=options.n, rng_seed=seed)
            python.append(time.perf_counter() - start)
            assert len(result) == options.n + 1
            subprocess.run([options.dla3d, "-n", str(options.n), "--rng-seed", str(seed), "-q", "--formats", "json",
                            "-o", prefix], check=True)
            with open(prefix + ".json") as record:
                cpp.append(json.load(record)["timings"]["grow_seconds"])
            print(f"seed {seed}: python {python[-1]:.3f} s, C++ {cpp[-1]:.3f} s", flush=True)
    p, c = statistics.median(python), statistics.median(cpp)
    print(f"median of {options.runs}: python {p:.3f} s, C++ {c:.3f} s, ratio {p / c:.4f} "
          f"({100 * (p / c - 1):+.1f}%)")


if __name__ == "__main__":
    main()
