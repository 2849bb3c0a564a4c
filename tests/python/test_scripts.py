"""The studies' scripts over the one runner and the one set of readers: bench's run_engine and
run_drag's launch on a stand-in program (a shell script printing what sable prints)."""
import os

from sable_tools.bench import bench
from sable_tools.drag import run_drag

FAKE_SABLE = """#!/bin/sh
echo "threads $OMP_NUM_THREADS args $*"
echo "Loop time of 0.5 s on 1 process for 100 steps with 20 atoms: 4000 particle-steps/s, 3 neighbor builds"
echo "BENCH natoms 20 ke 0.5"
[ -n "$SLEEP" ] && sleep "$SLEEP"
exit ${RC:-0}
"""


def fake(tmp_path):
    exe = tmp_path / "sable"
    exe.write_text(FAKE_SABLE)
    exe.chmod(0o755)
    return str(exe)


def test_bench_run_engine(tmp_path, monkeypatch):
    exe = fake(tmp_path)
    r = bench.run_engine("sable", exe, bench.CASES[0], {"nxy": 5}, 2, str(tmp_path / "w"), 0, "final.dump")
    assert (r["rc"], r["timed_out"], r["ok"]) == (0, False, True)
    assert (r["steps"], r["atoms"], r["builds"], r["psps"]) == (100, 20, 3, 4000.0)
    assert r["bench_line"] == "natoms 20 ke 0.5"
    screen = open(tmp_path / "w" / "out.txt").read()
    assert screen.startswith("threads 2 args -in ") and "-var nxy 5 -var dumpfile final.dump -var sable 1" in screen
    assert r["wall_s"] >= 0 and r["maxrss_mb"] > 0
    monkeypatch.setenv("RC", "4")
    r = bench.run_engine("sable", exe, bench.CASES[0], {}, 1, str(tmp_path / "w"), 0, "final.dump")
    assert (r["rc"], r["ok"]) == (4, False) and "BENCH natoms 20" in r["tail"]


def test_bench_run_engine_timeout(tmp_path, monkeypatch):
    monkeypatch.setenv("SLEEP", "5")
    r = bench.run_engine("sable", fake(tmp_path), bench.CASES[0], {}, 1, str(tmp_path / "w"), 0.5, "final.dump")
    assert r["timed_out"] and r["rc"] == -9 and not r["ok"] and r["wall_s"] < 4


def test_run_drag_launch(tmp_path, monkeypatch):
    monkeypatch.setenv("RC", "2")
    rc, wall, cpu, text = run_drag.launch([fake(tmp_path), "-in", "drag.in"], str(tmp_path), "stdout.txt", 3)
    assert rc == 2 and text.startswith("threads 3 args -in drag.in\n")
    assert open(tmp_path / "stdout.txt").read() == text
    assert wall >= 0 and cpu >= 0


def test_run_drag_parse_stdout():
    text = ("SCENE d=0.0015 Ntot=5731\nBLOCK 1 F=2.5\nBLOCK 2 F=3.5\nLoop time of 1.5 s on 1 process\n"
            "Loop time of 2 s on 1 process\nRESULT F_first=1 F_stat=3\nRESULT F_first=2 F_stat=4\n")
    rec = run_drag.parse_stdout(text)
    assert rec == {"blocks": [2.5, 3.5], "loop_time_s": 3.5, "scene": {"d": 0.0015, "Ntot": 5731.0},
                   "result": {"F_first": 2.0, "F_stat": 4.0}}
    assert os.path.basename(run_drag.DECK) == "drag.in"


def test_compare_mohr_judge_gives_the_stored_table():
    # reference_runs/mohr/compare/compare.json: the values of each code and seed and the rows judged from them
    import json
    import math
    from sable_tools.mohr import compare_mohr
    from sable_tools.paths import repo_path
    rec = json.load(open(repo_path("reference_runs", "mohr", "compare", "compare.json")))
    rows, ok = compare_mohr.judge(rec["values"], rec["seeds"])
    assert [r["quantity"] for r in rows] == [r["quantity"] for r in rec["rows"]]
    for got, want in zip(rows, rec["rows"]):
        assert got["result"] == want["result"] and got["n"] == want["n"]
        for k in ("sable_mean", "sable_se", "yade_mean", "yade_se", "diff", "tolerance", "paired_diff", "paired_se"):
            assert got[k] == want[k] or (math.isnan(got[k]) and math.isnan(want[k])) or \
                abs(got[k] - want[k]) <= 1e-12 * abs(want[k]), (got["quantity"], k)
    assert ok == all(r["result"] != "FAIL" for r in rec["rows"])


