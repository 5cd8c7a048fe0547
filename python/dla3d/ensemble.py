"""Ensembles of clusters on Dask: grow many, measure each where it grew, and gather the measures.

    import dla3d
    summary = dla3d.ensemble("grow", 100, seeds=1, particles=100000)  # a LocalCluster
    summary["fractal_dimension"]["gyration"]   # {"mean": 2.50, "ci95": 0.006, ...}

From the shell, on any Dask scheduler:

    python3 -m dla3d.ensemble --count 100 -n 100000 --scheduler tcp://HOST:8786

Cluster k grows with the rng seed seeds + k (or seeds[k]), exactly as `dla3d ... --rng-seed S`
grows it: the same structure, byte for byte. See docs/python.md.
"""

import argparse
import hashlib
import json
import math
import os
import sys
import tempfile
import time
import types

import numpy as np

from . import _core, _check_keywords, _command

# Student's t at 97.5% for 1-30 degrees of freedom; beyond, the normal 1.96.
_T975 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145,
         2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048,
         2.045, 2.042]
# The fit of Rg against n over the ensemble: the last decade, as `dla3d analyze` fits one cluster.
_GYRATION_SAMPLES = 40


def _interval(values):
    """Mean, the half-width of its 95% confidence interval (Student's t), and the spread."""
    values = np.asarray([v for v in values if v is not None and math.isfinite(v)], dtype=float)
    if len(values) == 0:
        return {"mean": None, "ci95": None, "std": None, "count": 0}
    mean = float(values.mean())
    if len(values) < 2:
        return {"mean": mean, "ci95": None, "std": None, "count": 1}
    std = float(values.std(ddof=1))
    t = _T975[len(values) - 2] if len(values) - 1 <= len(_T975) else 1.96
    return {"mean": mean, "ci95": t * std / math.sqrt(len(values)), "std": std, "count": int(len(values))}


def _numbers(record, prefix=""):
    """The numbers of a JSON record, flattened to dotted names: the model's statistics."""
    found = {}
    for key, value in record.items():
        name = prefix + key
        if isinstance(value, dict):
            found.update(_numbers(value, name + "."))
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            found[name] = value
    return found


def grow_one(model, options, rng_seed, save=None, formats=("csv",)):
    """Grows one cluster (on a worker) and returns its measures; with `save`, also writes its
    files as SAVE_SEED.EXT, which are the CLI's for that seed."""
    options = dict(options, rng_seed=rng_seed)
    result = _core.grow_run(model, options, _command(model, options), None)
    with tempfile.TemporaryDirectory() as folder:
        result.write(os.path.join(folder, "run"), ["json"])
        with open(os.path.join(folder, "run.json")) as record_file:
            record = json.load(record_file)
    if "aggregate" in record.get("measures", {}):
        # An aggregate's particles are in no attach order: its law is the one its record fits
        # over the clusters its joins made (statistics' measures.aggregate.fractal_dimension).
        gyration = mass_radius = None
        n, rg = np.zeros(0), np.zeros(0)
    else:
        gyration, mass_radius = result.fractal_dimension()
        n, rg = result.gyration(100, _GYRATION_SAMPLES)
    if save:
        result.write(f"{save}_{rng_seed}", list(formats))
    identity = hashlib.sha256()
    for array in (result.positions, result.parent, result.seed):
        identity.update(np.ascontiguousarray(array).tobytes())
    # What the run measured and counted; its options and what they resolved to say what was
    # asked, and its timings vary with the machine.
    statistics = {k: v for k, v in _numbers(record).items()
                  if k != "rng_seed" and not k.startswith(("options.", "resolved.", "look.", "timings."))}
    return {
        "rng_seed": rng_seed,
        "particles": len(result),
        "complete": result.complete,
        "sha256": identity.hexdigest(),
        "fractal_dimension_gyration": gyration,
        "fractal_dimension_mass_radius": mass_radius,
        "gyration_n": n.tolist(),
        "gyration_radius": rg.tolist(),
        "statistics": statistics,
    }


