"""The CSV outputs of sable-analyze: '#' lines of metadata, a header line, rows of numbers."""
import csv

import numpy as np


def rows(path):
    """One dict of strings per row, keyed by the header's names."""
    with open(path) as f:
        return list(csv.DictReader([l for l in f if not l.startswith('#')]))


def columns(path):
    """{column: array of floats}."""
    lines = [l.strip() for l in open(path) if l.strip() and not l.startswith('#')]
    names = lines[0].split(',')
    values = np.array([[float(v) for v in l.split(',')] for l in lines[1:]]).reshape(-1, len(names))
    return {n: values[:, k] for k, n in enumerate(names)}
