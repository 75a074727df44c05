# pvpython check of the bond snapshots of a run on N MPI ranks (per-rank pieces bonds_NNNNNN_rR.vtu
# under a .pvtu record) against the same run on one rank (one bonds_NNNNNN.vtu per snapshot):
# ParaView reads both series through their bonds.pvd; at every snapshot the N-rank one lists N
# pieces, holds every bond of the one-rank file exactly once (matched by its id cell array: no
# id twice, none missing, the pieces' cell counts summing to the bond count), each between the
# same two particles (particle_id of its points) at the same places, with the same float arrays
# (forces, moments, stresses, damage) to 1e-10 relative (of the largest value of each array over
# the run) and the same integer arrays (state: intact / softening / broken, class) exactly. It
# prints per run the bonds broken at the end, and how many bonds joined particles of two ranks
# (their ends' owners read from the particle pieces) and of those how many broke. No bonds_*
# file may lie in N_RANK_DIR that the series does not list. The exit code is the result.
# Usage: pvpython check_bond_pvtu.py ONE_RANK_DIR N_RANK_DIR N[,N...] [--min-broken-across K]
#   --min-broken-across K: fail unless at least K broken bonds joined particles of two ranks at
#   the last snapshot (the case is meant to break bonds across ranks).
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
from paraview import servermanager
from paraview.simple import PVDReader, UpdatePipeline
from vtk import vtkXMLUnstructuredGridReader
from vtk.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvtu_series import merged, series  # noqa: E402

one_dir, many_dir = sys.argv[1], sys.argv[2]
n_ranks = [int(n) for n in sys.argv[3].split(",")]
min_broken_across = int(sys.argv[sys.argv.index("--min-broken-across") + 1]) \
    if "--min-broken-across" in sys.argv else 0
tolerance = 1e-10
BROKEN = 2
failures = []


def bonds(reader, time):
    """Cell arrays, and per cell its two ends' particle ids and positions."""
    UpdatePipeline(time=time, proxy=reader)
    data = merged(servermanager.Fetch(reader))
    points = vtk_to_numpy(data.GetPoints().GetData())
    pid = vtk_to_numpy(data.GetPointData().GetArray("particle_id"))
    ends = np.array([[data.GetCell(c).GetPointId(0), data.GetCell(c).GetPointId(1)]
                     for c in range(data.GetNumberOfCells())], dtype=np.int64).reshape(-1, 2)
    out = {"ends_particle_id": pid[ends], "ends_position": points[ends].reshape(-1, 6)}
    cd = data.GetCellData()
    for k in range(cd.GetNumberOfArrays()):
        out[cd.GetArrayName(k)] = vtk_to_numpy(cd.GetArray(k))
    return out


def owners(record):
    """Particle id -> rank, from the particle pieces of the snapshot's record."""
    owner = {}
    for r, p in enumerate(ET.parse(os.path.join(many_dir, record)).getroot().iter("Piece")):
        reader = vtkXMLUnstructuredGridReader()
        reader.SetFileName(os.path.join(many_dir, p.get("Source")))
        reader.Update()
        for i in vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("id")):
            owner[int(i)] = r
    return owner


one, many = series(one_dir, "bonds.pvd"), series(many_dir, "bonds.pvd")
many_particles = dict((t, f) for t, f in series(many_dir, "particles.pvd"))
if len(one) != len(many) or len(one) < 2:
    failures.append("snapshots: %d on one rank, %d on %s" % (len(one), len(many), n_ranks))
one_reader = PVDReader(FileName=os.path.join(one_dir, "bonds.pvd"))
many_reader = PVDReader(FileName=os.path.join(many_dir, "bonds.pvd"))
diff, scale = {}, {}
listed = {"bonds.pvd"}
last = None
for (t1, f1), (tn, fn) in zip(one, many):
    if not fn.endswith(".pvtu") or t1 != tn:
        failures.append("%s at t = %r: expected a .pvtu at t = %r" % (fn, tn, t1))
        continue
    pieces = [p.get("Source") for p in
              ET.parse(os.path.join(many_dir, fn)).getroot().iter("Piece")]
    listed.update([fn] + pieces)
    missing = [p for p in pieces if not os.path.exists(os.path.join(many_dir, p))]
    if missing:
        failures.append("%s: pieces %s missing" % (fn, missing))
        continue
    counts = [int(ET.parse(os.path.join(many_dir, p)).getroot().find(".//Piece")
                  .get("NumberOfCells")) for p in pieces]
    a, b = bonds(one_reader, t1), bonds(many_reader, tn)
    n = len(a["id"])
    if len(pieces) not in n_ranks or sum(counts) != n:
        failures.append("%s: pieces %s with %s bonds for %d" % (fn, pieces, counts, n))
        continue
    ids, once = np.unique(b["id"], return_counts=True)
    if (once != 1).any() or not np.array_equal(ids, np.sort(a["id"])):
        failures.append("%s: bond ids twice %s, missing %s" % (
            fn, ids[once != 1][:5].tolist(), sorted(set(a["id"]) - set(ids))[:5]))
        continue
    if sorted(a) != sorted(b):
        failures.append("%s: arrays %s, on one rank %s" % (fn, sorted(b), sorted(a)))
        continue
    order_a, order_b = a["id"].argsort(), b["id"].argsort()
    for name in a:
        x, y = a[name][order_a], b[name][order_b]
        if x.dtype != y.dtype:
            failures.append("%s: %s is %s, %s on one rank" % (fn, name, y.dtype, x.dtype))
        elif x.dtype.kind in "iu":
            if (x != y).any():
                bad = np.nonzero((x != y).reshape(len(x), -1).any(axis=1))[0]
                failures.append("%s: %s differs at bonds %s" % (fn, name, a["id"][order_a][bad][:5]))
        else:
            diff[name] = max(diff.get(name, 0.0), abs(x - y).max(initial=0.0))
            scale[name] = max(scale.get(name, 0.0), abs(x).max(initial=0.0))
    last = (fn, tn, a["state"][order_a], a["ends_particle_id"][order_a])
unlisted = sorted(f for f in os.listdir(many_dir) if f.startswith("bonds") and f not in listed)
if unlisted:
    failures.append("files the series does not list: %s" % unlisted)
for name in sorted(diff):
    err = diff[name] / scale[name] if scale[name] > 0 else diff[name]
    print("%-18s largest difference %.3g relative (of %.3g)" % (name, err, scale[name]))
    if not err <= tolerance:
        failures.append("%s: %.3g relative, more than %g" % (name, err, tolerance))
if last:
    fn, t, state, ends = last
    owner = owners(many_particles[t])
    across = np.array([owner[int(p)] != owner[int(q)] for p, q in ends], dtype=bool)
    broken = state == BROKEN
    print("%s: %d bonds, %d broken; %d joined two ranks' particles, %d of them broken"
          % (fn, len(state), broken.sum(), across.sum(), (broken & across).sum()))
    if (broken & across).sum() < min_broken_across:
        failures.append("fewer than %d broken bonds across ranks" % min_broken_across)
print("snapshots", len(many), "ranks", n_ranks)
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