def summarize(model, options, clusters):
    """The ensemble's measures, with 95% confidence intervals, from the clusters' own."""
    clusters = sorted(clusters, key=lambda c: c["rng_seed"])
    summary = {
        "model": model,
        "command": _command(model, options),
        "count": len(clusters),
        "fractal_dimension": {
            "gyration": _interval(c["fractal_dimension_gyration"] for c in clusters),
            "mass_radius": _interval(c["fractal_dimension_mass_radius"] for c in clusters),
        },
    }
    # Rg against n where every cluster has the same n (clusters of one size): the mean at each n,
    # and D from the fit of log Rg = log n / D + c over the last decade.
    same = [c for c in clusters if c["gyration_n"] == clusters[0]["gyration_n"]]
    if clusters and len(same) == len(clusters) and len(clusters[0]["gyration_n"]) >= 2:
        n = np.asarray(clusters[0]["gyration_n"], dtype=float)
        rg = np.asarray([c["gyration_radius"] for c in clusters])
        points = [_interval(rg[:, k]) for k in range(len(n))]
        last_decade = n >= n[-1] / 10
        mean = np.asarray([p["mean"] for p in points])
        slope, intercept = np.polyfit(np.log(n[last_decade]), np.log(mean[last_decade]), 1)
        summary["gyration"] = {
            "n": n.astype(int).tolist(),
            "mean": mean.tolist(),
            "ci95": [p["ci95"] for p in points],
            "fit": {"dimension": 1.0 / slope, "intercept": intercept, "from_n": int(n[last_decade][0])},
        }
    names = sorted({name for c in clusters for name in c["statistics"]})
    summary["statistics"] = {name: _interval(c["statistics"].get(name) for c in clusters) for name in names}
    summary["clusters"] = clusters
    return summary


def _seed_list(count, seeds):
    if isinstance(seeds, int):
        return [seeds + k for k in range(count)]
    seeds = [int(s) for s in seeds]
    if len(seeds) != count:
        raise ValueError(f"seeds holds {len(seeds)} rng seeds for {count} clusters")
    return seeds


def run_ensemble(model, count, seeds=1, client=None, save=None, formats=("csv",), on_cluster=None, **options):
    """Grows `count` clusters of `model` with `options` (keyword arguments as for dla3d.grow and
    the others) on a Dask `client`: None starts a LocalCluster of one single-threaded worker a
    core; a string is a scheduler's address. Cluster k has the rng seed seeds + k (an int) or
    seeds[k]. `on_cluster(measures)` sees each cluster's measures as it comes in. Returns the
    summary: see summarize()."""
    if "rng_seed" in options:
        raise ValueError("rng_seed is set per cluster: give the ensemble's seeds instead")
    if any(not isinstance(v, str) and isinstance(v, (tuple, list)) and len(v) == 2 and hasattr(v[0], "shape")
           for v in options.values()):
        raise ValueError("an ensemble takes meshes as files, which every worker reads")
    return _run(model, options, count, seeds, client, save, formats, on_cluster)


def _run(model, options, count, seeds, client, save, formats, on_cluster, workers=None):
    if not isinstance(count, int) or count < 1:
        raise ValueError(f"count {count!r} is not a whole number of clusters, at least 1")
    seed_list = _seed_list(count, seeds)
    _check_keywords(model, options)
    _core.check(model, options)  # here, once, rather than on every worker
    from dask.distributed import Client, LocalCluster, as_completed
    own = None
    if client is None:
        own = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                           dashboard_address=None)
        client = Client(own)
    elif isinstance(client, str):
        client = own = Client(client)
    try:
        futures = client.map(grow_one, [model] * count, [options] * count, seed_list, [save] * count,
                             [tuple(formats)] * count, pure=False)
        clusters = []
        for future in as_completed(futures):
            measures = future.result()
            clusters.append(measures)
            if on_cluster:
                on_cluster(measures)
    finally:
        if own is not None:
            client.close()
            own.close()
    return summarize(model, options, clusters)


def plot(summary, path):
    """Rg against n, the ensemble's mean with its 95% interval and the fit, as a PNG."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    gyration = summary["gyration"]
    n = np.asarray(gyration["n"], dtype=float)
    mean = np.asarray(gyration["mean"])
    ci = np.asarray([c or 0.0 for c in gyration["ci95"]])
    fit = gyration["fit"]
    figure, axes = plt.subplots(figsize=(6, 4.5), dpi=100)
    axes.fill_between(n, mean - ci, mean + ci, color="tab:blue", alpha=0.25, label="95% interval")
    axes.loglog(n, mean, "o", color="tab:blue", markersize=3, label=f"mean of {summary['count']} clusters")
    fitted = n[n >= fit["from_n"]]
    axes.loglog(fitted, np.exp(fit["intercept"]) * fitted ** (1.0 / fit["dimension"]), "-", color="tab:red",
                label=f"fit: D = {fit['dimension']:.3f}")
    axes.set_xlabel("particles n")
    axes.set_ylabel("radius of gyration Rg")
    axes.set_title(summary["command"], fontsize=8)
    axes.legend()
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)


def _value(text):
    """A word as the keyword's value: a number, numbers (x,y,z), or the word itself."""
    def number(part):
        try:
            return int(part)
        except ValueError:
            return float(part)

    try:
        values = [number(p) for p in text.split(",")]
    except ValueError:
        return text
    return values[0] if len(values) == 1 else tuple(values)


