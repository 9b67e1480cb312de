#!/usr/bin/python3
"""Picture of the contact faces of a solution file (examples/contact, examples/prism or ssstar.Scene, -o file.h5).

  examples/plot_contact.py file.h5 [-o file.png] [--history file_history.png] [--data file.json]

One row per contact group or pair (a pair, named slave->master, is drawn on its slave face), drawn to scale in the
plane of the face (the plane through its nodes: a face in a plane of global axes is drawn in those axes, x and y for a
face z = const; a tilted or curved face in axes t1, t2 of its own plane, t1 along the global axis it runs along most).
Left: the contact nodes by state (separated, sliding, sticking), with the slip of the nodes in contact as arrows
(/contact/slip: the tangential displacement relative to the obstacle or to the master surface; files without it: u_t
in each node's own frame), all on one scale: the key arrow in the legend gives a round length in the units of the
mesh, and the title the largest slip (a micro-slip of 1e-6 is drawn as long as the key says, not as a slide); no arrows
where nothing slips. Right: the contact pressure r_n / area (each node's normal force over its tributary area). With
-load_steps, a last panel shows the contact area against the load factor. Legends sit below their panels.

A load path (a file with /steps, written by examples/contact or by ssstar.Scene) gets a second figure,
FILE_history.png: its history step by step for the contact group that carries it (a moving obstacle's group, else the
one with the largest normal force), with n that group's normal (pointing into the body: the normal of its face where
the face is flat, else its nodes' normals weighted by their normal forces) and t the direction in which the tangential force varies most (a global axis where it is one):
(i) the tangential force against the tangential displacement -- the applied tangential load against the mean
displacement of the traction group that carries it (weighted like its load, so that the loop's area is the work, the
energy friction dissipates over a cycle; a file of ssstar.Scene, whose loads change between steps, takes its traction
group too), or the friction force on the body against a moving obstacle's translation -- the loop closing for a
cycle; (ii) the normal force on the group against the indentation (m - u).n: the obstacle's translation m (0 for a
fixed one) less the body's displacement u (the mean displacement of its nodes: its rigid motion where a spring or
contact alone holds it, about 0 where Dirichlet conditions do; files without the field of each step: the loaded
traction group's, else the contact group's); (iii) the contact area and the sliding nodes against the time; (iv) the loop of (i) less its linear
elastic part (the displacement less the force times the slope fitted through the loop: the bodies' compliance, which
adds no area), where the slip shows. The contact faces are drawn at the last step.

A load path with prescribed displacements (-displacement_<G>: /steps/groups/<G>/reaction) gets FILE_reaction.png, the
force-displacement picture of each prescribed group: the reaction force the prescription exerts on the body against
the group's displacement, in the prescribed component that moves most (draw_reactions()).

--data writes what was drawn (per panel: title, axis labels and limits, and the lines' and points' values) as JSON.
As a module: draw(read(file)) returns the matplotlib figure, draw_history(read(file)) the history's (or None),
draw_reactions(file) the force-displacement picture's (or None), plotted(fig) what a figure draws."""
import argparse
import json

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STATES = {0: ("separated (L)", "0.6"), 1: ("sliding (M1)", "tab:blue"), 2: ("weak sliding (M2)", "tab:cyan"),
          3: ("sticking (M3+)", "tab:red"), 4: ("weak sticking (M3-)", "tab:orange"), 5: ("weak (M4)", "tab:purple"),
          6: ("separated, stuck (LS)", "0.3")}


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
    data["path"] = read_path(f, data) if "steps" in f else None
    return data


