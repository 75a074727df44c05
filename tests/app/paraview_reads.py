# pvpython check that ParaView reads what dembridge writes: particles as vertices and bonds as
# line cells, every named array present with its type (ids as 64-bit integers, group_mask as
# unsigned 32-bit, bond quantities as cell data), the group names as field data, one time step
# per snapshot. The exit code is the result.
import sys

from paraview import servermanager
from paraview.simple import PVDReader

out = sys.argv[1]
particles = PVDReader(FileName=out + "/particles.pvd")
particles.UpdatePipeline()
bonds = PVDReader(FileName=out + "/bonds.pvd")
bonds.UpdatePipeline()
n_particles = particles.GetDataInformation().GetNumberOfPoints()
n_bonds = bonds.GetDataInformation().GetNumberOfCells()
expected_p = {"radius", "displacement", "velocity", "angular_velocity", "force", "moment", "stress",
              "group_mask", "coordination", "id"}
expected_b = {"normal_force", "shear_force", "twisting_moment", "bending_moment", "force", "state",
              "tensile_stress", "shear_stress", "damage", "id"}
missing = (expected_p - set(particles.PointData.keys())) | (expected_b - set(bonds.CellData.keys()))
print("particles", n_particles, "bonds", n_bonds, "times", len(particles.TimestepValues))
failures = []
if n_particles != 11 or n_bonds != 10 or missing or len(particles.TimestepValues) < 2:
    failures.append("expected 11 particles, 10 bonds, several times; missing arrays: %s" % missing)

p = servermanager.Fetch(particles)
b = servermanager.Fetch(bonds)
types = {
    "particle id": p.GetPointData().GetArray("id").GetDataTypeAsString(),
    "group_mask": p.GetPointData().GetArray("group_mask").GetDataTypeAsString(),
    "coordination": p.GetPointData().GetArray("coordination").GetDataTypeAsString(),
    "position": p.GetPoints().GetData().GetDataTypeAsString(),
    "bond id": b.GetCellData().GetArray("id").GetDataTypeAsString(),
    "bond state": b.GetCellData().GetArray("state").GetDataTypeAsString(),
    "normal_force": b.GetCellData().GetArray("normal_force").GetDataTypeAsString(),
}
print("types", types)
want = {"particle id": ("long long", "long", "vtkIdType"), "group_mask": ("unsigned int",),
        "coordination": ("int",), "position": ("double",), "bond id": ("long long", "long"),
        "bond state": ("unsigned char",), "normal_force": ("double",)}
for key, allowed in want.items():
    if types[key] not in allowed:
        failures.append("%s is %s, expected %s" % (key, types[key], allowed))
ids = p.GetPointData().GetArray("id")
if [int(ids.GetValue(i)) for i in range(ids.GetNumberOfTuples())] != list(range(n_particles)):
    failures.append("particle ids are not 0..n-1")
names = p.GetFieldData().GetAbstractArray("group_names")
names = [names.GetValue(k) for k in range(names.GetNumberOfValues())] if names else None
print("group_names", names)
if names != ["clamp", "tip"]:
    failures.append("group_names %s, expected ['clamp', 'tip']" % names)
if b.GetCell(0).GetNumberOfPoints() != 2 or b.GetCellType(0) != 3:
    failures.append("bond cells are not lines")
if failures:
    print("FAIL: " + "; ".join(failures))
    sys.exit(1)
print("ok")
