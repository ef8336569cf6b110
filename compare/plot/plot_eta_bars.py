#!/usr/bin/env python3
"""Energy dissipation rate bars across runs: smooth-bed theory, experiment, published SPH, this SPH,
this VOF.

Usage: plot_eta_bars.py ETA_CSV [ETA_CSV ...] --out PNG

Each ETA_CSV is a case's csv/eta.csv written by `hydrojump compare` (columns case,
smooth_theory_percent, experiment_percent, published_sph_percent, sph_percent, vof_percent, and status:
"predicted" when the run held the toe and predicted y2, "imposed" when it held the tailwater depth);
missing values are left out of the bars. This SPH and VOF bars of an imposed case are hatched, and the
title says which the cases are.
"""
import math
import os
import sys

import numpy as np

from common import METHOD_STYLE, PlotInputError, plt, read_rows, save

SERIES = [
    ("smooth_theory_percent", "smooth bed (theory)", "0.75"),
    ("experiment_percent", "experiment", "0.2"),
    ("published_sph_percent", "published SPH (Bo et al. 2019)", "#2ca02c"),
    ("sph_percent", METHOD_STYLE["sph"]["label"], METHOD_STYLE["sph"]["color"]),
    ("vof_percent", METHOD_STYLE["vof"]["label"], METHOD_STYLE["vof"]["color"]),
]


def eta_bars(files, out):
    rows = []
    for f in files:
        rows.extend(read_rows(f))
    if not rows:
        print("plot_eta_bars.py: no rows in %s" % ", ".join(files), file=sys.stderr)
        return False
    cases = [r["case"] for r in rows]
    x = np.arange(len(rows))
    width = 0.8 / len(SERIES)
    fig, ax = plt.subplots(figsize=(max(6.5, 1.3 * len(rows) + 2), 3.6))
    shown = []
    for i, (key, label, color) in enumerate(SERIES):
        vals = np.array([r.get(key, math.nan) for r in rows], dtype=float)
        ok = np.isfinite(vals)
        if not ok.any():
            continue
        shown.extend(vals[ok])
        pos = x - 0.4 + (i + 0.5) * width
        imposed = np.array([r.get("status", "") == "imposed" for r in rows]) & ok
        model = key in ("sph_percent", "vof_percent")
        ax.bar(pos[ok & ~imposed], vals[ok & ~imposed], width, color=color, label=label)
        if model and imposed.any():
            ax.bar(pos[imposed], vals[imposed], width, color=color, hatch="///", edgecolor="white",
                   label=None if (ok & ~imposed).any() else label)
        for p, v in zip(pos[ok], vals[ok]):
            ax.text(p, v + 0.5, "%.1f" % v, ha="center", va="bottom", fontsize=6, rotation=90)
    ax.set_xticks(x)
    long_labels = max(len(c) for c in cases) > 8
    ax.set_xticklabels(cases, rotation=30 if long_labels else 0, ha="right" if long_labels else "center")
    ax.set_ylabel("η = (E1 − E2)/E1 (%)")
    # 0-100 %, widened to show a value outside it (a broken run's) instead of clipping it.
    ax.set_ylim(min([0.0] + [v - 5.0 for v in shown]), max([100.0] + [v + 8.0 for v in shown]))
    statuses = {r.get("status", "") for r in rows}
    if statuses == {"predicted"}:
        kind = "predicted (toe held at the basin start, y2 free)"
    elif statuses == {"imposed"}:
        kind = "imposed by the held tailwater depth"
    else:
        kind = "hatched: imposed by a held tailwater depth"
    ax.set_title("Energy dissipation rate; this SPH and VOF: " + kind, fontsize=9)
    ax.legend(fontsize=7, loc="upper left", ncol=2)
    ax.grid(axis="y", alpha=0.3)
    save(fig, out)
    return True


def main(argv):
    args = argv[1:]
    if "--out" not in args or args.index("--out") == len(args) - 1:
        print(__doc__, file=sys.stderr)
        return 2
    i = args.index("--out")
    out = args[i + 1]
    files = args[:i] + args[i + 2:]
    missing = [f for f in files if not os.path.exists(f)]
    if missing:
        print("plot_eta_bars.py: missing input files: " + ", ".join(missing), file=sys.stderr)
        return 1
    try:
        return 0 if eta_bars(files, out) else 1
    except (PlotInputError, ValueError) as e:
        print("plot_eta_bars.py: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