def read_path(f, d):
    """The table /steps of a load path, with the histories of the tractions, the motions of the obstacles, and each
    step's normal force, tangential force and normal of the contact group that carries the path"""
    st = f["steps"]
    path = {k: st[k][:] for k in st if isinstance(st[k], h5py.Dataset)}
    path["groups"] = {g: st["groups"][g]["displacement"][:] for g in st["groups"] if "displacement" in st["groups"][g]} if "groups" in st else {}
    path["motion"] = {g: st["motion"][g][:] for g in st["motion"]} if "motion" in st else {}
    path["tractions"] = {}
    if "scene/traction" in f:
        for g, grp in f["scene/traction"].items():
            path["tractions"][g] = history_values(grp.attrs.get("history"), grp.attrs["traction"])
    steps = sorted((k for k in st if k.isdigit()), key=int)
    group = carrying_group(f, d, steps, path)
    path["group"], path["group_name"] = group, d["names"][group] if group < len(d["names"]) else str(group)
    on = d["group"] == group
    path["normal"] = group_normal(f, steps, on, d["normal"])
    single = len(set(d["group"].tolist())) == 1
    N, T = [], []
    for k in steps:  # the group's normal and tangential force at each step (the table's own columns for one group)
        c = f["steps/%s/contact" % k]
        r = c["reaction"][:][on]
        n = (c["normal"][:] if "normal" in c else d["normal"])[on]
        rn = (r * n).sum(axis=1)
        N.append(rn.sum())
        T.append((r - rn[:, None] * n).sum(axis=0))
    path["group_normal_force"] = path["normal_force"] if single or not steps else np.array(N)
    path["group_tangential_force"] = path["tangential_force"] if single or not steps else np.array(T)
    body = body_nodes(f, d["coordinates"][on])
    path["body_displacement"] = np.array([f["steps/%s/fields/displacement" % k][:][body].mean(axis=0) for k in steps]) \
        if body is not None and all("fields" in f["steps/%s" % k] for k in steps) else None
    return path


def body_nodes(f, points):
    """The mesh nodes of the body that holds points (contact nodes): the connected part of the mesh's tetrahedra
    through them; None without a mesh"""
    if "geometry" not in f or "viz/topology/cells" not in f:
        return None
    x, cells = f["geometry/vertices"][:], f["viz/topology/cells"][:]
    label = np.arange(len(x))
    while True:  # each node takes the least label of its cells, until nothing changes
        least = label[cells].min(axis=1)
        new = label.copy()
        np.minimum.at(new, cells.ravel(), np.repeat(least, cells.shape[1]))
        if np.array_equal(new, label):
            break
        label = new[new]
    index = {tuple(v): i for i, v in enumerate(x)}
    mine = {label[index[tuple(p)]] for p in points if tuple(p) in index}
    return np.isin(label, list(mine)) if mine else None


def carrying_group(f, d, steps, path):
    """The contact group whose history is drawn: the first with a moving obstacle, else the one with the largest normal
    force at the last step"""
    names = d["names"]
    for g, name in enumerate(names):
        if name in path["motion"]:
            return g
    groups = sorted(set(d["group"].tolist()))
    if not steps or len(groups) == 1:
        return groups[0]
    c = f["steps/%s/contact" % steps[-1]]
    rn = (c["reaction"][:] * (c["normal"][:] if "normal" in c else d["normal"])).sum(axis=1)
    return max(groups, key=lambda g: rn[d["group"] == g].sum())


def group_normal(f, steps, on, normals):
    """The normal of a contact group over a path, pointing into the body: the normal of its face where the face is flat
    (the motion of an obstacle along it is the indentation, wherever the contact drifts), else its nodes' normals
    weighted by their normal forces; the mean of its normals where nothing pushes"""
    weighted = force_weighted_normal(f, steps, on, normals)
    x = f["contact/coordinates"][:][on]
    if len(x) > 2:
        w, v = np.linalg.eigh(np.cov((x - x.mean(axis=0)).T))
        if np.sqrt(max(w[0], 0)) <= 1e-9 * np.ptp(x, axis=0).max():  # flat
            return v[:, 0] if v[:, 0] @ weighted >= 0 else -v[:, 0]
    return weighted


