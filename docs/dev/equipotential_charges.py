"""Lab experiment for issue 68 (docs/dev/breakdown-field.md): the dielectric breakdown model with
the structure's charges solved so that it is one conductor, against `--field charges`' equal charges.

Particles are balls of radius 1/2 a spacing apart. Charges q at their centres hold every ball at
potential 0 with the far boundary at 1: sum_j q_j G(x_i, x_j) = 1, G = 1/r in 3D and ln(R/r) in 2D
(R = 1e6, a far circle), the self term G(a). The potential at a candidate site x, a spacing from a
particle and no nearer any other, is phi(x) = 1 - sum_j q_j G(x, x_j); a site grows with weight
phi^eta, as on the lattice. The inverse of G grows by a bordered update, so a particle costs O(N^2):
this is the exact field for point charges, to measure the physics, not a method for long runs.

    OMP_NUM_THREADS=1 /usr/bin/python3 docs/dev/equipotential_charges.py --dim 3 --eta 2 --count 2000 --seeds 1 2 3

prints D from the radius of gyration over the last decade of growth, for each seed and their mean.
`--weights parent` weighs particles by their charge instead of sites by their potential;
`--local R` keeps the charges by sweeps within R spacings of each new particle and a solve each
10% of growth (`--every`), and with `--iterations K` too, that solve is K conjugate-gradient
steps and only the chosen particle's sites are evaluated: the fast field's design, which
reaches 10^4 particles.
"""

import argparse

import numpy as np

RADIUS = 0.5  # a particle's, in spacings
FAR = 1e6  # 2D: the far circle's radius, in spacings


def kernel(dim, r):
    return 1.0 / r if dim == 3 else np.log(FAR / r)


def directions(dim, rng, k):
    """k unit vectors in a random frame: a site's offsets from its particle."""
    if dim == 2:
        angle = rng.uniform(0, 2 * np.pi) + 2 * np.pi * np.arange(k) / k
        return np.stack([np.cos(angle), np.sin(angle)], axis=1)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    axes = np.concatenate([q.T, -q.T])
    return axes[:k]


def sites_beside(p, i, dim, rng, k):
    """The candidate sites beside particle i no nearer any particle than a spacing, and their
    distances to particles 0..i."""
    new = p[i] + directions(dim, rng, k)
    gap = np.linalg.norm(new[:, None, :] - p[None, : i + 1, :], axis=2)
    keep = gap.min(axis=1) > 1.0 - 1e-9
    return new[keep], gap[keep]


def gyration_dimension(p, count):
    """D from the radius of gyration against the count, over the last decade of growth."""
    counts = np.arange(1, count + 1)
    centre = np.cumsum(p, axis=0) / counts[:, None]
    square = np.cumsum((p**2).sum(axis=1)) / counts
    gyration = np.sqrt(np.maximum(square - (centre**2).sum(axis=1), 1e-12))
    last = counts >= count // 10
    return np.polyfit(np.log(gyration[last]), np.log(counts[last]), 1)[0]


def choose(rng, eta, weights, q, phi, live, owner):
    """The site that grows: by phi^eta over the open sites ("site"), or a particle by its charge
    to the power eta and then one of its open sites by phi^eta ("parent")."""
    if weights == "site":
        w = np.where(live, phi**eta, 0.0)
        return rng.choice(len(w), p=w / w.sum())
    has_site = np.zeros(len(q), bool)
    has_site[owner[live]] = True
    w = np.where(has_site, np.clip(q, 0.0, None) ** eta, 0.0)
    if w.sum() <= 0:
        w = has_site.astype(float)
    j = rng.choice(len(q), p=w / w.sum())
    mine = np.flatnonzero(live & (owner == j))
    ws = phi[mine] ** eta
    return mine[rng.choice(len(mine), p=ws / ws.sum())] if ws.sum() > 0 else rng.choice(mine)


