"""The specimen checks of scripts/study.py on a packing's arrays (numpy only): the pairs that
bond formation bonds and the largest bonded cluster (separate so the runner stays readable)."""
import numpy as np


def bonded_pairs(x, r, eta):
    """Pairs (i < j) that dem/bonds/bonding.cc bonds: |x_i - x_j| <= eta (r_i + r_j) (1 + 1e-9)."""
    n = len(x)
    h = 2.0 * eta * r.max() * (1 + 1e-9)
    c = np.floor((x - x.min(axis=0)) / h).astype(np.int64)
    dims = c.max(axis=0) + 1
    key = (c[:, 2] * dims[1] + c[:, 1]) * dims[0] + c[:, 0]
    order = np.argsort(key, kind="stable")
    skey = key[order]
    I, J = [], []
    idx = np.arange(n)
    for dz in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                cc = c + np.array([dx, dy, dz])
                ok = np.all((cc >= 0) & (cc < dims), axis=1)
                nk = (cc[:, 2] * dims[1] + cc[:, 1]) * dims[0] + cc[:, 0]
                lo = np.searchsorted(skey, nk, "left")
                hi = np.searchsorted(skey, nk, "right")
                cnt = np.where(ok, hi - lo, 0)
                tot = int(cnt.sum())
                if tot == 0:
                    continue
                ii = np.repeat(idx, cnt)
                start = np.repeat(lo, cnt)
                offs = np.arange(tot) - np.repeat(np.cumsum(cnt) - cnt, cnt)
                jj = order[start + offs]
                keep = ii < jj
                I.append(ii[keep])
                J.append(jj[keep])
    I = np.concatenate(I) if I else np.zeros(0, np.int64)
    J = np.concatenate(J) if J else np.zeros(0, np.int64)
    d2 = ((x[J] - x[I]) ** 2).sum(axis=1)
    lim = eta * (r[I] + r[J]) * (1.0 + 1e-9)
    keep = d2 <= lim * lim
    return I[keep], J[keep]


def largest_cluster(n, I, J):
    parent = np.arange(n)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for i, j in zip(I.tolist(), J.tolist()):
        a, b = find(i), find(j)
        if a != b:
            parent[max(a, b)] = min(a, b)
    roots = np.array([find(i) for i in range(n)])
    labels, counts = np.unique(roots, return_counts=True)
    return roots == labels[np.argmax(counts)]