def force_weighted_normal(f, steps, on, normals):
    """A contact group's nodes' normals weighted by their normal forces over a path (the mean of its normals where
    nothing pushes), unit"""
    total = np.zeros(3)
    for k in steps:
        c = f["steps/%s/contact" % k]
        n = (c["normal"][:] if "normal" in c else normals)[on]
        rn = np.maximum((c["reaction"][:][on] * n).sum(axis=1), 0)
        total += (rn[:, None] * n).sum(axis=0)
    if np.linalg.norm(total) < 1e-300:
        total = normals[on].sum(axis=0)
    return total / np.linalg.norm(total) if np.linalg.norm(total) > 1e-300 else np.array([0.0, 0.0, 1.0])


def history_values(text, constant):
    """The knots' values of a history "t:x,y,z;..." as rows (a constant: one row)"""
    if text is None:
        return np.atleast_2d(constant)
    text = text.decode() if isinstance(text, bytes) else str(text)
    return np.array([[float(v) for v in knot.split(":")[1].split(",")] for knot in text.split(";")])


def direction_name(e):
    """x, y or z for a direction within 0.5 degrees of a global axis (either sign), else its components"""
    k = int(np.argmax(np.abs(e)))
    if abs(e[k]) >= np.cos(np.radians(0.5)):
        return ("-" if e[k] < 0 else "") + "xyz"[k]
    return "(%.3g, %.3g, %.3g)" % tuple(e)


def tangential_direction(forces, n):
    """The unit direction off n along which the tangential parts of forces (rows) vary most: a global axis when that
    direction is within 10 degrees of one (the force's component that carries the load), else the principal
    direction itself; its largest component positive"""
    t = forces - np.outer(forces @ n, n)
    centred = t - t.mean(axis=0) if len(t) > 1 and np.ptp(t, axis=0).max() > 0 else t
    if np.abs(centred).max() <= 0:
        return np.eye(3)[int(np.argmin(np.abs(n)))]
    e = np.linalg.svd(centred)[2][0]
    k = int(np.argmax(np.abs(e)))
    return np.eye(3)[k] if abs(e[k]) >= np.cos(np.radians(10)) else (e if e[k] > 0 else -e)


def loaded_group(path):
    """The traction group that loads the path: of those whose displacement the table follows, the one whose traction
    varies most along its history (ssstar.Scene changes loads between steps and writes the last: the largest), or None"""
    candidates = [g for g in path["tractions"] if g in path["groups"]]
    if not candidates:
        return None
    return max(candidates, key=lambda g: (np.ptp(np.linalg.norm(path["tractions"][g], axis=1)), np.abs(path["tractions"][g]).max()))


def history_series(d):
    """What the history figure draws, from the file alone: per panel the x and y values and their labels"""
    path = d["path"]
    n, group, name = path["normal"], path["group"], path["group_name"]
    moving = name in path["motion"]
    loaded = None if moving else loaded_group(path)
    steps = len(path["time"])
    load = path["load"] - np.outer(path["load"] @ n, n)
    if moving or np.abs(load).max() <= 1e-12 * max(np.abs(path["load"]).max(), 1e-300):  # no tangential load: the friction force
        force, force_what = path["group_tangential_force"], "friction force on the body at %s" % name
    else:
        force, force_what = path["load"], "applied load"
    t = tangential_direction(force, n)
    along = direction_name(t)
    series = {"normal": n, "tangential": t, "group": name, "loaded": loaded}
    if moving:
        x, x_what = path["motion"][name] @ t, "translation of the obstacle of %s along %s" % (name, along)
    elif loaded is not None:
        x, x_what = path["groups"][loaded] @ t, "mean displacement of %s along %s (weighted like its load)" % (loaded, along)
    else:
        x, x_what = path["groups"].get(name, np.zeros((steps, 3))) @ t, "mean displacement of %s along %s" % (name, along)
    series["tangential_loop"] = (x, force @ t, x_what, "%s along %s" % (force_what, along))
    # the indentation: the obstacle's translation less the body's displacement there, along n: the mean displacement of
    # the body (its rigid motion, where a spring or contact alone holds it; about 0 for a body held by Dirichlet
    # conditions), else of the loaded group or of the contact group
    motion = path["motion"][name] if moving else np.zeros((steps, 3))
    if path["body_displacement"] is not None:
        body, ref = path["body_displacement"], "the body (its nodes)"
    else:
        ref = loaded if loaded is not None else name
        body, ref = path["groups"].get(ref, np.zeros((steps, 3))), ref
    delta = (motion - body) @ n
    what = ("m the translation of the obstacle of %s, u the mean displacement of %s" % (name, ref) if moving else
            "u the mean displacement of %s (the obstacle of %s fixed)" % (ref, name))
    series["indentation"] = (delta, path["group_normal_force"], "indentation (m - u).n: %s, n = %s" % (what, direction_name(n)),
                             "normal force on %s" % name)
    return series


