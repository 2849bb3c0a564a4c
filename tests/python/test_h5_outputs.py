"""sable's HDF5 outputs read back: every file has its time axis (root attribute `units`, the
`time` dataset with `units` and `timestep`, beside `step`); fix ave/cg's XDMF sidecar
references exactly the datasets, shapes and windows of its .h5 file, before and after a kill;
dump local to a .h5 file holds the rows of the same dump's text, snapshot by snapshot."""
import os
import signal
import subprocess
import time
import xml.etree.ElementTree as ET

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")

# Two grains collide head-on (x periodic: they fly on, the killed run below never ends). Every output is defined before `timestep`: the files must carry
# the time step the run uses, not the default one. The second run doubles dt.
DECK = """units si
atom_style granular
atom_modify map array
boundary p f f
newton off
communicate single vel yes
region reg block -0.005 0.005 -0.002 0.002 -0.002 0.002 units box
create_box 1 reg
neighbor 0.0002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e8
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single -0.0011 0 0 units box
create_atoms 1 single 0.0011 0 0 units box
set atom 1 diameter 0.002 density 2500 vx 1.0
set atom 2 diameter 0.0016 density 2500 vx -1.0
fix integr all nve/sphere
compute k all ke
fix at all ave/time 100 1 100 c_k hdf5 ave.h5
fix ah all ave/histo 100 1 100 -1 1 4 vx mode vector hdf5 histo.h5
compute cg all stress/cg kernel gauss 0.002 grid -0.004 0.004 3 -0.002 0.002 2 -0.002 0.002 2
fix cga all ave/cg 100 500 c_cg file cg.h5
compute pl all pair/gran/local id force
dump dt all local 10 local.txt c_pl[1] c_pl[2] c_pl[4] c_pl[5] c_pl[6] index
dump_modify dt format float %.17g
dump dh all local 10 local.h5 c_pl[1] c_pl[2] c_pl[4] c_pl[5] c_pl[6] index
timestep 1e-7
run 1000
timestep 2e-7
run {second}
"""

# Each file's records: its steps.
FILES = {"ave.h5": range(0, 2001, 100), "histo.h5": range(0, 2001, 100), "cg.h5": range(500, 2001, 500),
         "local.h5": range(0, 2001, 10)}


def run_deck(sable, work, second="1000"):
    (work / "deck.in").write_text(DECK.format(second=second))
    return subprocess.Popen([sable, "-in", "deck.in", "-log", "none", "-screen", "none"], cwd=work,
                            env={**os.environ, "OMP_NUM_THREADS": "1"})


@pytest.fixture(scope="module")
def run(sable, tmp_path_factory):
    work = tmp_path_factory.mktemp("h5_outputs")
    assert run_deck(sable, work).wait(timeout=120) == 0
    return work


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


@pytest.mark.parametrize("name", FILES)
def test_time_axis_and_units(run, name):
    with h5py.File(run / name, "r") as f:
        assert text(f.attrs["units"]) == "si"
        assert f.attrs["timestep"] == 1e-7  # the first record's dt, set after the fix's line
        t, step = f["time"], np.asarray(f["step"])
        assert text(t.attrs["units"]) == "s" and t.attrs["timestep"] == 1e-7
        assert step.tolist() == list(FILES[name])
        # dt 1e-7 for the first 1000 steps, 2e-7 after: each record's own time
        want = np.where(step <= 1000, step * 1e-7, 1e-4 + (step - 1000) * 2e-7)
        assert np.allclose(t, want, rtol=1e-12, atol=0)


def test_dump_local_h5_holds_the_text_rows(run):
    from sable_tools.readers import dump
    snaps = list(dump.local_snapshots(str(run / "local.txt")))
    with h5py.File(run / "local.h5", "r") as f:
        assert [text(c) for c in f.attrs["columns"]] == snaps[0][1]  # the ENTRIES line's words
        entries, first, count = np.asarray(f["entries"]), np.asarray(f["first"]), np.asarray(f["count"])
        assert f["step"][:].tolist() == [s for s, _, _ in snaps]
    assert entries.shape == (count.sum(), 6) and first.tolist() == np.concatenate([[0], np.cumsum(count)[:-1]]).tolist()
    for (step, names, rows), a, n in zip(snaps, first, count):
        assert len(rows) == n, step
        want = np.array(rows, dtype=float).reshape(-1, 6)  # %.17g: the same doubles
        assert np.array_equal(entries[a:a + n], want), step
    assert count.max() == 1 and count.min() == 0  # the collision, and steps without contact


