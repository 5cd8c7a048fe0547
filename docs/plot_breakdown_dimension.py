#!/usr/bin/env python3
"""Draws docs/images/breakdown_dimension.png: the fractal dimension of the breakdown model
against eta, in 2D and 3D, from ensembles grown by the Python module (docs/breakdown.md).

    PYTHONPATH=build/python python3 docs/plot_breakdown_dimension.py [OUT.png]

Each point is the mean over CLUSTERS runs of PARTICLES particles of D from the radius of
gyration (its last decade), with the standard error of the mean as its bar; the runs go on
both cores, one thread each: about five minutes.
"""
import multiprocessing
import statistics
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import dla3d

PARTICLES = 4000
CLUSTERS = 6
ETAS = (0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0)
# S. Satpathy, Phys. Rev. B 33, 5093 (1986): the lattice model in 3D.
SATPATHY_3D = {1.0: 2.5, 2.0: 2.1, 3.0: 1.9, 4.0: 1.75}


def dimension(job):
    dimensions, eta, seed = job
    # At eta 1 eight walkers, so that the point is the breakdown model's and not DLA's walker.
    walkers = 8 if eta == 1.0 else 0
    result = dla3d.breakdown(particles=PARTICLES, eta=eta, dimensions=dimensions, rng_seed=seed,
                             threads=1, walkers=walkers)
    return result.fractal_dimension()[0]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "docs/images/breakdown_dimension.png"
    jobs = [(d, eta, 4000 + i) for d in (2, 3) for eta in ETAS for i in range(CLUSTERS)]
    with multiprocessing.Pool(2) as pool:
        values = pool.map(dimension, jobs, chunksize=1)
    points = {}
    for (d, eta, _), value in zip(jobs, values):
        points.setdefault((d, eta), []).append(value)

    figure, axes = plt.subplots(figsize=(6.4, 4.4), dpi=100)
    for d, colour in ((3, "tab:blue"), (2, "tab:orange")):
        means = [statistics.mean(points[(d, eta)]) for eta in ETAS]
        errors = [statistics.stdev(points[(d, eta)]) / len(points[(d, eta)]) ** 0.5 for eta in ETAS]
        axes.errorbar(ETAS, means, yerr=errors, marker="o", capsize=3, color=colour,
                      label=f"dla3d breakdown, {d}D ({CLUSTERS} runs of {PARTICLES:,})")
        for eta, mean, error in zip(ETAS, means, errors):
            print(f"{d}D eta {eta}: D = {mean:.3f} +- {error:.3f}")
    axes.plot(list(SATPATHY_3D), list(SATPATHY_3D.values()), "s", color="tab:blue", fillstyle="none",
              markersize=9, label="Satpathy 1986, 3D lattice")
    axes.plot([1.0], [2.50], "D", color="black", fillstyle="none", markersize=8, label="DLA, 3D and 2D")
    axes.plot([1.0], [1.71], "D", color="black", fillstyle="none", markersize=8)
    axes.axhline(1.0, color="grey", linewidth=0.8, linestyle=":")
    axes.set_xlabel("η")
    axes.set_ylabel("fractal dimension D (radius of gyration)")
    axes.set_title("The breakdown model: D against η")
    axes.legend(fontsize=8)
    axes.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(out)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
