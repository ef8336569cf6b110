#!/usr/bin/env python3
"""Per-case figures of a hydrojump comparison.

Usage: plot_case.py CSV_DIR FIG_DIR

Reads CSV_DIR/{case,longitudinal,sections,profiles,metrics,eta,toe_frames}.csv and
snapshot_<method>.csv and writes FIG_DIR/surface.png, profiles.png, velocity_decay.png, eta.png,
toe_frames.png, snapshot_sph.png, snapshot_vof.png (each only when its data exist).
"""
import math
import os
import sys

import numpy as np

from common import METHOD_STYLE, PlotInputError, by_method, number, plt, read_key_values, read_rows, save
from plot_eta_bars import eta_bars


def plot_surface(csv_dir, fig_dir, case):
    lon = by_method(read_rows(os.path.join(csv_dir, "longitudinal.csv")))
    if not lon:
        return
    fig, ax = plt.subplots(figsize=(9, 3.6))
    bed_drawn = False
    toe_drawn = False
    for method, rows in lon.items():
        x = np.array([r["x_m"] for r in rows])
        eta = np.array([r["surface_mean_m"] for r in rows])
        sd = np.array([r["surface_std_m"] for r in rows])
        st = METHOD_STYLE.get(method, {"color": "k", "label": method})
        ax.plot(x, eta, color=st["color"], lw=1.3, label=st["label"])
        ax.fill_between(x, eta - sd, eta + sd, color=st["color"], alpha=0.18, lw=0)
        if not bed_drawn:
            zb = np.array([r["z_bed_m"] for r in rows])
            ax.fill_between(x, zb.min() - 0.02, zb, color="0.55", lw=0, label="bed")
            bed_drawn = True
        toe = number(case, method + "_toe_x_m")
        if math.isfinite(toe):
            ax.axvline(toe, color=st["color"], ls=":", lw=0.9)
            toe_drawn = True
    y1 = number(case, "inflow_depth_m")
    floor = number(case, "floor_z_m", 0.0)
    y2 = number(case, "measured_y2_m")
    if math.isfinite(floor + y1):
        ax.axhline(floor + y1, color="0.3", ls="--", lw=0.8, label="experiment y1")
    if math.isfinite(floor + y2):
        ax.axhline(floor + y2, color="0.1", ls="-.", lw=0.8, label="experiment y2")
    for x in (number(case, "basin_start_m"), number(case, "basin_end_m")):
        if math.isfinite(x):
            ax.axvline(x, color="0.6", lw=0.6)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("elevation z (m)")
    ax.set_title("Case %s: time-mean free surface (band: ±1 std%s)"
                 % (case.get("case", ""), "; dotted: toe" if toe_drawn else ""))
    ax.legend(fontsize=7, ncol=3, loc="upper left")
    ax.grid(alpha=0.3)
    save(fig, os.path.join(fig_dir, "surface.png"))


def plot_toe_frames(csv_dir, fig_dir, case):
    """Each frame's toe against time per method, with the corrugated reach's start (a toe upstream of it
    has left the reach) and the time-mean surface's toe."""
    toes = by_method(read_rows(os.path.join(csv_dir, "toe_frames.csv")))
    if not toes:
        return
    fig, ax = plt.subplots(figsize=(7, 3.2))
    for method, rows in toes.items():
        t = np.array([r["time_s"] for r in rows], dtype=float)
        x = np.array([r["toe_x_m"] for r in rows], dtype=float)
        st = METHOD_STYLE.get(method, {"color": "k", "label": method})
        ax.plot(t, x, "o-", color=st["color"], ms=2.5, lw=0.9, label=st["label"] + ": each frame")
        toe = number(case, method + "_toe_x_m")
        if math.isfinite(toe):
            ax.axhline(toe, color=st["color"], ls=":", lw=0.9, label=st["label"] + ": time-mean surface")
    start = number(case, "basin_start_m")
    if math.isfinite(start):
        ax.axhline(start, color="0.4", ls="--", lw=0.8, label="basin (reach) start")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("toe x (m)")
    ax.set_title("Case %s: the toe of each frame over the window" % case.get("case", ""))
    ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)
    save(fig, os.path.join(fig_dir, "toe_frames.png"))


