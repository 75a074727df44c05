# pvpython check that ParaView opens a coupled run's output from one file: coupled.pvd holds the
# particles, the bonds and the FE continuum as three blocks of one multiblock data set, on one
# time base (the same times for the three), with the continuum's displacement field.
# Usage: pvpython paraview_reads_coupled.py OUTPUT_DIR N_PARTICLES N_BONDS. Exit code = result.
import sys

from paraview import servermanager
from paraview.simple import PVDReader

out, n_particles, n_bonds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
reader = PVDReader(FileName=out + "/coupled.pvd")
reader.UpdatePipeline()
times = list(reader.TimestepValues)
data = servermanager.Fetch(reader)
print("blocks", data.GetNumberOfBlocks(), "times", len(times))
failures = []
if data.GetNumberOfBlocks() != 3:
    failures.append("expected 3 blocks (particles, bonds, continuum), got %d" % data.GetNumberOfBlocks())
else:
    def leaf(block):
        # a .pvtu part may come as a composite data set: take its first piece (one rank)
        while block is not None and block.IsA("vtkCompositeDataSet"):
            block = block.GetPiece(0) if block.IsA("vtkMultiPieceDataSet") else block.GetBlock(0)
        return block
    particles, bonds, continuum = (leaf(data.GetBlock(k)) for k in range(3))
    print("particles", particles.GetNumberOfPoints(), "bonds", bonds.GetNumberOfCells(),
          "continuum cells", continuum.GetNumberOfCells())
    if particles.GetNumberOfPoints() != n_particles:
        failures.append("particles: %d points, expected %d" % (particles.GetNumberOfPoints(), n_particles))
    if bonds.GetNumberOfCells() != n_bonds:
        failures.append("bonds: %d cells, expected %d" % (bonds.GetNumberOfCells(), n_bonds))
    if continuum.GetNumberOfCells() == 0 or continuum.GetPointData().GetArray("displacement") is None:
        failures.append("continuum: no cells or no displacement array")
if len(times) < 3:
    failures.append("expected several snapshot times, got %d" % len(times))
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
