"""The readers (sable_tools.readers) on real outputs: stored runs of sable, LIGGGHTS and YADE,
and the dump, fix ave/time text and HDF5 files of a short sable run made here."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

from sable_tools.paths import repo_path
from sable_tools.readers import analyze, ave_time, dump, h5, screen, yade

DRAG = repo_path("reference_runs", "drag")
SABLE_LOG = os.path.join(DRAG, "effect_L12", "runs", "L12_E1e6_h1.5", "sable_s49979687", "log.txt")
LIGGGHTS_LOG = os.path.join(DRAG, "dense_prep", "runs", "dense_E3.68e7_hL1", "liggghts_s49979687", "stdout.txt")
YADE_STATES = repo_path("reference_runs", "reference", "mohr", "yade", "seed_15485867_yade_states.txt")
SABLE_STATES = repo_path("reference_runs", "mohr", "compare", "sable", "seed_15485867", "m_states.txt")


def test_sable_timing_block_is_the_last_runs():
    # the log's last run: "Loop time of 422.333 s on 1 process for 191550 steps with 20315 atoms: 9.21e+06 ..."
    d = screen.sable_loop(open(SABLE_LOG).read())
    assert (d["loop_s"], d["steps"], d["atoms"], d["builds"]) == (422.333, 191550, 20315, 386)
    assert d["psps_printed"] == 9.21e6
    assert d["psps"] == pytest.approx(20315 * 191550 / 422.333)
    assert d["split"] == {"pair": 74.2, "neigh": 2.6, "integrate": 8.6, "fixes": 14.6, "output": 0.0}


def test_liggghts_timing_block_and_version():
    text = open(LIGGGHTS_LOG).read()
    d = screen.liggghts_loop(text)
    last = [l for l in text.splitlines() if l.startswith("Loop time of")][-1].split()
    assert (d["loop_s"], d["procs"], d["steps"], d["atoms"]) == (float(last[3]), int(last[5]), int(last[8]),
                                                                 int(last[11].rstrip(",")))
    assert d["version"].startswith("LIGGGHTS-PUBLIC 3.8.0")
    assert set(d["split"]) == {"Pair", "Neigh", "Comm", "Outpt", "Other"}
    assert sum(d["split"].values()) == pytest.approx(100.0, abs=0.01)


def test_no_timing_block():
    assert screen.sable_loop("ERROR: deck.in:3: unknown command") == {"psps": None}
    assert screen.liggghts_loop("") == {"psps": None}


def stored_yade_screens():
    """Stored YADE references whose screen tail holds every OBSERVABLE line (the decks without avetime files)."""
    root = repo_path("reference_runs", "reference")
    for deck in sorted(os.listdir(root)):
        folder = os.path.join(root, deck, "yade")
        if os.path.exists(os.path.join(folder, "log_tail.txt")):
            rec = json.load(open(os.path.join(folder, "results.json")))
            tail = open(os.path.join(folder, "log_tail.txt")).read()
            if tail.count("OBSERVABLE") == len(rec["observables"]):
                yield pytest.param(tail, rec["observables"], id=deck)


STORED_YADE = list(stored_yade_screens())


def test_stored_yade_screens_found():
    assert len(STORED_YADE) >= 10


@pytest.mark.parametrize("tail,stored", STORED_YADE)
def test_parse_screen_gives_the_stored_observables(tail, stored):
    obs, _ = screen.parse_screen(tail)
    assert obs.keys() == stored.keys()
    for k, v in obs.items():
        assert v == stored[k] or (math.isnan(v) and math.isnan(stored[k]))


def test_parse_screen_tables_and_odd_values():
    text = ("Step Atoms v_ke c_f[1]\n0 2 1.5 1e20\n10 2 0.5 -3\nLoop time of 0.1 s\n"
            "5 5 5\nOBSERVABLE e 0.25\nOBSERVABLE bad -nan(ind)\nOBSERVABLE too many words\n")
    obs, series = screen.parse_screen(text)
    assert obs.keys() == {"e", "bad"} and obs["e"] == 0.25 and math.isnan(obs["bad"])
    assert series == {"atoms": [[0.0, 10.0], [2.0, 2.0]], "ke": [[0.0, 10.0], [1.5, 0.5]], "f[1]": [[10.0], [-3.0]]}


@pytest.mark.parametrize("path,code", [(YADE_STATES, "yade"), (SABLE_STATES, "sable")])
def test_states_files_of_both_codes(path, code):
    meta, rows = yade.read_states(path)
    lines = [l for l in open(path).read().splitlines() if l.strip()]
    assert len(rows) == len(lines) - 2
    assert list(rows[0]) == lines[1].split()
    assert [float(x) for x in lines[-1].split()] == list(rows[-1].values())
    assert int(meta["N"]) > 0
    meta_t, text = yade.read_states(path, text=True)  # as printed: the digits the tests judge
    assert meta_t == meta and list(text[-1].values()) == lines[-1].split()


DECK = """units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e8
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-7
create_atoms 1 single -0.0011 0 0 units box
create_atoms 1 single 0.0011 0 0 units box
set atom 1 diameter 0.002 density 2500 vx 1.0
set atom 2 diameter 0.0016 density 2500 vx -1.0
fix integr all nve/sphere
compute k all ke
variable x1 equal x[1]
fix at all ave/time 500 1 500 c_k v_x1 file ave.txt hdf5 ave.h5
dump d all custom 1000 out.dump id type radius x y z
compute cg all stress/cg kernel gauss 0.002 grid -0.004 0.004 3 -0.002 0.002 2 -0.002 0.002 2
fix cga all ave/cg 100 1000 c_cg file cg.h5
thermo_style custom step atoms ke
thermo 1000
run 3000
print "OBSERVABLE x1 ${x1}"
"""


@pytest.fixture(scope="module")
def run(sable, tmp_path_factory):
    """A head-on collision of two spheres (3000 steps), run once for the tests below."""
    work = tmp_path_factory.mktemp("readers")
    (work / "deck.in").write_text(DECK)
    p = subprocess.run([sable, "-in", "deck.in", "-log", "none"], cwd=work, capture_output=True, text=True,
                       env={**os.environ, "OMP_NUM_THREADS": "1"}, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    return work, p.stdout


def test_dump_last_snapshot(run):
    work, text = run
    atoms, box, periodic = dump.read_last_dump(str(work / "out.dump"))
    order = np.argsort(atoms["id"])
    assert atoms["id"][order].tolist() == [1.0, 2.0]
    assert atoms["radius"][order].tolist() == [0.001, 0.0008]
    assert box.tolist() == [[-0.01, 0.01]] * 3 and periodic == [False] * 3
    obs, _ = screen.parse_screen(text)
    assert atoms["x"][order][0] == pytest.approx(obs["x1"], rel=1e-5)  # step 3000 in both


def test_screen_thermo_of_the_run(run):
    _, text = run
    _, series = screen.parse_screen(text)
    assert series["atoms"] == [[0.0, 1000.0, 2000.0, 3000.0], [2.0] * 4]
    assert screen.sable_loop(text)["steps"] == 3000


def test_ave_time_text_and_hdf5_agree(run):
    work, _ = run
    obs, series = ave_time.ave_time_file(str(work / "ave.txt"), "at")
    assert (obs["at_rows"], obs["at_first_step"], obs["at_last_step"]) == (7.0, 0.0, 3000.0)  # steps 0, 500, ...
    cols, values, steps = h5.read_series(str(work / "ave.h5"))
    assert cols == ["c_k", "v_x1"]
    assert steps.tolist() == series["at_k"][0]
    assert values[:, 0].tolist() == pytest.approx(series["at_k"][1], rel=1e-6)
    assert values[:, 1].tolist() == pytest.approx(series["at_x1"][1], rel=1e-6)
    assert values[-1, 1] == pytest.approx(obs["at_x1"], rel=1e-6)


def test_key_lines_of_a_stored_run():
    # "SCENE d=0.0015 E=3.68e7 Wd=20 Ld=8 Dd=2 zc=0.012 h=0.012 dt=5.22056904202558e-06 ... Ntot=5731"
    scene = screen.key_lines(open(LIGGGHTS_LOG).read(), "SCENE")
    assert len(scene) == 1
    assert (scene[0]["d"], scene[0]["E"], scene[0]["dt"], scene[0]["Ntot"]) == ("0.0015", "3.68e7",
                                                                               "5.22056904202558e-06", "5731")


def test_key_lines_order_and_odd_words():
    text = "RESULT a=1 b=x=2\nRESULTS c=3\nnote RESULT d=4\nRESULT e=5 loose\n"
    assert screen.key_lines(text, "RESULT") == [{"a": "1", "b": "x=2"}, {"e": "5"}]


def test_ave_time_rows_of_a_stored_torque_file():
    # "# TimeStep f_cyl[6]" then "195381 -0.000955777", "199212 -0.0013807", ...
    path = os.path.join(os.path.dirname(SABLE_LOG), "drag_torque.txt")
    cols, rows = ave_time.read_rows(path)
    lines = [l for l in open(path).read().splitlines() if l.strip()]
    assert cols == ["f_cyl[6]"] and rows.shape == (len(lines) - 2, 2)
    assert rows[:2].tolist() == [[195381.0, -0.000955777], [199212.0, -0.0013807]]


def test_sable_analyze_csv_rows_and_columns():
    # sable-analyze mohr-cycles' output: '#' metadata lines, then cycle,n,mu_M,... rows
    path = os.path.join(os.path.dirname(SABLE_STATES), "mohr_cycles.csv")
    rows, cols = analyze.rows(path), analyze.columns(path)
    body = [l for l in open(path).read().splitlines() if l and not l.startswith("#")]
    assert list(rows[0]) == list(cols) == body[0].split(",")
    assert len(rows) == len(body) - 1
    for name, values in cols.items():
        assert [float(r[name]) for r in rows] == values.tolist()


def test_tagged_numbered_and_loop_times():
    text = ("BENCH natoms 300 ke 4.5e-06 ztop 0.0094\nBENCHMARK x\nBLOCK 1 F=2.5\nBLOCK 2 F=3.0 n=4\n"
            "BLOCK x F=9\nHALF 3 F=-1e-3\nLoop time of 1.5 s on 1 process for 10 steps with 2 atoms: 13 "
            "particle-steps/s, 0 neighbor builds\nLoop time of 0.25 on 1 procs for 5 steps with 2 atoms\n"
            "BENCH natoms 2\n")
    assert screen.tagged(text, "BENCH") == ["natoms 300 ke 4.5e-06 ztop 0.0094", "natoms 2"]
    assert screen.numbered(text, "BLOCK") == [(1, {"F": "2.5"}), (2, {"F": "3.0", "n": "4"})]
    assert screen.numbered(text, "HALF") == [(3, {"F": "-1e-3"})]
    assert screen.loop_times(text) == [1.5, 0.25]
    assert screen.loop_times("no run") == []


def test_loop_times_of_a_stored_log():
    # the drag log's runs: settling, fill, the rotation; the last is the timing block's
    text = open(SABLE_LOG).read()
    times = screen.loop_times(text)
    assert len(times) == text.count("\nLoop time of") and times[-1] == 422.333


def test_cg_windows_of_the_run(run):
    import h5py
    work, _ = run
    path = str(work / "cg.h5")
    with h5py.File(path, "r") as f:  # the file as written: 3 windows of 10 samples
        raw = {k: np.asarray(f[k]) for k in ("step", "samples", "rho")}
    assert raw["step"].tolist() == [1000, 2000, 3000] and raw["samples"].tolist() == [10, 10, 10]
    assert raw["rho"].max() > 0
    d = h5.cg_windows(path)
    assert {"rho", "stress", "x", "y", "z", "step", "frame", "support"} <= set(d)
    assert all(isinstance(k, str) for k in d) and isinstance(d["frame"], str)
    assert (len(d["x"]), len(d["y"]), len(d["z"])) == (3, 2, 2) and d["stress"].shape == (3, 2, 2, 6)
    w = raw["samples"]
    assert d["rho"] == pytest.approx(np.tensordot(w, raw["rho"], axes=1) / w.sum(), rel=1e-12)
    last = h5.cg_windows(path, slice(-1, None))
    assert last["step"].tolist() == [3000] and last["rho"] == pytest.approx(raw["rho"][-1], rel=1e-12)
    with pytest.raises(SystemExit):
        h5.cg_windows(path, slice(5, None))


def test_analyze_one_row_repeated_names(tmp_path):
    # sable-analyze ks: '# ' metadata, then one row whose header names n twice (one per sample)
    p = tmp_path / "ks.csv"
    p.write_text("# source: a.csv b.csv\nd,p,n,n,critical\n0.25,0.5,40,60,0.2776\n")
    assert analyze.one_row(str(p)) == {"d": 0.25, "p": 0.5, "n": 40.0, "n_2": 60.0, "critical": 0.2776}


def test_analyze_table_csv(tmp_path):
    p = tmp_path / "curve.csv"
    p.write_text("# source: f.csv\n# gaussian_limit: 1\n# note: a: b\nx,pdf,fit\n0.5,0,0.1\n1.5,2.25,2\n\n")
    t = analyze.table(str(p))
    assert t.meta == {"source": "f.csv", "gaussian_limit": "1", "note": "a: b"}
    assert dict(t) == {"x": [0.5, 1.5], "pdf": [0.0, 2.25], "fit": [0.1, 2.0]}
    analyze.need(t, str(p), "x", "pdf")
    with pytest.raises(SystemExit, match="no column 'eq7'"):
        analyze.need(t, str(p), "x", "eq7")
    (tmp_path / "empty.csv").write_text("# source: f.csv\n")
    with pytest.raises(SystemExit, match="no header line"):
        analyze.table(str(tmp_path / "empty.csv"))


def test_analyze_table_hdf5(tmp_path):
    # sable-analyze's HDF5 layout: one 1-D dataset per column, the root attribute columns, metadata as attributes
    import h5py
    p = str(tmp_path / "curve.h5")
    with h5py.File(p, "w") as f:
        f.attrs["columns"] = np.array(["x", "pdf"], dtype=h5py.string_dtype())
        f.attrs["source"] = np.array([b"f.csv"])
        f["x"], f["pdf"], f["other"] = np.array([0.5, 1.5]), np.array([0.0, 2.25]), np.array([9.0])
    t = analyze.table(p)
    assert t.meta == {"columns": ["x", "pdf"], "source": "f.csv"}
    assert list(t) == ["x", "pdf"] and t["pdf"].tolist() == [0.0, 2.25]


LOCAL = """ITEM: TIMESTEP
100
ITEM: NUMBER OF ENTRIES
2
ITEM: BOX BOUNDS pp ff pp
0 1
0 1
-1 1
ITEM: ENTRIES c_f[1] c_f[2] c_f[3]
1 2 0.5
1 3 -0.25
ITEM: TIMESTEP
200
ITEM: NUMBER OF ENTRIES
1
ITEM: BOX BOUNDS pp ff pp
0 1
0 1
-1 1
ITEM: ENTRIES c_f[1] c_f[2] c_f[3]
2 3 1.5e-3

