# pvpython check that ParaView reads what dembridge writes: particles as vertices and bonds as
# line cells, every named array present, one time step per snapshot. The exit code is the result.
import sys

from paraview.simple import PVDReader

out = sys.argv[1]
particles = PVDReader(FileName=out + "/particles.pvd")
particles.UpdatePipeline()
bonds = PVDReader(FileName=out + "/bonds.pvd")
bonds.UpdatePipeline()
n_particles = particles.GetDataInformation().GetNumberOfPoints()
n_bonds = bonds.GetDataInformation().GetNumberOfCells()
expected_p = {"radius", "displacement", "velocity", "angular_velocity", "force", "moment", "stress"}
expected_b = {"normal_force", "shear_force", "twisting_moment", "bending_moment", "state"}
bond_arrays = set(bonds.PointData.keys()) | set(bonds.CellData.keys())
missing = (expected_p - set(particles.PointData.keys())) | (expected_b - bond_arrays)
print("particles", n_particles, "bonds", n_bonds, "times", len(particles.TimestepValues))
if n_particles != 11 or n_bonds != 10 or missing or len(particles.TimestepValues) < 2:
    print("FAIL: expected 11 particles, 10 bonds, several times; missing arrays:", missing)
    sys.exit(1)
print("ok")
