#!/usr/bin/python3
"""Convert a user's mesh (Abaqus .inp, VTK/VTU, Exodus, gmsh 4, ...) into the mesh the dembridge
FEM layer reads: gmsh MSH 2.2 ASCII with 8-node hexahedra and 4-node boundary quadrilaterals,
named physical groups kept as $PhysicalNames (the names case files use under
FEM/Boundary conditions and FEM/Loads).

    /usr/bin/python3 scripts/mesh_convert.py INPUT OUTPUT.msh

Cells deal.II cannot take here (tetrahedra, wedges, pyramids, second-order cells, lines,
triangles, vertices) are dropped and reported, as are cell sets that lose all their cells.
Groups come from the input's physical tags (gmsh:physical) or, failing those, from its named
cell sets (Abaqus *ELSET / *SURFACE element sets, Exodus blocks). Uses meshio (python3-meshio).
"""
import sys
from collections import Counter

import meshio
import numpy as np

KEEP = {"hexahedron": 3, "quad": 2}


def convert(source, target):
    mesh = meshio.read(source)
    report = []
    dropped = Counter()
    blocks, physical = [], []
    names = {}  # name -> [tag, dim]

    phys_in = mesh.cell_data.get("gmsh:physical")
    if phys_in is not None:
        tag_names = {int(v[0]): (k, int(v[1])) for k, v in mesh.field_data.items()}
        for block, tags in zip(mesh.cells, phys_in):
            if block.type not in KEEP:
                dropped[block.type] += len(block.data)
                continue
            blocks.append(meshio.CellBlock(block.type, block.data))
            physical.append(np.asarray(tags, dtype=int))
            for t in np.unique(tags):
                name, dim = tag_names.get(int(t), (f"group_{int(t)}", KEEP[block.type]))
                names[name] = [int(t), dim]
    else:
        # Named cell sets -> physical tags 1, 2, ...; cells in no set get tag 0 for faces (no
        # boundary name) and a "domain" volume group for hexahedra.
        sets = mesh.cell_sets or {}
        tag_of = {name: k + 1 for k, name in enumerate(sorted(sets))}
        for b, block in enumerate(mesh.cells):
            if block.type not in KEEP:
                dropped[block.type] += len(block.data)
                continue
            tags = np.zeros(len(block.data), dtype=int)
            for name, per_block in sets.items():
                idx = per_block[b] if b < len(per_block) else None
                if idx is not None and len(idx):
                    tags[np.asarray(idx, dtype=int)] = tag_of[name]
                    names[name] = [tag_of[name], KEEP[block.type]]
            if block.type == "hexahedron" and (tags == 0).any():
                volume_tag = len(tag_of) + 1
                tags[tags == 0] = volume_tag
                names["domain"] = [volume_tag, 3]
            blocks.append(meshio.CellBlock(block.type, block.data))
            physical.append(tags)
        for name in sets:
            if name not in names:
                report.append(f"cell set '{name}' dropped: none of its cells is a hexahedron or quad")

    if not any(b.type == "hexahedron" for b in blocks):
        sys.exit(f"mesh_convert: {source} has no 8-node hexahedra (found: "
                 f"{', '.join(sorted(c.type for c in mesh.cells))})")
    for cell_type, n in sorted(dropped.items()):
        report.append(f"dropped {n} {cell_type} cells")
    kept = [(b, p) for b, p in zip(blocks, physical) if b.type == "hexahedron" or (p > 0).any()]
    out = meshio.Mesh(
        mesh.points,
        [b for b, _ in kept],
        cell_data={"gmsh:physical": [p for _, p in kept], "gmsh:geometrical": [p for _, p in kept]},
        field_data={k: np.array(v) for k, v in names.items()},
    )
    meshio.write(target, out, file_format="gmsh22", binary=False)
    counts = Counter()
    for b in out.cells:
        counts[b.type] += len(b.data)
    print(f"mesh_convert: wrote {target}: {counts['hexahedron']} hexahedra, "
          f"{counts['quad']} boundary quads, groups: {', '.join(sorted(names)) or 'none'}")
    for line in report:
        print(f"mesh_convert: {line}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    convert(sys.argv[1], sys.argv[2])