"""


@pytest.mark.parametrize("gz", [False, True])
def test_dump_local_snapshots_and_column(tmp_path, gz):
    import gzip
    path = str(tmp_path / ("c.txt.gz" if gz else "c.txt"))
    with (gzip.open(path, "wt") if gz else open(path, "w")) as f:
        f.write(LOCAL)
    snaps = list(dump.local_snapshots(path))
    names = ["c_f[1]", "c_f[2]", "c_f[3]"]
    assert snaps == [(100, names, [["1", "2", "0.5"], ["1", "3", "-0.25"]]), (200, names, [["2", "3", "1.5e-3"]])]
    assert dump.local_column(path, 2).tolist() == [0.5, -0.25, 1.5e-3]
    assert dump.local_column(path, 2, first=101).tolist() == [1.5e-3]
    assert dump.local_column(path, 0, first=300).tolist() == []


def test_dump_local_of_a_stored_peak():
    # mohr.in's peak contacts (dump local, gzipped): "ITEM: ENTRIES c_fab[1] ... c_fab[5]", then "484 494 -0.728812 ..."
    path = repo_path("reference_runs", "mohr", "sweep", "clumps", "runs", "mu0.1_rot1_d0.5_cundall_N400_c15_beta0.25",
                     "s15485867", "mohr_peak_c1.txt.gz")
    (step, names, rows), = dump.local_snapshots(path)
    import gzip
    lines = gzip.open(path, "rt").read().splitlines()
    assert step == int(lines[1]) and len(rows) == int(lines[3])
    assert names == [f"c_fab[{k}]" for k in range(1, 6)] and rows[0] == lines[9].split()
    assert dump.local_column(path, 2)[0] == float(lines[9].split()[2])


def test_numeric_keys_last_wins_numbers_only():
    text = "RESULT F=1.5 name=abc n=3\nRESULTX F=9\nRESULT F=2.5 e=nan\nother RESULT F=7\n"
    got = screen.numeric_keys(text, "RESULT")
    assert set(got) == {"F", "n", "e"} and (got["F"], got["n"]) == (2.5, 3.0) and math.isnan(got["e"])
    assert screen.numeric_keys(text, "CAVITY") == {}


VTK_POINTS = """# vtk DataFile Version 2.0
LIGGGHTS mesh/VTK export
ASCII
DATASET POLYDATA
POINTS 4 float
0 0 0.5 1 0 0.25
0 1 0 1
1 -2e-3
POLYGONS 1 5
4 0 1 2 3
CELL_DATA 3
FIELD FieldData 2
wear 1 3 float
0.5 0.25 1e-3
area 1 3 float
1 1 1
"""

SABLE_SCALARS = """CELL_DATA 2
SCALARS wear float 1
LOOKUP_TABLE default
2.5 -1
SCALARS wearx float 1
LOOKUP_TABLE default
7 7
"""


def test_vtk_points_and_fields(tmp_path):
    from sable_tools.readers import vtk
    p = tmp_path / "m.vtk"
    p.write_text(VTK_POINTS)
    assert vtk.points(str(p)).tolist() == [[0, 0, 0.5], [1, 0, 0.25], [0, 1, 0], [1, 1, -2e-3]]
    assert vtk.field(VTK_POINTS, "wear") == [0.5, 0.25, 1e-3]   # LIGGGHTS' FIELD array
    assert vtk.field(SABLE_SCALARS, "wear") == [2.5, -1.0]      # sable's SCALARS, not wearx
    assert vtk.field(VTK_POINTS, "missing") is None


def test_multisphere_scan_final_zcm():
    from sable_tools.tutorials.multisphere_scan import final_zcm
    liggghts = ("Step Atoms KinEng c_tut_z \n       0        0            0            0 \n"
                "   40000       50 1.2e-06 0.0123 \nLoop time of 1 on 1 procs for 40000 steps with 50 atoms\n")
    assert final_zcm(liggghts) == 0.0123
    assert math.isnan(final_zcm(liggghts.replace("      50 ", "      49 ")))  # not all inserted
    assert math.isnan(final_zcm("ERROR: no deck"))


def test_error_lines():
    text = ("ERROR\nERROR: deck.in:3: unknown command 'foo'\nWARNING: ERROR in a warning\n"
            "Traceback (most recent call last):\nRuntimeError: compute sl: hi is not above lo\n"
            "ERROR on proc 0: Cannot open file x (../input.cpp:12)\n")
    assert screen.error_lines(text) == ["ERROR: deck.in:3: unknown command 'foo'",
                                        "RuntimeError: compute sl: hi is not above lo",
                                        "ERROR on proc 0: Cannot open file x (../input.cpp:12)"]
    assert screen.error_lines("all fine\n") == []


def test_merged_keys_and_a_conflict():
    text = "RESULT a=1 b=x\nnoise RESULT c=3\nRESULT a=1 c=2.5\nRESULTS d=4\n"
    assert screen.merged_keys(text, "RESULT") == {"a": "1", "b": "x", "c": "2.5"}
    with pytest.raises(ValueError, match="'a' printed twice"):
        screen.merged_keys("RESULT a=1\nRESULT a=2\n", "RESULT")


def test_loop_times_of_both_codes():
    text = ("Loop time of 0.25 s on 1 process for 10 steps with 2 atoms: 80 particle-steps/s, 1 neighbor builds\n"
            "Loop time of 1.5 on 1 procs for 100 steps with 2 atoms\nLoop time of ? s\n")
    assert screen.loop_times(text) == [0.25, 1.5]


def test_sable_loop_reads_the_lammps_wording_and_the_old_line():
    new = ("Loop time of 0.5 on 1 procs for 100 steps with 20 atoms\nPerformance: 4000 particle-steps/s, 3 neighbor "
           "builds\nTime split: pair 50.0%, neigh 10.0%, integrate 20.0%, fixes 20.0%, output 0.0%\n")
    old = "Loop time of 0.5 s on 1 process for 100 steps with 20 atoms: 4000 particle-steps/s, 3 neighbor builds\n"
    for text in (new, old):
        d = screen.sable_loop(text)
        assert (d["loop_s"], d["steps"], d["atoms"], d["psps_printed"], d["builds"]) == (0.5, 100, 20, 4000.0, 3)
    # a LIGGGHTS block (no Performance line of sable's) is not taken for sable's
    assert screen.sable_loop("Loop time of 0.5 on 1 procs for 100 steps with 20 atoms\n\nPair  time (%) = 1") == \
        {"psps": None}


def test_parse_screen_keeps_keywords_for_lammps_header_words():
    text = "   Step  Atoms  KinEng  Volume  v_KinEng\n 0 2 1.5 8 3\n10 2 0.5 8 1\nLoop time of 0.1 on 1 procs\n"
    _, series = screen.parse_screen(text)
    assert set(series) == {"atoms", "ke", "vol", "kineng"}  # v_KinEng: a variable's own name, kept
    assert series["ke"] == [[0.0, 10.0], [1.5, 0.5]]