def draw_history(d):
    """The figure of a load path (read(); None without /steps): force against displacement, tangential and normal,
    and the contact area and sliding nodes against the time"""
    path = d["path"]
    if path is None:
        return None
    fig, grid = plt.subplots(2, 2, figsize=(13, 9.5), layout="constrained")
    axes = [grid[0, 0], grid[1, 0], grid[1, 1], grid[0, 1]]
    series = history_series(d)
    # (i) tangential force against tangential displacement
    x, y, xlabel, ylabel = series["tangential_loop"]
    axes[0].set_xlabel(xlabel)
    axes[0].set_ylabel(ylabel)
    axes[0].plot(x, y, "o-", ms=3, lw=1.2, color="tab:blue")
    axes[0].plot(x[:1], y[:1], "s", color="tab:green", label="first step")
    axes[0].plot(x[-1:], y[-1:], "D", color="tab:red", label="last step")
    axes[0].set_title("tangential force against displacement (friction dissipated %.4g in all)" % path["dissipation"][-1])
    # the same without its linear elastic part (the bodies' compliance, a straight line with no area): the hysteresis
    slope = np.polyfit(y, x, 1)[0] if np.ptp(y) > 0 else 0.0
    axes[3].plot(x - slope * y, y, "o-", ms=3, lw=1.2, color="tab:blue")
    axes[3].plot((x - slope * y)[:1], y[:1], "s", color="tab:green", label="first step")
    axes[3].plot((x - slope * y)[-1:], y[-1:], "D", color="tab:red", label="last step")
    axes[3].set_xlabel("the same displacement less %.4g times the force (its linear elastic part)" % slope)
    axes[3].set_ylabel(ylabel)
    axes[3].set_title("the loop without the elastic compliance: slip and hysteresis")
    axes[3].grid(True)
    axes[3].axhline(0, color="0.7", lw=0.8)
    axes[3].legend(fontsize=8, loc="best")
    # (ii) normal force against indentation
    delta, N, xlabel, ylabel = series["indentation"]
    axes[1].plot(delta, N, "o-", ms=3, lw=1.2, color="tab:purple")
    axes[1].set_xlabel(xlabel)
    axes[1].set_ylabel(ylabel)
    axes[1].set_title("normal force against indentation")
    # (iii) contact area and sliding nodes against the time
    t = path["time"]
    axes[2].plot(t, path["area"], "o-", ms=3, color="tab:blue", label="contact area")
    axes[2].set_xlabel("time (of the histories)")
    axes[2].set_ylabel("contact area")
    twin = axes[2].twinx()
    twin.plot(t, path["sliding"], "s--", ms=3, color="tab:red", label="sliding nodes")
    twin.plot(t, path["sliding"] + path["sticking"], ":", color="0.4", label="touching nodes")
    twin.set_ylabel("nodes")
    axes[2].set_title("contact area and sliding nodes")
    lines = axes[2].get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    axes[2].legend(lines[0] + more[0], lines[1] + more[1], fontsize=8, loc="center right")
    for ax in axes[:2]:
        ax.grid(True)
        ax.axhline(0, color="0.7", lw=0.8)
    axes[0].legend(fontsize=8, loc="best")
    axes[2].grid(True)
    return fig


