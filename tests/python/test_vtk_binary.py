"""dump custom/vtk with `dump_modify ID binary yes`: the XML files (.vtu, .vtp, the pieces of .pvtu
and .pvtp) with their arrays appended raw, the legacy .vtk BINARY. Read back by sable_tools'
own reader and by VTK's, they hold the same arrays as the ASCII files of the same run (which
print 12 significant digits) and the exact doubles of a dump custom printed with %.17g."""
import os
import subprocess

import numpy as np
import pytest

from sable_tools.readers import vtk as vtkr

COLUMNS = "id type radius mass x y z vx vy vz fx fy fz omegax omegay omegaz"
FORMATS = ["vtk", "vtu", "vtp", "pvtu", "pvtp"]

# Grains rain on a floor (hertz, tangential history): after 3000 steps they touch it and each
# other, so forces and spins are non-zero and unround.
DECK = """units si
atom_style granular
boundary f f f
region box block -0.006 0.006 -0.006 0.006 0 0.016 units box
create_box 1 box
neighbor 0.0004 bin
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 5e-6
lattice sc 0.0021
region fill cylinder z 0 0 0.004 0.0012 0.006 units box
create_atoms 1 region fill
set group all diameter 0.002 density 2500
variable vz atom -0.3+0.05*sin(id*1.3)
variable vx atom 0.05*cos(id*0.7)
set group all vz v_vz vx v_vx
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
dump t all custom 3000 full.txt {cols}
dump_modify t sort id format float %.17g
{vtk}
run 3000
"""


def vtk_dumps():
    lines = []
    for k, ext in enumerate(FORMATS):
        for mode in ("ascii", "binary"):
            name = f"{mode[0]}{k}"
            lines.append(f"dump {name} all custom/vtk 3000 {mode}_{ext}*.{ext} {COLUMNS}")
            lines.append(f"dump_modify {name} sort id binary {'yes' if mode == 'binary' else 'no'}")
    return "\n".join(lines)


@pytest.fixture(scope="module")
def run(sable, tmp_path_factory):
    work = tmp_path_factory.mktemp("vtk_binary")
    (work / "deck.in").write_text(DECK.format(cols=COLUMNS, vtk=vtk_dumps()))
    p = subprocess.run([sable, "-in", "deck.in", "-log", "none"], cwd=work, capture_output=True, text=True,
                       env={**os.environ, "OMP_NUM_THREADS": "1"}, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    return work


def snapshot_file(work, mode, ext):
    """The step-3000 snapshot's data file (a parallel wrapper's piece)."""
    base = work / f"{mode}_{ext}3000.{ext}"
    return work / f"{mode}_{ext}3000_0.{ext[1:]}" if ext.startswith("p") else base


def read(work, mode, ext):
    path = snapshot_file(work, mode, ext)
    return vtkr.legacy_arrays(path) if ext == "vtk" else vtkr.xml_arrays(path)


def full_dump(work):
    """The last snapshot of the %.17g dump custom: {column: values} in id order."""
    lines = (work / "full.txt").read_text().splitlines()
    start = max(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    names = lines[start].split()[2:]
    rows = np.array([[float(x) for x in line.split()] for line in lines[start + 1:]])
    return {name: rows[:, k] for k, name in enumerate(names)}


@pytest.mark.parametrize("ext", FORMATS)
def test_binary_file_is_binary(run, ext):
    raw = snapshot_file(run, "binary", ext).read_bytes()
    if ext == "vtk":
        assert raw.split(b"\n")[2] == b"BINARY"
    else:
        assert b'format="appended"' in raw and b'<AppendedData encoding="raw">' in raw
        assert b'format="ascii"' not in raw and b'header_type="UInt64"' in raw
    text = snapshot_file(run, "ascii", ext).read_bytes()
    assert b"BINARY" not in text and b"appended" not in text


@pytest.mark.parametrize("ext", FORMATS)
def test_binary_holds_the_ascii_values(run, ext):
    a, b = read(run, "ascii", ext), read(run, "binary", ext)
    assert sorted(a) == sorted(b)
    n = len(a["Points"])
    assert n > 10 and a["Points"].shape == (n, 3)
    for name in a:
        assert a[name].shape == b[name].shape, name
        assert a[name].dtype.kind == b[name].dtype.kind, name
        if b[name].dtype.kind == "f":  # ASCII prints %.12g of the same double
            printed = np.vectorize(lambda x: float("%.12g" % x))(b[name])
            assert np.array_equal(a[name], printed), name
        else:
            assert np.array_equal(a[name], b[name]), name


@pytest.mark.parametrize("ext", FORMATS)
def test_binary_values_are_the_dumps_doubles(run, ext):
    b, full = read(run, "binary", ext), full_dump(run)
    assert np.array_equal(b["Points"], np.column_stack([full["x"], full["y"], full["z"]]))
    for vec in ("v", "f", "omega"):
        comps = [vec + c for c in "xyz"] if vec != "v" else ["vx", "vy", "vz"]
        assert np.array_equal(b[vec], np.column_stack([full[c] for c in comps])), vec
    for name in ("id", "type", "radius", "mass"):
        assert np.array_equal(b[name], full[name]), name
    # Not trivially zero: the grains touch and turn.
    assert np.abs(b["omega"]).max() > 0 and np.abs(b["f"]).max() > 0


def test_vtk_reads_the_binary_files(run):
    """VTK's own readers (ParaView's) give the same points and arrays from both files."""
    vtk = pytest.importorskip("vtk", reason="python3-vtk9 (.ci/install_deps.sh installs it)")
    from vtk.util.numpy_support import vtk_to_numpy
    for ext in FORMATS:
        got = {}
        for mode in ("ascii", "binary"):
            path = str(run / f"{mode}_{ext}3000.{ext}")
            r = vtk.vtkGenericDataObjectReader() if ext == "vtk" else vtk.vtkXMLGenericDataObjectReader()
            r.SetFileName(path)
            r.Update()
            o = r.GetOutput()
            pd = o.GetPointData()
            got[mode] = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}
            got[mode]["Points"] = vtk_to_numpy(o.GetPoints().GetData())
            assert o.GetNumberOfCells() == o.GetNumberOfPoints() > 10, (ext, mode)
        mine = read(run, "binary", ext)
        assert sorted(got["binary"]) == sorted(got["ascii"]) and "omega" in got["binary"]
        for name, values in got["binary"].items():
            assert np.array_equal(values, mine[name]), (ext, name)
            assert np.allclose(values, got["ascii"][name], rtol=1e-11, atol=0), (ext, name)