def test_bench_core_probe(tmp_path):
    probe = tmp_path / "sable_core_probe"
    probe.write_text("#!/bin/sh\necho \"threads $OMP_NUM_THREADS\"\necho round_trip_us 0.09 barrier_us 0.5 region_us 1.25\n")
    assert bench.core_probe(str(tmp_path / "sable")) is None  # not executable yet
    probe.chmod(0o755)
    assert bench.core_probe(str(tmp_path / "sable")) == dict(round_trip_us=0.09, barrier_us=0.5, region_us=1.25)
    probe.write_text("#!/bin/sh\necho nothing\n")
    assert bench.core_probe(str(tmp_path / "sable")) is None


def test_compare_seeds_table_gives_the_stored_comparison():
    # reference_runs/reference/rate_pour/seeds.json: both codes' per-seed values and the rows judged
    # from them under input_scripts/compare/rate_pour.in's #@ tolerance lines
    import json
    import math
    from sable_tools import compare, compare_seeds
    from sable_tools.paths import repo_path
    rec = json.load(open(repo_path("reference_runs", "reference", "rate_pour", "seeds.json")))
    h = compare.parse_header(repo_path("input_scripts", "compare", "rate_pour.in"))
    rows, ok = compare_seeds.table(rec["values"], "liggghts", h)
    assert ok and [r["observable"] for r in rows] == [r["observable"] for r in rec["rows"]]
    for got, want in zip(rows, rec["rows"]):
        assert (got["result"], got["tolerance"], got["n"]) == (want["result"], want["tolerance"], want["n"])
        for k in ("sable_mean", "sable_sd", "liggghts_mean", "liggghts_sd", "se", "diff_over_se"):
            assert got[k] == want[k] or abs(got[k] - want[k]) <= 1e-13 * abs(want[k]), (got["observable"], k)
    # the SE of the difference by hand: sqrt(sd_s^2 / n + sd_l^2 / n)
    r0 = rows[0]
    assert r0["se"] == __import__("pytest").approx(math.sqrt(r0["sable_sd"] ** 2 / 6 + r0["liggghts_sd"] ** 2 / 6),
                                                    rel=1e-14)


def test_compare_seeds_table_one_seed_and_unmatched(tmp_path):
    from sable_tools import compare, compare_seeds
    deck = tmp_path / "d.in"
    deck.write_text("#@ tolerance a sigma 2\n#@ unjudged b not a physical quantity\n")
    h = compare.parse_header(str(deck))
    values = {"sable": {"a": [1.0], "b": [2.0, 3.0], "c": [1.0, 1.0]}, "yade": {"a": [1.5], "b": [2.0, 2.5], "c": [1.0, 1.0]}}
    rows, ok = compare_seeds.table(values, "yade", h)
    by = {r["observable"]: r for r in rows}
    assert by["a"]["result"] == "FAIL" and by["a"]["tolerance"] == "no spread (one seed)"
    assert by["b"]["result"] == "not judged" and by["c"]["result"] == "FAIL" and not ok


def test_bench_merge_results():
    old = {"info": {"date": "2026-11-01"}, "results": {"drum": {"runs": [1]}, "bed_30k": {"runs": [2]},
                                                       "other": {"runs": [3], "measured": "2026-10-01"}}}
    new = {"bed_30k": {"runs": [4]}, "shear_2d": {"runs": [5]}}
    m = bench.merge_results(old, new)
    assert list(m) == ["bed_30k", "shear_2d", "drum", "other"]  # CASES' order a, c, d, then unknown
    assert m["bed_30k"] == {"runs": [4]} and m["drum"] == {"runs": [1], "measured": "2026-11-01"}
    assert m["other"]["measured"] == "2026-10-01"
