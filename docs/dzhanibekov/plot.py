#!/usr/bin/python3
"""Plots the CSVs written by wedge-dzhanibekov: one PNG per case.

usage: /usr/bin/python3 docs/dzhanibekov/plot.py CSV_DIR PNG_DIR

Top panel: the body-frame angular velocity components over time (rad/s). Middle: their magnitudes on a
log scale (shows round-off growing and exact zeros). Bottom: relative drift of the kinetic energy and of
|L| (round-off with World's default implicit midpoint; a slow loss with --gyroscopic euler).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

AXES = "xyzw"
TITLES = {
    "4d_a": "(a) 4D cuboid (1.1, 0.3, 2.5, 0.7): xy spin 5 rad/s, perturbations 0.05 in xz, xw, yz, yw",
    "4d_b": "(b) as (a) with the perturbations removed: pure xy spin (a relative equilibrium: nothing moves)",
    "4d_c": "(c) yz spin 5 rad/s, intermediate plane of the yzw subspace; perturbations 0.05 in yw, zw",
    "4d_d": "(d) as (c), plus perturbations 0.05 out of the subspace (xy, xz, xw)",
    "4d_c_xyz": "(c') yz spin in the xyz subspace instead (perturbations 0.05 in xy, xz): stays in xyz",
    "3d_flip": "3D box (1, 2, 3): spin 5 rad/s in the intermediate plane xz, perturbations 0.005 in xy, yz",
}
FLOOR = 1e-17  # exact zeros are drawn here in the log panel


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    cols = {name: [float(r[i]) for r in data] for i, name in enumerate(header)}
    return header, cols


def label(name):  # "w03" -> "ω_xw (e03)"
    i, j = int(name[1]), int(name[2])
    return f"ω_{AXES[i]}{AXES[j]}"


def plot(csv_path, png_path, title):
    header, cols = read(csv_path)
    t = cols["time"]
    comps = [h for h in header if h.startswith("w")]
    fig, (ax, axl, ax2) = plt.subplots(3, 1, figsize=(10, 7.5), sharex=True,
                                       gridspec_kw={"height_ratios": [3, 2, 1.2]})
    for name in comps:
        ax.plot(t, cols[name], lw=0.9, label=label(name))
        axl.semilogy(t, [max(abs(v), FLOOR) for v in cols[name]], lw=0.8)
    ax.set_ylabel("body-frame ω (rad/s)")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", ncol=len(comps), fontsize=8)
    axl.set_ylabel("|ω_ij| (rad/s, log)")
    axl.set_ylim(FLOOR / 3, 30)
    axl.grid(alpha=0.3)
    axl.text(0.005, 0.03, f"exact zeros drawn at {FLOOR:g}", transform=axl.transAxes, fontsize=7)
    e0, l0 = cols["energy"][0], cols["L"][0]
    ax2.plot(t, [e / e0 - 1 for e in cols["energy"]], lw=1.0, label="E / E0 − 1")
    ax2.plot(t, [v / l0 - 1 for v in cols["L"]], lw=1.0, label="|L| / |L0| − 1")
    ax2.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2), useOffset=False)
    ax2.set_xlabel("time (s)")
    ax2.grid(alpha=0.3)
    ax2.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=80)
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        return 2
    src, dst = sys.argv[1], sys.argv[2]
    os.makedirs(dst, exist_ok=True)
    for case, title in TITLES.items():
        csv_path = os.path.join(src, case + ".csv")
        if not os.path.exists(csv_path):
            sys.stderr.write(f"plot.py: missing {csv_path}\n")
            return 1
        png = os.path.join(dst, case + ".png")
        plot(csv_path, png, title)
        print(f"{png} ({os.path.getsize(png) // 1024} KB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
