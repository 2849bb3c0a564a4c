"""The states files that mohr.in (sable) and input_scripts/mohr/mohr_yade.py (YADE's recorder)
write: one header line of key=value settings, the column names, one row per state."""
import csv
import gzip


def read_states(path, text=False):
    """A states file of mohr.in or mohr_yade.py (plain or .gz): (the header line's key=value
    settings, the rows as dicts of floats; of strings as printed with text=True)."""
    op = gzip.open if path.endswith(".gz") else open
    with op(path, "rt") as f:
        header = f.readline()
        rows = list(csv.DictReader(f, delimiter=" "))
    meta = dict(kv.split("=", 1) for kv in header.split()[3:] if "=" in kv)
    return meta, (rows if text else [{k: float(v) for k, v in r.items()} for r in rows])
