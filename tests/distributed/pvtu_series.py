# What the pvpython checks of N-rank snapshots (check_pvtu.py, check_bond_pvtu.py) share: the
# (time, file) list of a .pvd series, and a reader's output as one data set.
import os
import xml.etree.ElementTree as ET


def series(directory, name):
    """The (time, file) entries of DIRECTORY/NAME, a ParaView .pvd collection, in its order."""
    return [(float(d.get("timestep")), d.get("file"))
            for d in ET.parse(os.path.join(directory, name)).getroot().iter("DataSet")]


def merged(data):
    """One unstructured grid of a reader's output (a reader may hand the pieces over as blocks)."""
    if data.IsA("vtkMultiBlockDataSet"):
        from vtk import vtkAppendFilter
        append = vtkAppendFilter()
        for b in range(data.GetNumberOfBlocks()):
            append.AddInputData(data.GetBlock(b))
        append.Update()
        data = append.GetOutput()
    return data