def hyperslab(item):
    """(start, count) rows of a HyperSlab DataItem and its source (an HDF DataItem)."""
    sel, src = item.findall("DataItem")
    rows = np.array(sel.text.split(), dtype=int).reshape(3, -1)
    assert sel.get("Dimensions") == "3 %d" % rows.shape[1] and src.get("Format") == "HDF"
    return rows, src


def check_xdmf(work, windows_on_disk=None):
    """Every grid of cg.xdmf against cg.h5: datasets, declared shapes, the values each
    attribute selects, times; returns the number of grids."""
    root = ET.parse(work / "cg.xdmf").getroot()
    assert root.tag == "Xdmf" and root.get("Version") == "2.0"
    coll = root.find("Domain/Grid")
    assert coll.get("GridType") == "Collection" and coll.get("CollectionType") == "Temporal"
    grids = coll.findall("Grid")
    with h5py.File(work / "cg.h5", "r", swmr=True) as f:
        rows = len(f["step"])
        shape = tuple(int(v) for v in f["shape"])
        for item in root.iter("DataItem"):  # every referenced dataset exists with the declared dimensions
            if item.get("Format") != "HDF":
                continue
            fname, path = item.text.strip().split(":")
            assert fname == "cg.h5" and path.lstrip("/") in f, item.text
            dims = tuple(int(v) for v in item.get("Dimensions").split())
            d = f[path]
            assert item.get("NumberType") == "Float" and item.get("Precision") == "8" and d.dtype == np.float64
            if d.maxshape[0] is None:  # a growing dataset: the windows the sidecar lists, at most those on disk
                assert dims[1:] == d.shape[1:] and dims[0] == len(grids) <= d.shape[0]
            else:
                assert dims == d.shape, path
        assert len(grids) <= rows and (windows_on_disk is None or len(grids) == rows)
        pts = np.asarray(f["points"])
        x, y, z = (np.asarray(f[k]) for k in "xyz")
        want = np.stack(np.meshgrid(x, y, z, indexing="ij"), axis=-1).reshape(-1, 3)  # [nx][ny][nz], z fastest
        assert np.array_equal(pts, want)
        fields = [text(v) for v in f.attrs["fields"]]
        for w, g in enumerate(grids):
            assert float(g.find("Time").get("Value")) == f["time"][w]
            assert g.get("Name") == "step %d" % f["step"][w]
            topo, geo = g.find("Topology"), g.find("Geometry")
            assert topo.get("TopologyType") == "3DSMesh" and topo.get("Dimensions") == "%d %d %d" % shape
            assert geo.get("GeometryType") == "XYZ" and geo.find("DataItem").text.strip() == "cg.h5:/points"
            attrs = g.findall("Attribute")
            assert [a.get("Name") for a in attrs] == fields
            for a in attrs:
                d = f[a.get("Name")]
                ncomp = d.shape[4] if d.ndim == 5 else 1
                kind = {1: "Scalar", 3: "Vector", 6: "Matrix"}[ncomp]
                assert a.get("AttributeType") == kind and a.get("Center") == "Node"
                item = a.find("DataItem")
                assert item.get("ItemType") == "HyperSlab"
                (start, stride, count), src = hyperslab(item)
                assert start[0] == w and list(start[1:]) == [0] * (d.ndim - 1) and list(stride) == [1] * d.ndim
                assert list(count) == [1] + list(d.shape[1:])
                got = d[tuple(slice(s, s + c) for s, c in zip(start, count))]
                dims = tuple(int(v) for v in item.get("Dimensions").split())
                assert dims == shape + ((ncomp,) if ncomp > 1 else ())
                assert np.array_equal(got.reshape(dims), d[w])
    return len(grids)


def test_cg_xdmf_matches_the_h5(run):
    with h5py.File(run / "cg.h5", "r") as f:
        assert len(f["step"]) == 4 and np.asarray(f["rho"]).max() > 0
    assert check_xdmf(run, windows_on_disk=True) == 4
    assert not any(p.suffix == ".tmp" for p in run.iterdir())


def test_cg_xdmf_valid_after_a_kill(sable, tmp_path):
    """Killed mid-run (SIGKILL), the sidecar lists only windows that reached the .h5 file."""
    p = run_deck(sable, tmp_path, second="100000000")
    try:
        t0 = time.time()
        while time.time() - t0 < 90:
            assert p.poll() is None, "sable ended before the kill"
            x = tmp_path / "cg.xdmf"
            if x.exists() and x.read_text().count("<Time ") >= 7:  # three blocks: 1, 2 and 4 windows
                break
            time.sleep(0.05)
        else:
            pytest.fail("no 7 windows in cg.xdmf within 90 s")
        time.sleep(0.3)
    finally:
        p.send_signal(signal.SIGKILL)
        p.wait()
    assert check_xdmf(tmp_path) >= 7