def plot_profiles(csv_dir, fig_dir, case):
    rows = read_rows(os.path.join(csv_dir, "profiles.csv"))
    if not rows:
        return
    sections = []
    for r in rows:
        if r["section"] not in [s[0] for s in sections]:
            sections.append((r["section"], r["x_m"]))
    n = len(sections)
    fig, axes = plt.subplots(1, n, figsize=(2.2 * n + 1, 3.6), sharey=False, squeeze=False)
    for ax, (name, x) in zip(axes[0], sections):
        for method, mrows in by_method([r for r in rows if r["section"] == name]).items():
            st = METHOD_STYLE.get(method, {"color": "k", "label": method})
            wet = [r for r in mrows if r["wet_fraction"] >= 0.5]
            if not wet:
                continue
            z = np.array([r["z_m"] for r in wet])
            u = np.array([r["u_mean_m_s"] for r in wet])
            sd = np.array([r["u_std_m_s"] for r in wet])
            ax.plot(u, z, color=st["color"], lw=1.2, label=st["label"])
            ax.fill_betweenx(z, u - sd, u + sd, color=st["color"], alpha=0.15, lw=0)
        ax.axvline(0.0, color="0.5", lw=0.6)
        ax.set_title("%s\nx = %.3f m" % (name, x), fontsize=8)
        ax.set_xlabel("u (m/s)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("z (m)")
    axes[0][0].legend(fontsize=6)
    fig.suptitle("Case %s: time-mean velocity profiles" % case.get("case", ""), fontsize=10)
    fig.tight_layout()
    save(fig, os.path.join(fig_dir, "profiles.png"))


def wavelength_mean(v, n):
    """Centred running mean over n samples (one bed wavelength), NaN-aware, same length."""
    out = np.full(len(v), np.nan)
    h = n // 2
    for i in range(len(v)):
        w = v[max(0, i - h): i + h + 1]
        w = w[np.isfinite(w)]
        if len(w):
            out[i] = w.mean()
    return out


def plot_decay(csv_dir, fig_dir, case):
    lon = by_method(read_rows(os.path.join(csv_dir, "longitudinal.csv")))
    u1 = number(case, "inflow_velocity_m_s")
    if not lon or not math.isfinite(u1) or u1 == 0:
        return
    wavelength = number(case, "bed_wavelength_m", 0.0)
    if not math.isfinite(wavelength):
        wavelength = 0.0
    fig, ax = plt.subplots(figsize=(7, 3.6))
    plotted = False
    for method, rows in lon.items():
        toe = number(case, method + "_toe_x_m")
        if not math.isfinite(toe):
            continue
        sel = [r for r in rows if r["x_m"] >= toe]
        x = np.array([r["x_m"] - toe for r in sel])
        st = METHOD_STYLE.get(method, {"color": "k", "label": method})
        umax = np.array([r["max_velocity_mean_m_s"] for r in sel]) / u1
        ubar = np.array([r["mean_velocity_mean_m_s"] for r in sel]) / u1
        # Over corrugations the curves oscillate with the bed; also show them averaged over one wavelength.
        n = int(round(wavelength / (x[1] - x[0]))) if wavelength > 0 and len(x) > 1 else 0
        if n >= 3:
            ax.plot(x, umax, color=st["color"], lw=0.6, alpha=0.45)
            ax.plot(x, ubar, color=st["color"], lw=0.6, alpha=0.45, ls="--")
            umax, ubar = wavelength_mean(umax, n), wavelength_mean(ubar, n)
        ax.plot(x, umax, color=st["color"], lw=1.4, label=st["label"] + ": u_max/U1")
        ax.plot(x, ubar, color=st["color"], lw=1.1, ls="--", label=st["label"] + ": U/U1")
        plotted = True
    if not plotted:
        plt.close(fig)
        return
    ax.set_xlabel("distance from the toe x - x_t (m)")
    ax.set_ylabel("velocity / U1")
    title = "Case %s: velocity decay along the basin" % case.get("case", "")
    if wavelength > 0:
        title += "\n(thick: averaged over one bed wavelength %.0f mm; thin: local)" % (1000 * wavelength)
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    save(fig, os.path.join(fig_dir, "velocity_decay.png"))


def plot_snapshot(csv_dir, fig_dir, case, method):
    rows = read_rows(os.path.join(csv_dir, "snapshot_%s.csv" % method))
    if not rows:
        return
    x = np.array([r["x_m"] for r in rows])
    z = np.array([r["z_m"] for r in rows])
    xs, ix = np.unique(x, return_inverse=True)
    zs, iz = np.unique(z, return_inverse=True)
    u = np.full((len(zs), len(xs)), np.nan)
    w = np.full((len(zs), len(xs)), np.nan)
    u[iz, ix] = [r["u_m_s"] for r in rows]
    w[iz, ix] = [r["w_m_s"] for r in rows]
    speed = np.hypot(u, w)
    # Colour and arrow scale from the 99.5th percentile of the speed, so that a few spray particles
    # (single fast particles above the surface) do not wash out the flow (the colour bar extends).
    finite_speed = speed[np.isfinite(speed)]
    top = float(np.percentile(finite_speed, 99.5)) if finite_speed.size else 1.0
    top = top if top > 0.0 else 1.0
    fig, ax = plt.subplots(figsize=(10, 3.0))
    mesh = ax.pcolormesh(xs, zs, speed, shading="nearest", cmap="viridis", vmin=0.0, vmax=top)
    # sparse arrows, about 70 along the channel and 10 over the depth
    sx = max(1, len(xs) // 70)
    sz = max(1, len(zs) // 10)
    X, Z = np.meshgrid(xs[::sx], zs[::sz])
    U, W = u[::sz, ::sx], w[::sz, ::sx]
    ok = np.isfinite(U) & np.isfinite(W)
    # an arrow of the percentile speed spans 1.5 arrow spacings along x
    ax.quiver(X[ok], Z[ok], U[ok], W[ok], color="w", width=0.0012, headwidth=3, scale_units="xy",
              scale=top / (1.5 * (xs[sx] - xs[0]) if len(xs) > sx else 1.0))
    fig.colorbar(mesh, ax=ax, label="|u| (m/s)", pad=0.01, extend="max" if np.nanmax(speed) > top else "neither")
    bed = read_rows(os.path.join(csv_dir, "longitudinal.csv"))
    if bed:
        bx = np.array([r["x_m"] for r in bed if r["method"] == method])
        bz = np.array([r["z_bed_m"] for r in bed if r["method"] == method])
        if len(bx):
            ax.fill_between(bx, zs.min() - 0.01, bz, color="0.55", lw=0)
    ax.set_ylim(zs.min() - 0.005, zs.max() + 0.01)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    st = METHOD_STYLE.get(method, {"label": method})
    ax.set_title("Case %s: %s velocity field at t = %.2f s (vertical scale exaggerated)"
                 % (case.get("case", ""), st["label"], rows[0]["time_s"]), fontsize=9)
    save(fig, os.path.join(fig_dir, "snapshot_%s.png" % method))


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    csv_dir, fig_dir = argv[1], argv[2]
    if not os.path.isdir(csv_dir):
        print("plot_case.py: %s is not a directory (the csv/ of a comparison)" % csv_dir, file=sys.stderr)
        return 1
    os.makedirs(fig_dir, exist_ok=True)
    figures = [
        ("surface.png", lambda case: plot_surface(csv_dir, fig_dir, case)),
        ("profiles.png", lambda case: plot_profiles(csv_dir, fig_dir, case)),
        ("velocity_decay.png", lambda case: plot_decay(csv_dir, fig_dir, case)),
        ("eta.png", lambda case: eta_bars([os.path.join(csv_dir, "eta.csv")], os.path.join(fig_dir, "eta.png"))),
        ("toe_frames.png", lambda case: plot_toe_frames(csv_dir, fig_dir, case)),
        ("snapshot_sph.png", lambda case: plot_snapshot(csv_dir, fig_dir, case, "sph")),
        ("snapshot_vof.png", lambda case: plot_snapshot(csv_dir, fig_dir, case, "vof")),
    ]
    failed = []
    try:
        case = read_key_values(os.path.join(csv_dir, "case.csv"))
    except PlotInputError as e:  # every figure's title and marks come from it
        print("plot_case.py: %d of %d figures not made: %s" % (len(figures), len(figures), e), file=sys.stderr)
        return 1
    # One figure's bad input costs that figure only; each failure is named, and the exit status says so.
    for name, plot in figures:
        try:
            plot(case)
        except (PlotInputError, ValueError, KeyError, IndexError) as e:
            failed.append("%s (%s)" % (name, e))
    if failed:
        # One line, the last of the log: the caller quotes it.
        print("plot_case.py: %d of %d figures not made: %s" % (len(failed), len(figures), "; ".join(failed)),
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
