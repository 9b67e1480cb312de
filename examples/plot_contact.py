#!/usr/bin/python3
"""Picture of the contact faces of a solution file (examples/contact or examples/prism, -o file.h5).

  examples/plot_contact.py file.h5 [-o file.png]

One row per contact group or pair (a pair, named slave->master, is drawn on its slave face), drawn in the
coordinates (t1, t2) of its plane (the frame the solver uses, so any plane works; for a curved obstacle or a pair, the
plane of the group's mean normal). Left: the contact nodes by state (separated, sliding, sticking), with the slip of
the nodes in contact as arrows (/contact/slip: the tangential displacement relative to the obstacle or to the master
surface; files without it: u_t in each node's own frame). Right: the contact pressure r_n / area (each node's normal
force over its tributary area). With
-load_steps, a last panel shows the contact area against the load factor."""
import argparse

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STATES = {0: ("separated (L)", "0.6"), 1: ("sliding (M1)", "tab:blue"), 2: ("weak sliding (M2)", "tab:cyan"),
          3: ("sticking (M3+)", "tab:red"), 4: ("weak sticking (M3-)", "tab:orange"), 5: ("weak (M4)", "tab:purple"),
          6: ("separated, stuck (LS)", "0.3")}


def frame(n):
    """Rows t1, t2, n of the node frame for the unit normal n, as SSStarNodeFrame computes it."""
    a = np.array([0.0, 1.0, 0.0]) if abs(n[0]) > 0.9 else np.array([1.0, 0.0, 0.0])
    t1 = a - a.dot(n) * n
    t1 /= np.linalg.norm(t1)
    return np.array([t1, np.cross(n, t1), n])


def read(name):
    f = h5py.File(name, "r")
    c = f["contact"]
    p = len(c["coordinates"])
    data = {k: c[k][:] for k in ("coordinates", "displacement", "reaction", "state")}
    data["normal"] = c["normal"][:] if "normal" in c else np.tile([0.0, 0.0, 1.0], (p, 1))
    data["area"] = c["area"][:] if "area" in c else None
    data["group"] = c["group"][:] if "group" in c else np.zeros(p, int)
    names = c["group"].attrs.get("names", b"contact") if "group" in c else b"contact"
    data["names"] = (names.decode() if isinstance(names, bytes) else str(names)).split(",")
    data["slip"] = c["slip"][:] if "slip" in c else None
    data["steps"] = {k: f["load_steps"][k][:] for k in f["load_steps"]} if "load_steps" in f else None
    return data


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    parser.add_argument("-o", "--output", help="PNG file (default: FILE with .png)")
    args = parser.parse_args()
    d = read(args.file)
    groups = sorted(set(d["group"].tolist()))
    ncols = 3 if d["steps"] is not None else 2
    fig, axes = plt.subplots(len(groups), ncols, figsize=(6.5 * ncols, 4.4 * len(groups)), squeeze=False)
    for row, g in zip(axes, groups):
        on = d["group"] == g
        n = d["normal"][on]
        mean = n.sum(axis=0)
        R = frame(mean / np.linalg.norm(mean) if np.linalg.norm(mean) > 1e-12 else n[0])
        un = (d["displacement"][on] * n).sum(axis=1)
        x, u = d["coordinates"][on] @ R.T, (d["displacement"][on] - un[:, None] * n) @ R.T
        rn = (d["reaction"][on] * n).sum(axis=1)
        if d["slip"] is not None:
            u = d["slip"][on] @ R.T
        state = d["state"][on]
        name = d["names"][g] if g < len(d["names"]) else str(g)
        for s, (label, color) in STATES.items():
            here = state == s
            if here.any():
                row[0].scatter(x[here, 0], x[here, 1], s=14, color=color, label="%s: %d" % (label, here.sum()), zorder=2)
        touching = ~np.isin(state, (0, 6))
        if touching.any() and np.abs(u[touching, :2]).max() > 0:  # (no arrows where nothing slips: a patch test)
            row[0].quiver(x[touching, 0], x[touching, 1], u[touching, 0], u[touching, 1], angles="xy", color="k", width=0.002, zorder=3)
        row[0].set_title("%s: contact states and slip" % name)
        print("drew %s: %d contact nodes" % (name, on.sum()))
        row[0].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
        pressure = rn / d["area"][on] if d["area"] is not None else rn
        sc = row[1].scatter(x[:, 0], x[:, 1], c=pressure, s=18, cmap="viridis")
        fig.colorbar(sc, ax=row[1], label="contact pressure r_n / area" if d["area"] is not None else "normal reaction r_n")
        lifted = ~touching
        if lifted.any():
            row[1].scatter(x[lifted, 0], x[lifted, 1], s=40, facecolors="none", edgecolors="0.4", label="separated")
            row[1].legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.15))
        row[1].set_title("%s: contact pressure" % name)
        for ax in row[:2]:
            ax.set_aspect("equal")
            ax.set_xlabel("t1")
            ax.set_ylabel("t2")
        if d["steps"] is not None:
            st = d["steps"]
            row[2].plot(st["factor"], st["area"], "o-")
            row[2].set_xlabel("load factor")
            row[2].set_ylabel("contact area (all groups)")
            row[2].set_title("contact area against load")
            row[2].grid(True)
    fig.tight_layout()
    out = args.output or args.file.rsplit(".", 1)[0] + ".png"
    fig.savefig(out, dpi=110)
    print("wrote " + out)


if __name__ == "__main__":
    main()