def grow(dim, eta, count, seed, k, weights):
    rng = np.random.default_rng(seed)
    p = np.zeros((count, dim))
    inverse = np.zeros((count, count))
    inverse[0, 0] = 1.0 / kernel(dim, RADIUS)
    capacity = count * k + k
    sites = np.zeros((capacity, dim))
    owner = np.zeros(capacity, int)
    open_ = np.zeros(capacity, bool)
    to_charges = np.zeros((capacity, count))  # G(site, particle), kept as particles come
    n_sites = 0

    def add_sites(i):
        nonlocal n_sites
        new, gap = sites_beside(p, i, dim, rng, k)
        m = len(new)
        sites[n_sites : n_sites + m] = new
        owner[n_sites : n_sites + m] = i
        open_[n_sites : n_sites + m] = True
        to_charges[n_sites : n_sites + m, : i + 1] = kernel(dim, gap)
        n_sites += m

    add_sites(0)
    for n in range(1, count):
        q = inverse[:n, :n].sum(axis=1)
        phi = np.clip(1.0 - to_charges[:n_sites, :n] @ q, 0.0, None)
        s = choose(rng, eta, weights, q, phi, open_[:n_sites], owner[:n_sites])
        x = sites[s]
        p[n] = x
        # Bordered inverse: the new particle's row and column.
        b = kernel(dim, np.linalg.norm(p[:n] - x, axis=1))
        ab = inverse[:n, :n] @ b
        schur = kernel(dim, RADIUS) - b @ ab
        inverse[:n, :n] += np.outer(ab, ab) / schur
        inverse[:n, n] = -ab / schur
        inverse[n, :n] = -ab / schur
        inverse[n, n] = 1.0 / schur
        # Sites within a spacing of the new particle close; the rest learn its term.
        d = np.linalg.norm(sites[:n_sites] - x, axis=1)
        open_[:n_sites] &= d > 1.0 - 1e-9
        to_charges[:n_sites, n] = kernel(dim, np.maximum(d, 1e-9))
        add_sites(n)
    return gyration_dimension(p, count)


def grow_local(dim, eta, count, seed, k, radius, sweeps, every, weights):
    """The same model with the charges kept by local relaxation: a new particle takes the charge
    that holds it at 0, `sweeps` Gauss-Seidel sweeps relax the particles within `radius` spacings
    of it, and the whole system is solved afresh each time the count grows by the fraction
    `every`. With weights "parent", a particle grows with weight q^eta (its charge is the
    field on it, what the walkers' contacts count) and then its site by phi^eta."""
    rng = np.random.default_rng(seed)
    self_term = kernel(dim, RADIUS)
    p = np.zeros((count, dim))
    g = np.zeros((count, count))
    g[0, 0] = self_term
    q = np.zeros(count)
    q[0] = 1.0 / self_term
    capacity = count * k + k
    sites = np.zeros((capacity, dim))
    owner = np.zeros(capacity, int)
    open_ = np.zeros(capacity, bool)
    to_charges = np.zeros((capacity, count))
    n_sites = 0

    def add_sites(i):
        nonlocal n_sites
        new, gap = sites_beside(p, i, dim, rng, k)
        m = len(new)
        sites[n_sites : n_sites + m] = new
        owner[n_sites : n_sites + m] = i
        open_[n_sites : n_sites + m] = True
        to_charges[n_sites : n_sites + m, : i + 1] = kernel(dim, gap)
        n_sites += m

    add_sites(0)
    next_solve = 8
    for n in range(1, count):
        if n >= next_solve:
            q[:n] = np.linalg.solve(g[:n, :n], np.ones(n))
            next_solve = max(n + 1, int(n * (1 + every)))
        phi = np.clip(1.0 - to_charges[:n_sites, :n] @ q[:n], 0.0, None)
        s = choose(rng, eta, weights, q[:n], phi, open_[:n_sites], owner[:n_sites])
        x = sites[s]
        p[n] = x
        d = np.linalg.norm(p[:n] - x, axis=1)
        g[n, :n] = g[:n, n] = kernel(dim, d)
        g[n, n] = self_term
        q[n] = (1.0 - g[n, :n] @ q[:n]) / self_term
        near = np.append(np.flatnonzero(d < radius), n)
        for _ in range(sweeps):
            for i in near:
                q[i] += (1.0 - g[i, : n + 1] @ q[: n + 1]) / self_term
        ds = np.linalg.norm(sites[:n_sites] - x, axis=1)
        open_[:n_sites] &= ds > 1.0 - 1e-9
        to_charges[:n_sites, n] = kernel(dim, np.maximum(ds, 1e-9))
        add_sites(n)
    return gyration_dimension(p, count)


