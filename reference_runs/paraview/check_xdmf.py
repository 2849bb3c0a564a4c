"""fix ave/cg's XDMF sidecar opened by ParaView's own reader, checked against the HDF5 file.

Run with ParaView's Python (Debian: `apt-get install paraview python3-paraview`; not part
of CI, which does not install ParaView):

    pvpython --force-offscreen-rendering reference_runs/paraview/check_xdmf.py WORK/cg.xdmf

WORK holds a run of tests/python/test_h5_outputs.py's deck (cg.h5 and cg.xdmf). For every
time step ParaView lists, the grid's points must be the file's `points` and every array the
window's values in the file, bit for bit (x, y, z as the file orders its nodes: z fastest).
Exit status 1 on the first difference.
"""
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import XDMFReader

xdmf = sys.argv[1]
h5 = xdmf[: -len(".xdmf")] + ".h5"
reader = XDMFReader(FileNames=[xdmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues)
with h5py.File(h5, "r") as f:
    assert len(times) == f["time"].shape[0], (len(times), f["time"].shape)
    points = f["points"][()]
    for w, t in enumerate(times):
        assert t == f["time"][w], (t, f["time"][w])
        reader.UpdatePipeline(t)
        grid = servermanager.Fetch(reader)
        got = np.array([grid.GetPoints().GetPoint(i) for i in range(grid.GetNumberOfPoints())])
        assert np.array_equal(got, points), "points differ"
        pd = grid.GetPointData()
        names = [pd.GetArray(k).GetName() for k in range(pd.GetNumberOfArrays())]
        for name in names:
            a = pd.GetArray(name)
            got = np.array([a.GetTuple(i) for i in range(a.GetNumberOfTuples())])
            want = f[name][w].reshape(len(points), -1)
            if not np.array_equal(got, want):
                print(f"window {w} (t = {t}): {name} differs"), sys.exit(1)
        print(f"window {w}: t = {t:.6g} s, {grid.GetClassName()} of {len(points)} nodes, arrays "
              + ", ".join(f"{n} ({pd.GetArray(n).GetNumberOfComponents()})" for n in names) + ": equal to the h5")
print(f"ParaView's XDMF reader: {len(times)} windows of {xdmf}, every point and array as in {h5}")
