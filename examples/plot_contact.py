#!/usr/bin/python3
"""Picture of the contact face from a solution file of examples/prism (-o file.h5).

  examples/plot_contact.py file.h5 [-o file.png]

Left: contact nodes by state (separated, sliding, sticking) with the tangential slip u_t as arrows.
Right: the normal reaction r_n (contact pressure times area) and the gap u_n."""
import argparse

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STATES = {0: ("separated (L)", "0.6"), 1: ("sliding (M1)", "tab:blue"), 2: ("weak sliding (M2)", "tab:cyan"),
          3: ("sticking (M3+)", "tab:red"), 4: ("weak sticking (M3-)", "tab:orange"), 5: ("weak (M4)", "tab:purple")}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    parser.add_argument("-o", "--output", help="PNG file (default: FILE with .png)")
    args = parser.parse_args()
    f = h5py.File(args.file, "r")
    x, u, r = f["contact/coordinates"][:], f["contact/displacement"][:], f["contact/reaction"][:]
    state = f["contact/state"][:]

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 4.2))
    for s, (label, color) in STATES.items():
        on = state == s
        if on.any():
            ax1.scatter(x[on, 0], x[on, 1], s=14, color=color, label="%s: %d" % (label, on.sum()), zorder=2)
    ax1.quiver(x[:, 0], x[:, 1], u[:, 0], u[:, 1], angles="xy", color="k", width=0.002, zorder=3)
    ax1.set_title("contact states and tangential displacement u_t")
    ax1.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    sc = ax2.scatter(x[:, 0], x[:, 1], c=r[:, 2], s=18, cmap="viridis")
    fig.colorbar(sc, ax=ax2, label="normal reaction r_n")
    gap = u[:, 2] > 1e-8 * np.abs(u).max()
    ax2.scatter(x[gap, 0], x[gap, 1], s=40, facecolors="none", edgecolors="0.4", label="u_n > 0 (lifted off)")
    ax2.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.15))
    ax2.set_title("normal reaction at the contact nodes")
    for ax in (ax1, ax2):
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.tight_layout()
    out = args.output or args.file.rsplit(".", 1)[0] + ".png"
    fig.savefig(out, dpi=110)
    print("wrote " + out)


if __name__ == "__main__":
    main()