def grow_parents(dim, eta, count, seed, k, radius, sweeps, every, iterations):
    """"local" with parent weights as the fast field would run it: only the chosen particle's
    sites are evaluated, and each global solve is `iterations` conjugate-gradient steps from the
    kept charges rather than an exact solve. No matrix of site potentials, so it reaches 10^4."""
    rng = np.random.default_rng(seed)
    self_term = kernel(dim, RADIUS)
    p = np.zeros((count, dim))
    g = np.zeros((count, count))
    g[0, 0] = self_term
    q = np.zeros(count)
    q[0] = 1.0 / self_term
    capacity = count * k + k
    sites = np.zeros((capacity, dim))
    owner = np.zeros(capacity, int)
    open_ = np.zeros(capacity, bool)
    open_count = np.zeros(count, int)
    n_sites = 0

    def add_sites(i):
        nonlocal n_sites
        new, _ = sites_beside(p, i, dim, rng, k)
        m = len(new)
        sites[n_sites : n_sites + m] = new
        owner[n_sites : n_sites + m] = i
        open_[n_sites : n_sites + m] = True
        open_count[i] += m
        n_sites += m

    def conjugate_gradients(n):
        a = g[:n, :n]
        x = q[:n].copy()
        r = 1.0 - a @ x
        d = r.copy()
        rr = r @ r
        for _ in range(iterations):
            if rr < 1e-24 * n:
                break
            ad = a @ d
            step = rr / (d @ ad)
            x += step * d
            r -= step * ad
            rr, previous = r @ r, rr
            d = r + (rr / previous) * d
        q[:n] = x

    add_sites(0)
    next_solve = 8
    for n in range(1, count):
        if n >= next_solve:
            conjugate_gradients(n)
            next_solve = max(n + 1, int(n * (1 + every)))
        w = np.where(open_count[:n] > 0, np.clip(q[:n], 0.0, None) ** eta, 0.0)
        if w.sum() <= 0:
            w = (open_count[:n] > 0).astype(float)
        j = rng.choice(n, p=w / w.sum())
        mine = np.flatnonzero(open_[:n_sites] & (owner[:n_sites] == j))
        gap = np.linalg.norm(sites[mine][:, None, :] - p[None, :n, :], axis=2)
        phi = np.clip(1.0 - kernel(dim, gap) @ q[:n], 0.0, None)
        ws = phi**eta
        s = mine[rng.choice(len(mine), p=ws / ws.sum())] if ws.sum() > 0 else rng.choice(mine)
        x = sites[s]
        p[n] = x
        d = np.linalg.norm(p[:n] - x, axis=1)
        g[n, :n] = g[:n, n] = kernel(dim, d)
        g[n, n] = self_term
        q[n] = (1.0 - g[n, :n] @ q[:n]) / self_term
        near = np.append(np.flatnonzero(d < radius), n)
        for _ in range(sweeps):
            for i in near:
                q[i] += (1.0 - g[i, : n + 1] @ q[: n + 1]) / self_term
        closing = open_[:n_sites] & (np.linalg.norm(sites[:n_sites] - x, axis=1) <= 1.0 - 1e-9)
        np.subtract.at(open_count, owner[:n_sites][closing], 1)
        open_[:n_sites] &= ~closing
        add_sites(n)
    return gyration_dimension(p, count)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--dim", type=int, choices=(2, 3), default=3)
    parser.add_argument("--eta", type=float, default=1.0)
    parser.add_argument("--count", type=int, default=2000)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1])
    parser.add_argument("--sites", type=int, default=0, help="sites a particle: 6 in 3D, 6 in 2D")
    parser.add_argument("--local", type=float, default=0.0,
                        help="keep the charges by local relaxation within this many spacings (0: exactly)")
    parser.add_argument("--sweeps", type=int, default=2)
    parser.add_argument("--every", type=float, default=0.1, help="solve afresh as the count grows by this fraction")
    parser.add_argument("--weights", choices=("site", "parent"), default="site")
    parser.add_argument("--iterations", type=int, default=0,
                        help="with --local and --weights parent: conjugate-gradient steps a solve (0: exactly)")
    a = parser.parse_args()
    k = a.sites or 6
    if a.local > 0 and a.weights == "parent" and a.iterations > 0:
        ds = [grow_parents(a.dim, a.eta, a.count, seed, k, a.local, a.sweeps, a.every, a.iterations) for seed in a.seeds]
    elif a.local > 0:
        ds = [grow_local(a.dim, a.eta, a.count, seed, k, a.local, a.sweeps, a.every, a.weights) for seed in a.seeds]
    else:
        ds = [grow(a.dim, a.eta, a.count, seed, k, a.weights) for seed in a.seeds]
    for seed, d in zip(a.seeds, ds):
        print(f"dim {a.dim} eta {a.eta} count {a.count} seed {seed}: D = {d:.3f}")
    if len(ds) > 1:
        print(f"mean {np.mean(ds):.3f} +- {np.std(ds, ddof=1) / np.sqrt(len(ds)):.3f}")


if __name__ == "__main__":
    main()
