#!/usr/bin/env python3
"""Dam-break surge front of both methods against the measured one, in the experiment's time origin
(filled markers) and unshifted (open markers).

Usage: plot_dam_break.py FRONT_CSV PNG

FRONT_CSV is csv/front.csv written by `hydrojump compare` for a dam-break case (columns t_exp_s,
measured_x_over_L, sph_shifted_x_over_L, sph_unshifted_x_over_L, vof_shifted_x_over_L,
vof_unshifted_x_over_L); empty cells are points that method did not compare.
"""
import math
import sys

from common import METHOD_STYLE, PlotInputError, plt, read_rows, save


def front_figure(csv_path, png):
    rows = read_rows(csv_path)
    if not rows:
        print("plot_dam_break.py: no rows in %s" % csv_path, file=sys.stderr)
        return False
    t = [r["t_exp_s"] for r in rows]
    fig, ax = plt.subplots(figsize=(5.0, 3.6))
    ax.plot(t, [r["measured_x_over_L"] for r in rows], "ks", ms=4, label="Koshizuka & Oka (1996)")
    for method in ("sph", "vof"):
        style = METHOD_STYLE[method]
        for origin, fill in (("shifted", style["color"]), ("unshifted", "none")):
            values = [r["%s_%s_x_over_L" % (method, origin)] for r in rows]
            pts = [(a, b) for a, b in zip(t, values) if not math.isnan(b)]
            if not pts:
                continue
            label = "%s, %s" % (style["label"], "experiment's time origin" if origin == "shifted" else "unshifted")
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=style["color"], mfc=fill, ms=4,
                    lw=0.8, label=label)
    ax.set_xlabel("t (s, experiment)")
    ax.set_ylabel("surge front x / L")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, png)
    return True


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        return 0 if front_figure(argv[1], argv[2]) else 1
    except PlotInputError as e:
        print("plot_dam_break.py: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
