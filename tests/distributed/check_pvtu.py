# pvpython check of the particle snapshots of a run on N MPI ranks (per-rank pieces under a .pvtu
# record) against the same run on one rank (one .vtu per snapshot): ParaView reads both series
# through their particles.pvd; at every snapshot the N-rank one lists N pieces whose point counts
# sum to the particle count (at least two of them hold some in a fresh run), and holds the same particles (matched by their id array) with the
# same positions, velocities, angular velocities and stresses to 1e-10 relative (of the largest
# value of each array), and the same integer arrays exactly. The exit code is the result.
# With N as a list (2,3: a run on 2 ranks resumed on 3) each record may have any of those counts
# of pieces; no particles_* file may lie in N_RANK_DIR that the series does not list (a resume
# removes the interrupted run's later snapshots).
# Usage: pvpython check_pvtu.py ONE_RANK_DIR N_RANK_DIR N[,N...]
import os
import sys
import xml.etree.ElementTree as ET

from paraview import servermanager
from paraview.simple import PVDReader, UpdatePipeline
from vtk.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvtu_series import merged, series  # noqa: E402

one_dir, many_dir = sys.argv[1], sys.argv[2]
n_ranks = [int(n) for n in sys.argv[3].split(",")]
tolerance = 1e-10
failures = []


def arrays(reader, time):
    UpdatePipeline(time=time, proxy=reader)
    data = merged(servermanager.Fetch(reader))
    out = {"points": vtk_to_numpy(data.GetPoints().GetData())}
    pd = data.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        out[pd.GetArrayName(k)] = vtk_to_numpy(pd.GetArray(k))
    return out


one, many = series(one_dir, "particles.pvd"), series(many_dir, "particles.pvd")
if len(one) != len(many) or len(one) < 2:
    failures.append("snapshots: %d on one rank, %d on %d" % (len(one), len(many), n_ranks))
one_reader = PVDReader(FileName=os.path.join(one_dir, "particles.pvd"))
many_reader = PVDReader(FileName=os.path.join(many_dir, "particles.pvd"))
worst = {}
listed = {"particles.pvd"}
for (t1, f1), (tn, fn) in zip(one, many):
    if not fn.endswith(".pvtu") or t1 != tn:
        failures.append("%s at t = %r: expected a .pvtu at t = %r" % (fn, tn, t1))
        continue
    pieces = [p.get("Source") for p in
              ET.parse(os.path.join(many_dir, fn)).getroot().iter("Piece")]
    counts = [int(ET.parse(os.path.join(many_dir, p)).getroot().find(".//Piece")
                  .get("NumberOfPoints")) for p in pieces]
    a, b = arrays(one_reader, t1), arrays(many_reader, tn)
    n = len(a["id"])
    listed.update([fn] + pieces)
    # (a rank may own none: an empty piece; a fresh run's particles must be split, a resumed
    # run's spread anew may all fall to one rank)
    split = sum(c > 0 for c in counts) >= 2 or len(n_ranks) > 1
    if len(pieces) not in n_ranks or sum(counts) != n or not split:
        failures.append("%s: pieces %s with %s points for %d particles" % (fn, pieces, counts, n))
        continue
    order_a, order_b = a["id"].argsort(), b["id"].argsort()
    if sorted(a) != sorted(b) or (a["id"][order_a] != b["id"][order_b]).any():
        failures.append("%s: arrays %s or ids differ from %s" % (fn, sorted(b), f1))
        continue
    for name in a:
        x, y = a[name][order_a], b[name][order_b]
        if x.dtype != y.dtype:
            failures.append("%s: %s is %s, %s on one rank" % (fn, name, y.dtype, x.dtype))
        elif x.dtype.kind in "iu":
            if (x != y).any():
                failures.append("%s: %s differs" % (fn, name))
        else:
            scale = max(abs(x).max(), 1e-300)
            worst[name] = max(worst.get(name, 0.0), abs(x - y).max() / scale)
unlisted = sorted(f for f in os.listdir(many_dir) if f.startswith("particles") and f not in listed)
if unlisted:
    failures.append("files the series does not list: %s" % unlisted)
for name, err in sorted(worst.items()):
    print("%-18s largest relative difference %.3g" % (name, err))
    if not err <= tolerance:
        failures.append("%s: %.3g relative, more than %g" % (name, err, tolerance))
print("snapshots", len(many), "ranks", n_ranks)
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
