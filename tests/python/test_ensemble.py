"""Ensembles on Dask: a LocalCluster of 2 workers grows what single runs grow, and measures
3D DLA's fractal dimension."""

import json
import subprocess
import sys

import numpy as np
import pytest

import dla3d
from dla3d.ensemble import grow_one

distributed = pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with distributed.Client(cluster) as client:
        yield client
    cluster.close()


def test_six_clusters_on_two_workers_are_six_single_runs(client, cli, tmp_path):
    seen = []
    summary = dla3d.ensemble("grow", 6, seeds=1, client=client, particles=100000, save=str(tmp_path / "c"),
                             on_cluster=seen.append)
    assert len(seen) == 6 and summary["count"] == 6
    assert sorted(c["rng_seed"] for c in summary["clusters"]) == [1, 2, 3, 4, 5, 6]
    assert {w for w in client.scheduler_info()["workers"]} and len(client.scheduler_info()["workers"]) == 2
    for measures in summary["clusters"]:
        single = grow_one("grow", {"particles": 100000}, measures["rng_seed"])
        assert measures == single
    # A cluster written on a worker is the CLI's for its seed, byte for byte.
    cli("--particles", "100000", "--rng-seed", "4", "-q", "--formats", "csv", "-o", str(tmp_path / "cli"))
    assert (tmp_path / "c_4.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    # 3D DLA: D = 2.50 +- 0.03 by gyration on twenty clusters (growth_test.cpp), +- 0.1 by
    # mass-radius. Six clusters cannot pin the mean that closely (one cluster's D spreads by
    # about 0.07), so their 95% interval must reach the band.
    gyration = summary["fractal_dimension"]["gyration"]
    assert gyration["mean"] - gyration["ci95"] <= 2.53 and gyration["mean"] + gyration["ci95"] >= 2.47
    assert 0 < gyration["ci95"] < 0.1
    assert abs(summary["fractal_dimension"]["mass_radius"]["mean"] - 2.50) < 0.1
    # Rg against n: one n grid, Rg growing, and a fit near D.
    rg = summary["gyration"]
    assert rg["n"][-1] == 100001 and (np.diff(rg["mean"]) > 0).all()
    assert abs(rg["fit"]["dimension"] - 2.5) < 0.1
    walkers = summary["statistics"]["walk.walkers"]
    assert walkers["mean"] == 100000 and walkers["ci95"] == 0


def test_every_model_runs_as_an_ensemble(client):
    for model, options in [("colonize", {"max_nodes": 500}), ("drop", {"particles": 500}),
                           ("ballistic", {"particles": 500}), ("eden", {"sites": 500}),
                           ("grow", {"particles": 500, "dimensions": 2})]:
        summary = dla3d.ensemble(model, 3, seeds=[10, 20, 30], client=client, **options)
        assert [c["rng_seed"] for c in summary["clusters"]] == [10, 20, 30]
        assert summary["statistics"] and summary["fractal_dimension"]["gyration"]["count"] >= 0
    # An aggregate's dimension is its record's law, fitted over the clusters its joins made.
    summary = dla3d.ensemble("aggregate", 3, seeds=[10, 20, 30], client=client, monomers=400, mode="tuned")
    law = summary["statistics"]["measures.aggregate.fractal_dimension"]
    assert law["count"] == 3 and abs(law["mean"] - 1.8) < 1e-3
    assert summary["fractal_dimension"]["gyration"]["count"] == 0


def test_bad_ensembles_are_refused_before_any_worker_starts():
    with pytest.raises(ValueError, match=r"particles=-5 is not in \[0, 2e\+09\]"):
        dla3d.ensemble("grow", 2, particles=-5)
    with pytest.raises(ValueError, match="rng_seed is set per cluster"):
        dla3d.ensemble("grow", 2, rng_seed=3)
    with pytest.raises(ValueError, match="seeds holds 1 rng seeds for 2 clusters"):
        dla3d.ensemble("grow", 2, seeds=[1])
    with pytest.raises(ValueError, match="not a whole number of clusters"):
        dla3d.ensemble("grow", 0)


def test_the_command_writes_json_and_a_plot(tmp_path):
    done = subprocess.run([sys.executable, "-m", "dla3d.ensemble", "--count", "3", "--workers", "2", "-n", "3000",
                           "-o", str(tmp_path / "e")], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "3 clusters in" in done.stderr and "wrote" in done.stderr
    summary = json.loads((tmp_path / "e.json").read_text())
    assert summary["count"] == 3 and summary["command"] == "dla3d -n 3000"
    png = (tmp_path / "e.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10000
    refused = subprocess.run([sys.executable, "-m", "dla3d.ensemble", "--count", "2", "--stickiness", "7"],
                             capture_output=True, text=True, timeout=120)
    assert refused.returncode == 2 and "error:" in refused.stderr and "stickiness" in refused.stderr