def _keywords(words):
    """The model's options given on this tool's command line as --name VALUE (or a lone --flag),
    -n for the count, as keyword arguments: the library checks them as it checks Python's."""
    keywords = {}
    at = 0
    while at < len(words):
        word = words[at]
        if not word.startswith("-"):
            raise ValueError(f"{word}: not an option (--name VALUE)")
        name, _, value = word.lstrip("-").partition("=")
        name = name.replace("-", "_")
        if not value:
            if at + 1 < len(words) and not (words[at + 1].startswith("--") or words[at + 1] == "-n"):
                value = words[at + 1]
                at += 1
        keywords[name] = True if not value else _value(value)
        at += 1
    return keywords


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m dla3d.ensemble",
        description="Grow an ensemble of clusters on Dask and measure it. Words it does not know "
                    "(-n 100000, --dimensions 2) go to the model, as on dla3d's command line.")
    parser.add_argument("--model", default="grow", choices=[name for name, _ in _core.models()])
    parser.add_argument("--count", type=int, default=10, help="clusters (default 10)")
    parser.add_argument("--first-seed", type=int, default=1, help="cluster k has rng seed FIRST_SEED + k (default 1)")
    parser.add_argument("--scheduler", help="a Dask scheduler's address (tcp://HOST:8786); "
                                            "default: a LocalCluster of one worker a core")
    parser.add_argument("--workers", type=int, help="with no scheduler: the LocalCluster's workers")
    parser.add_argument("--output", "-o", default="ensemble", help="writes OUTPUT.json and OUTPUT.png")
    parser.add_argument("--save", help="also write each cluster's CSV, as SAVE_SEED.csv")
    options, words = parser.parse_known_args(argv)
    if options.count < 1:
        parser.error(f"--count {options.count} is not at least 1")
    if options.workers is not None and (options.scheduler or options.workers < 1):
        parser.error("--workers starts a LocalCluster of at least 1 worker, without --scheduler")
    for word in words:
        if word in ("-o", "--output", "--formats", "--rng-seed") or word.startswith(("--rng-seed=", "--formats=")):
            parser.error(f"{word}: the ensemble sets it for each cluster")
    try:
        model_options = _keywords(words)
    except ValueError as error:
        parser.error(str(error))
    start = time.time()
    done = []

    def report(measures):
        done.append(measures)
        print(f"\rdla3d.ensemble: {len(done)}/{options.count} clusters, "
              f"{time.time() - start:.0f} s", end="", file=sys.stderr, flush=True)

    try:
        summary = _run(options.model, model_options, options.count, options.first_seed, options.scheduler, options.save,
                       ("csv",), report, options.workers)
    except (ValueError, OSError) as error:  # bad options; a scheduler out of reach, a file a worker lacks
        print(f"\ndla3d.ensemble: error: {error}", file=sys.stderr)
        return 2
    summary["seconds"] = time.time() - start
    with open(options.output + ".json", "w") as out:
        json.dump(summary, out, indent=1)
    written = options.output + ".json"
    if "gyration" in summary:
        plot(summary, options.output + ".png")
        written += " " + options.output + ".png"
    d = summary["fractal_dimension"]
    fmt = lambda v: "n/a" if v["mean"] is None else f"{v['mean']:.3f} ± {v['ci95'] or 0:.3f}"
    print(f"\ndla3d.ensemble: {summary['count']} clusters in {summary['seconds']:.1f} s; D by gyration "
          f"{fmt(d['gyration'])}, by mass-radius {fmt(d['mass_radius'])} (95%)\ndla3d.ensemble: wrote {written}",
          file=sys.stderr)
    return 0


class _Callable(types.ModuleType):
    """Importing this module makes it the package's `ensemble`, in place of the function of that
    name in dla3d/__init__.py: so the module, when called, is that function."""

    def __call__(self, model, count, seeds=1, client=None, **options):
        return run_ensemble(model, count, seeds, client=client, **options)


if __name__ == "__main__":
    sys.exit(main())
sys.modules[__name__].__class__ = _Callable
