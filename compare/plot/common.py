"""Shared helpers of the hydrojump comparison plots: read the tidy CSVs written by `hydrojump compare`.

The scripts read CSV files only (never the solvers' outputs), so a figure can be restyled and redrawn
without rerunning anything.
"""
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 250  # print quality
METHOD_STYLE = {
    "sph": {"color": "#1f77b4", "label": "SPH (this study)"},
    "vof": {"color": "#d62728", "label": "VOF (OpenFOAM)"},
}


# Columns that hold ids and names: kept as text even when they look like numbers (a case "007" or
# "2_5", which Python's float() would read as 7 and 25).
TEXT_COLUMNS = frozenset({"case", "method", "section", "role", "key", "value", "quantity", "unit", "name", "status"})


class PlotInputError(Exception):
    """An input CSV that cannot make its figure: the message names the file and what it lacks."""


class Row(dict):
    """A CSV row; reading a column it lacks is a PlotInputError naming the file and the column."""

    def __init__(self, values, path):
        super().__init__(values)
        self.path = path

    def __missing__(self, key):
        raise PlotInputError("%s has no column '%s'" % (self.path, key))


def to_float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def read_rows(path):
    """Rows of a CSV (Row dicts); the fields of the numeric columns become floats (NaN when empty or
    not a number), the text columns (TEXT_COLUMNS) stay text. A missing file gives no rows."""
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    out = []
    for r in rows:
        d = {}
        for k, v in r.items():
            if k is None:  # more fields than the header names
                raise PlotInputError("%s: a row has more fields than the header" % path)
            if k in TEXT_COLUMNS:
                d[k] = "" if v is None else v
            else:
                d[k] = to_float(v)
        out.append(Row(d, path))
    return out


def read_key_values(path):
    """A key,value CSV (case.csv) as a dict of text; number() reads a value as a float."""
    return {r["key"]: r["value"] for r in read_rows(path)}


def number(mapping, key, default=math.nan):
    """mapping[key] as a float: `default` when it is missing, NaN when it is empty or not a number."""
    if key not in mapping:
        return default
    return to_float(mapping[key])


def by_method(rows):
    groups = {}
    for r in rows:
        groups.setdefault(r["method"], []).append(r)
    return groups


def save(fig, path):
    """Writes the figure to a temporary file beside `path`, then renames it: a reader never sees a
    half-written PNG, and a failed save leaves the previous figure."""
    directory, name = os.path.split(os.path.abspath(path))
    tmp = os.path.join(directory, ".%s.tmp-%d" % (name, os.getpid()))
    fmt = os.path.splitext(name)[1].lstrip(".") or "png"
    try:
        fig.savefig(tmp, dpi=DPI, bbox_inches="tight", format=fmt)
        os.replace(tmp, path)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.remove(tmp)
    print("wrote", path, flush=True)