def face_frame(x, normals):
    """The axes a face is drawn in, to scale: rows t1, t2, n of the plane through its nodes x (the least-squares plane;
    n its normal, oriented like the nodes' normals), and the names of t1 and t2. A face in a plane of global axes is
    drawn in those (x, y for z = const); another in t1 along the global axis the face runs along most, t2 = n x t1."""
    n = np.linalg.eigh(np.cov((x - x.mean(axis=0)).T) if len(x) > 2 else np.eye(3))[1][:, 0]
    mean = normals.sum(axis=0)
    if len(x) <= 2 or np.linalg.norm(mean) > 1e-12 and abs(n @ mean) < 1e-12:
        n = mean / np.linalg.norm(mean) if np.linalg.norm(mean) > 1e-12 else np.array([0.0, 0.0, 1.0])
    n = -n if n @ mean < 0 else n
    for k in range(3):
        if abs(abs(n[k]) - 1) < 1e-9:  # a plane of global axes
            a, b = [j for j in range(3) if j != k]
            return np.array([np.eye(3)[a], np.eye(3)[b], n]), ("xyz"[a], "xyz"[b])
    proj = np.eye(3) - np.outer(n, n)
    extent = [np.ptp(x @ proj[k]) for k in range(3)]
    k = int(np.argmax(extent))
    t1 = proj[k] / np.linalg.norm(proj[k])
    return np.array([t1, np.cross(n, t1), n]), ("t1 (in the face's plane, along %s)" % "xyz"[k], "t2 = n x t1")


def nice_length(x):
    """1, 2 or 5 times a power of ten, at most x (x > 0): the length of the key arrow"""
    e = np.floor(np.log10(x))
    for m in (5, 2, 1):
        if m * 10 ** e <= x:
            return m * 10 ** e
    return 10 ** e


def slip_arrows(ax, x, u, touching):
    """The slip u_t of the touching nodes as arrows on one scale (the largest about a tenth of the panel's width);
    returns the quiver (None without slip), the largest slip and the length of the key arrow, a round number"""
    slip = np.linalg.norm(u[touching, :2], axis=1)
    largest = slip.max() if touching.any() else 0.0
    if largest <= 0:
        return None, 0.0, 0.0
    extent = max(np.ptp(x[:, 0]), np.ptp(x[:, 1]))
    scale = largest / (0.1 * extent)  # slip per unit of length on the panel
    q = ax.quiver(x[touching, 0], x[touching, 1], u[touching, 0], u[touching, 1], angles="xy", scale_units="xy", scale=scale,
                  color="k", width=0.003, zorder=3)
    return q, largest, nice_length(largest)


KEY_HANDLE = 5.0  # length of the legend's handles, in font sizes: the key arrow is drawn in its handle


def place_key(fig, ax, legend, q, key, scale):
    """Draws the key arrow, a slip of key on the arrows' scale, in the handle of the legend's last entry (kept free
    for it); a shorter round key when that one does not fit. Called once the layout has placed the legend."""
    renderer = fig.canvas.get_renderer()
    per_data = ax.transData.transform((1, 0))[0] - ax.transData.transform((0, 0))[0]  # pixels per unit of t1
    fontsize = legend.prop.get_size_in_points() * fig.dpi / 72
    room = 0.9 * KEY_HANDLE * fontsize
    while key / scale * per_data > room:
        key = nice_length(0.99 * key)
    text = legend.get_texts()[-1]
    box = text.get_window_extent(renderer)
    tip = (box.x0 - legend.handletextpad * fontsize - 0.05 * KEY_HANDLE * fontsize, 0.5 * (box.y0 + box.y1))
    X, Y = ax.transAxes.inverted().transform(tip)
    text.set_text("key: a slip of %.0e (mesh units)" % key)
    ax.quiverkey(q, X, Y, key, "", labelpos="E", coordinates="axes", color="k").set_zorder(legend.get_zorder() + 1)  # over the legend
    return key


