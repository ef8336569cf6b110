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


def to_float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def read_rows(path):
    """Rows of a CSV as dicts; numeric-looking fields become floats."""
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    out = []
    for r in rows:
        d = {}
        for k, v in r.items():
            x = to_float(v)
            d[k] = v if (math.isnan(x) and v.lower() != "nan") else x
        out.append(d)
    return out


def read_key_values(path):
    return {r["key"]: r["value"] for r in read_rows(path)}


def by_method(rows):
    groups = {}
    for r in rows:
        groups.setdefault(r["method"], []).append(r)
    return groups


def save(fig, path):
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    print("wrote", path)