def draw(d):
    """The figure of the solution d (read()): per contact group its states with the slip and its contact pressure"""
    groups = sorted(set(d["group"].tolist()))
    ncols = 3 if d["steps"] is not None else 2
    frames = {g: face_frame(d["coordinates"][d["group"] == g], d["normal"][d["group"] == g]) for g in groups}
    aspect = max(np.ptp(c[:, 1]) / max(np.ptp(c[:, 0]), 1e-300) for c in
                 (d["coordinates"][d["group"] == g] @ frames[g][0].T for g in groups))
    height = float(np.clip(5.5 * aspect + 2.5, 3.5, 9.0))
    fig, axes = plt.subplots(len(groups), ncols, figsize=(6.5 * ncols, height * len(groups)), squeeze=False, layout="constrained")
    keys = []
    for row, g in zip(axes, groups):
        on = d["group"] == g
        n = d["normal"][on]
        R, axis_names = frames[g]
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
        q, largest, key = slip_arrows(row[0], x, u, touching)
        if q is not None:  # the legend's last entry, its handle left free: the key arrow goes there
            row[0].plot([], [], linestyle="none", label="key: a slip of %.0e (mesh units)" % key)
        row[0].set_title("%s: contact states; slip u_t (largest %.2g)" % (name, largest))
        print("drew %s: %d contact nodes" % (name, on.sum()))
        # below the tick labels and the axis label (about 36 points): an offset in font sizes, whatever the panel's height
        legend = row[0].legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, 0.0), borderaxespad=5, ncol=2, handlelength=KEY_HANDLE)
        if q is not None:
            keys.append((row[0], legend, q, key))
        pressure = rn / d["area"][on] if d["area"] is not None else rn
        sc = row[1].scatter(x[:, 0], x[:, 1], c=pressure, s=18, cmap="viridis")
        fig.colorbar(sc, ax=row[1], label="contact pressure r_n / area" if d["area"] is not None else "normal reaction r_n")
        lifted = ~touching
        if lifted.any():
            row[1].scatter(x[lifted, 0], x[lifted, 1], s=40, facecolors="none", edgecolors="0.4", label="separated")
            row[1].legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, 0.0), borderaxespad=5)
        row[1].set_title("%s: contact pressure" % name)
        for ax in row[:2]:
            ax.set_aspect("equal")
            ax.set_xlabel(axis_names[0])
            ax.set_ylabel(axis_names[1])
        if d["steps"] is not None:
            st = d["steps"]
            row[2].plot(st["factor"], st["area"], "o-")
            row[2].set_xlabel("load factor")
            row[2].set_ylabel("contact area (all groups)")
            row[2].set_title("contact area against load")
            row[2].grid(True)
    # the layout places everything (the legends with the key's entry), then stays: the key arrows need its scale
    fig.canvas.draw()
    fig.set_layout_engine("none")
    fig.keys = [place_key(fig, ax, legend, q, key, q.scale) for ax, legend, q, key in keys]
    return fig


def read_reactions(name):
    """For each prescribed group of a load path (/scene/displacement/<G> with /steps/groups/<G>/reaction): its
    displacement (the file's mean of the group, or its prescribed history at the steps' times), its reaction, its free
    components and the units of the file ({} without)"""
    f = h5py.File(name, "r")
    if "steps/groups" not in f or "scene/displacement" not in f:
        return {}
    st, groups = f["steps"], {}
    times = st["time"][:]
    for g, grp in f["scene/displacement"].items():
        if g not in st["groups"] or "reaction" not in st["groups"][g]:
            continue
        if "displacement" in st["groups"][g]:
            u = st["groups"][g]["displacement"][:]
        else:  # a volume group: its prescribed values at the steps' times
            text = grp.attrs["displacement"]
            text = text.decode() if isinstance(text, bytes) else str(text)
            knots = [k.split(":") for k in text.replace("free", "nan").split(";")] if ":" in text else [("0", text.replace("free", "nan"))]
            t = np.array([float(k[0]) for k in knots])
            v = np.array([[float(x) for x in k[1].split(",")] for k in knots])
            u = np.array([[np.interp(s, t, v[:, c]) for c in range(3)] for s in times])
        groups[g] = {"displacement": u, "reaction": st["groups"][g]["reaction"][:], "free": grp.attrs["free"][:], "time": times}
    return groups


def draw_reactions(name):
    """The force-displacement picture of a load path's prescribed groups (read_reactions()): one panel per group, its
    reaction against its displacement in the prescribed component whose displacement varies most; None without"""
    groups = read_reactions(name)
    if not groups:
        return None
    f = h5py.File(name, "r")
    length = f["scene"].attrs.get("length_unit", "mesh length unit")
    force = f["scene"].attrs.get("force_unit", "E unit x length$^2$")
    fig, axes = plt.subplots(1, len(groups), figsize=(5.2 * len(groups), 4.2), squeeze=False, layout="constrained")
    for ax, (g, d) in zip(axes[0], sorted(groups.items())):
        held = [k for k in range(3) if not d["free"][k]]
        k = max(held, key=lambda c: np.ptp(d["displacement"][:, c]))
        axis = "xyz"[k]
        ax.plot(d["displacement"][:, k], d["reaction"][:, k], "o-", color="tab:blue")
        ax.axhline(0, color="0.7", lw=0.8)
        ax.axvline(0, color="0.7", lw=0.8)
        ax.set_xlabel("displacement $u_%s$ of %s (%s)" % (axis, g, length))
        ax.set_ylabel("reaction $R_%s$ at %s (%s)" % (axis, g, force))
        ax.set_title("%s: reaction on the body against displacement, %d steps" % (g, len(d["time"])), fontsize=10)
    return fig


def plotted(fig):
    """What a figure draws, panel by panel: its title, axis labels and limits, and the values of its lines and of its
    points (scatter offsets, with their colour values where a colour map gives them)"""
    panels = []
    for ax in fig.axes:
        if not ax.get_title() and not ax.lines and not ax.collections:
            continue  # a colour bar's axes
        panel = {"title": ax.get_title(), "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(), "xlim": list(ax.get_xlim()),
                 "ylim": list(ax.get_ylim()), "aspect": ax.get_aspect() if isinstance(ax.get_aspect(), float) else str(ax.get_aspect()),
                 "lines": [{"label": ln.get_label(), "x": np.asarray(ln.get_xdata(), float).tolist(), "y": np.asarray(ln.get_ydata(), float).tolist()}
                           for ln in ax.lines if len(ln.get_xdata())], "points": []}
        for c in ax.collections:
            offsets = np.asarray(c.get_offsets(), float)
            if not len(offsets) or not hasattr(c, "get_array"):
                continue
            values = c.get_array()
            panel["points"].append({"label": c.get_label(), "x": offsets[:, 0].tolist(), "y": offsets[:, 1].tolist(),
                                    "values": None if values is None else np.asarray(values, float).tolist()})
        panels.append(panel)
    return panels


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file")
    parser.add_argument("-o", "--output", help="PNG file (default: FILE with .png)")
    parser.add_argument("--history", help="PNG file of a load path's history (default: FILE_history.png; with /steps)")
    parser.add_argument("--data", help="JSON file of what was drawn: per figure and panel the labels, limits and values")
    args = parser.parse_args()
    with h5py.File(args.file, "r") as f:
        if "contact" not in f:
            print("%s has no contact nodes: no contact faces to draw" % args.file)
            return
    data = read(args.file)
    drawn = {}
    fig = draw(data)
    out = args.output or args.file.rsplit(".", 1)[0] + ".png"
    fig.savefig(out, dpi=110, bbox_inches="tight")
    drawn["faces"] = plotted(fig)
    print("wrote " + out)
    fig = draw_history(data)
    if fig is not None:
        out = args.history or args.file.rsplit(".", 1)[0] + "_history.png"
        fig.savefig(out, dpi=110, bbox_inches="tight")
        drawn["history"] = plotted(fig)
        print("wrote " + out)
    fig = draw_reactions(args.file)
    if fig is not None:
        out = args.file.rsplit(".", 1)[0] + "_reaction.png"
        fig.savefig(out, dpi=110, bbox_inches="tight")
        drawn["reaction"] = plotted(fig)
        print("wrote " + out)
    if args.data:
        with open(args.data, "w") as f:
            json.dump(drawn, f, indent=1)
        print("wrote " + args.data)


if __name__ == "__main__":
    main()
