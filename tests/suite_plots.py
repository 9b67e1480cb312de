"""examples/plot_contact.py tells the truth: on the files the project writes (the scenes, load paths from C and from
Python, moving obstacles, pairs, a refined mesh), what it draws is checked against the file, by an independent reading
of the file: the contact faces to scale in their own plane, the pressures, and a load path's history (the group that
carries it, its normal force against the indentation, the force components that carry the load)."""
import glob
import importlib.util
import os
import re

import h5py
import matplotlib
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

matplotlib.use("Agg")
CONTACT = os.path.join(ROOT, "examples", "contact")
SCENES = os.path.join(ROOT, "scenes")
# shorter load paths of the scenes (the same kind of file in a few steps)
SHORT = {"drag": ["-steps", "0,1,1.5"], "punch": ["-steps", "0,1,1.25"], "track": ["-steps", "0,1,1.25,1.5"]}


def plot_module():
    spec = importlib.util.spec_from_file_location("plot_contact", os.path.join(ROOT, "examples", "plot_contact.py"))
    plot = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plot)
    return plot


def scene_file(name, extra=()):
    """examples/contact on scenes/<name>.opts (a shorter path where SHORT says), its -o file"""
    h5 = os.path.join(OUT, "plots_%s.h5" % name)
    run(mpiexec(1, CONTACT, "-options_file", os.path.join(SCENES, name + ".opts"), *SHORT.get(name, []), *extra, "-o", h5))
    return h5


def python_file():
    """A load path decided by a Python loop (examples/scene.py onset: ssstar.Scene, loads set between steps)"""
    h5 = os.path.join(OUT, "plots_onset.h5")
    run([PYTHON, os.path.join(ROOT, "examples", "scene.py"), "onset", "--out", h5])
    return h5


def group_names(f):
    names = f["contact/group"].attrs.get("names", b"contact") if "group" in f["contact"] else b"contact"
    return (names.decode() if isinstance(names, bytes) else str(names)).split(",")


def check_faces(plot, h5):
    """Each group's face drawn to scale in its own plane: a flat face's points at the distances of its nodes (any pair),
    in the global axes of its plane where it lies in one (those coordinates exactly, the axes named); a curved face's
    no farther apart than its nodes and not much nearer; equal aspect; the pressure panel r_n / area of the file"""
    d = plot.read(h5)
    fig = plot.draw(d)
    f = h5py.File(h5, "r")
    x, r, n = f["contact/coordinates"][:], f["contact/reaction"][:], f["contact/normal"][:]
    area = f["contact/area"][:]
    group = f["contact/group"][:] if "group" in f["contact"] else np.zeros(len(x), int)
    names = group_names(f)
    rng = np.random.default_rng(0)
    for g in sorted(set(group.tolist())):
        on, name = group == g, names[g]
        states = [ax for ax in fig.axes if ax.get_title().startswith(name + ": contact states")]
        pressure = [ax for ax in fig.axes if ax.get_title() == name + ": contact pressure"]
        expect(len(states) == 1 and len(pressure) == 1, "%s: the panels of group %s" % (h5, name))
        ax = pressure[0]
        drawn = np.asarray(ax.collections[0].get_offsets(), float)
        values = np.asarray(ax.collections[0].get_array(), float)
        expect(drawn.shape == (on.sum(), 2), "%s, %s: %d points drawn for %d nodes" % (h5, name, len(drawn), on.sum()))
        expect(np.allclose(values, (r[on] * n[on]).sum(axis=1) / area[on], rtol=1e-12, atol=0), "%s, %s: the pressure is not r_n / area" % (h5, name))
        xs = x[on]
        c = xs - xs.mean(axis=0)
        w, v = np.linalg.eigh(c.T @ c)
        flat = np.sqrt(max(w[0], 0) / len(xs)) <= 1e-9 * max(np.ptp(xs, axis=0).max(), 1e-300)
        i, j = rng.integers(0, len(xs), 400), rng.integers(0, len(xs), 400)
        d3, d2 = np.linalg.norm(xs[i] - xs[j], axis=1), np.linalg.norm(drawn[i] - drawn[j], axis=1)
        scale = np.ptp(xs, axis=0).max()
        if flat:
            expect(np.abs(d3 - d2).max() <= 1e-9 * scale, "%s, %s: a flat face not drawn to scale (distances off by %.2g of its size)" % (h5, name, np.abs(d3 - d2).max() / scale))
            normal = v[:, 0]
            k = int(np.argmax(np.abs(normal)))
            if abs(abs(normal[k]) - 1) < 1e-9:  # in a plane of global axes: drawn in those, named
                a, b = [m for m in range(3) if m != k]
                expect(np.array_equal(drawn, xs[:, [a, b]]) and ax.get_xlabel() == "xyz"[a] and ax.get_ylabel() == "xyz"[b],
                       "%s, %s: a face z = const not drawn in its global axes %s, %s (labels %s, %s)" % (h5, name, "xyz"[a], "xyz"[b], ax.get_xlabel(), ax.get_ylabel()))
        else:
            expect((d2 <= d3 + 1e-9 * scale).all() and d2.sum() >= 0.9 * d3.sum(), "%s, %s: a curved face drawn out of scale (%.3f of its distances)" % (h5, name, d2.sum() / d3.sum()))
        for a in states + pressure:
            lo, hi = a.get_xlim(), a.get_ylim()
            expect(a.get_aspect() == 1.0 and lo[0] <= drawn[:, 0].min() and lo[1] >= drawn[:, 0].max() and hi[0] <= drawn[:, 1].min() and hi[1] >= drawn[:, 1].max(),
                   "%s, %s: not equal aspect, or points outside the panel" % (h5, name))
    return d


def axis_of(label):
    """The direction a label names: 'along x' / 'along (a, b, c)' / 'n = -z'"""
    m = re.search(r"(?:along|n =) (-?[xyz]|\([^)]*\))", label)
    expect(m is not None, "no direction in the label '%s'" % label)
    text = m.group(1)
    if text.startswith("("):
        return np.array([float(s) for s in text[1:-1].split(",")])
    e = np.eye(3)["xyz".index(text[-1])]
    return -e if text.startswith("-") else e


def body_of(f, on):
    """The mesh nodes of the body whose contact nodes are on: grown cell by cell from those nodes (a pair's mesh holds
    two bodies)"""
    x, cells = f["geometry/vertices"][:], f["viz/topology/cells"][:]
    nearest = [np.argmin(((x - p) ** 2).sum(axis=1)) for p in f["contact/coordinates"][:][on]]
    reached = np.zeros(len(x), bool)
    reached[nearest] = True
    while True:
        grown = reached.copy()
        grown[cells[reached[cells].any(axis=1)]] = True
        if grown.sum() == reached.sum():
            return reached
        reached = grown


def check_history(plot, d, h5):
    """The history against the file: the group that carries the path (the moving obstacle's, else the largest normal
    force), its force-weighted normal n; the loop's x and y the file's columns along the direction its labels name,
    which lies off n; the normal force on the group against (m - u).n; the area; no 'None' in any label"""
    fig = plot.draw_history(d)
    f = h5py.File(h5, "r")
    st = f["steps"]
    steps = sorted((k for k in st if k.isdigit()), key=int)
    names = group_names(f)
    group = f["contact/group"][:] if "group" in f["contact"] else np.zeros(len(f["contact/coordinates"]), int)
    moving = [g for g, name in enumerate(names) if "motion" in st and name in st["motion"]]
    contact = [(f["steps/%s/contact/reaction" % k][:], f["steps/%s/contact/normal" % k][:] if "normal" in f["steps/%s/contact" % k] else f["contact/normal"][:]) for k in steps]
    normal_force = lambda g: np.array([((r * n).sum(axis=1))[group == g].sum() for r, n in contact])  # noqa: E731
    g = moving[0] if moving else max(sorted(set(group.tolist())), key=lambda g: normal_force(g)[-1])
    name = names[g]
    weighted = sum(((np.maximum((r * n).sum(axis=1), 0)[:, None] * n)[group == g]).sum(axis=0) for r, n in contact)
    n = weighted / np.linalg.norm(weighted)
    xs = f["contact/coordinates"][:][group == g]
    w, v = np.linalg.eigh((xs - xs.mean(axis=0)).T @ (xs - xs.mean(axis=0)))
    if np.sqrt(max(w[0], 0) / len(xs)) <= 1e-9 * np.ptp(xs, axis=0).max():  # a flat face: its normal
        n = v[:, 0] * np.sign(v[:, 0] @ n)
    panels = {ax.get_title().split(" (")[0]: ax for ax in fig.axes if ax.get_title()}
    for ax in fig.axes:
        for text in (ax.get_title(), ax.get_xlabel(), ax.get_ylabel()):
            expect("None" not in text, "%s: a label says None: %s" % (h5, text))
    loop = panels["tangential force against displacement"]
    x, y = loop.lines[0].get_xdata(), loop.lines[0].get_ydata()
    t = axis_of(loop.get_xlabel())
    expect(np.allclose(axis_of(loop.get_ylabel()), t) and abs(t @ n) < 0.2, "%s: the loop's direction %s is not off the normal %s" % (h5, t, n))
    source = re.search(r"(translation of the obstacle of|mean displacement of) ([^\s,()]+)", loop.get_xlabel())
    expect(source is not None, "%s: the loop's x is not named" % h5, loop.get_xlabel())
    column = st["motion/%s" % source.group(2)] if source.group(1).startswith("translation") else st["groups/%s/displacement" % source.group(2)]
    # a global axis exactly; a direction the label gives to 3 digits, to 2e-3 of the largest value
    close = (lambda a, b: np.allclose(a, b, rtol=1e-9, atol=1e-12 * max(np.abs(b).max(), 1e-300))) if np.abs(t).max() == 1 else \
        (lambda a, b: np.abs(a - b).max() <= 2e-3 * max(np.abs(b).max(), 1e-300))  # noqa: E731
    expect(close(x, column[:] @ t), "%s: the loop's x is not %s along %s" % (h5, column.name, t))
    if loop.get_ylabel().startswith("applied load"):
        expect(close(y, st["load"][:] @ t), "%s: the loop's y is not the applied load" % h5)
    else:
        expect(loop.get_ylabel().startswith("friction force on the body at %s" % name), "%s: the loop's y is neither the load nor %s's friction force" % (h5, name), loop.get_ylabel())
        T = np.array([(r - (r * nn).sum(axis=1)[:, None] * nn)[group == g].sum(axis=0) for r, nn in contact])
        expect(close(y, T @ t), "%s: the loop's y is not the friction force on %s" % (h5, name))
    ind = panels["normal force against indentation"]
    x, y = ind.lines[0].get_xdata(), ind.lines[0].get_ydata()
    expect(ind.get_ylabel() == "normal force on %s" % name and np.allclose(y, normal_force(g), rtol=1e-9, atol=1e-12 * max(np.abs(y).max(), 1e-300)),
           "%s: not the normal force on %s" % (h5, name), ind.get_ylabel())
    ref = re.search(r"u the mean displacement of ([^\s,()]+)", ind.get_xlabel())
    expect(ref is not None and np.allclose(axis_of(ind.get_xlabel()), n, atol=1e-2), "%s: the indentation's u or n is not named (n = %s)" % (h5, n), ind.get_xlabel())
    m = st["motion/%s" % name][:] if moving else 0
    if ref.group(1) == "the":  # the body: the nodes of the mesh's cells reached from the group's contact nodes
        u = np.array([f["steps/%s/fields/displacement" % k][:][body_of(f, group == g)].mean(axis=0) for k in steps])
    else:
        u = st["groups/%s/displacement" % ref.group(1)][:]
    expect(np.allclose(x, (m - u) @ n, rtol=1e-9, atol=1e-12 * max(np.abs(x).max(), 1e-300)), "%s: the indentation is not (m - u).n" % h5)
    area = [ln for ax in fig.axes for ln in ax.lines if ln.get_label() == "contact area"]
    expect(area and np.array_equal(area[0].get_ydata(), st["area"][:]), "%s: the contact area is not the file's" % h5)
    return {"group": name, "direction": t, "indentation": x, "normal": n}


@test("plot_contact.py tells the truth on the kinds of file the project writes, checked against the file: a ball "
      "dragged along the slab (C, a moving obstacle: the friction force along x against the ball's translation along x, "
      "the indentation (m - u).n, the ball's 0.02 less the slab's mean sag, 0.019-0.02 at every step of the drag, not the 2 of its travel), the "
      "unstructured slab pressed from above (the face 4.2 x 4.2 drawn in x, y to scale), the Python loop of examples/scene.py "
      "onset (its traction group top, never 'None'), a pair (the slider), the incline's tilted plane, the Hertz ball's "
      "curved cap, a refined mesh (shear, -dm_refine 1)", full=True)
def plots_tell_the_truth():
    plot = plot_module()
    files = {"drag": scene_file("drag"), "press": scene_file("press"), "onset": python_file(), "slider": scene_file("slider"),
             "incline": scene_file("incline"), "hertz": scene_file("hertz"), "refined": scene_file("shear", ["-level", "2", "-dm_refine", "1"])}
    for name, h5 in files.items():
        d = check_faces(plot, h5)
        if d["path"] is not None:
            h = check_history(plot, d, h5)
            if name == "drag":
                expect(h["group"] == "top" and np.allclose(h["direction"], [1, 0, 0]) and (0.019 <= h["indentation"][1:]).all() and (h["indentation"] <= 0.02).all(),
                       "drag: group %s, direction %s, indentation %s" % (h["group"], h["direction"], h["indentation"]))
            if name == "onset":
                expect(np.allclose(h["direction"], [1, 0, 0]), "onset: the shear is along x, drawn along %s" % h["direction"])


@test("plot_contact.py on every scene of scenes/ (their files at their levels, the long load paths shortened): each "
      "face to scale in its own plane with the file's pressures, each history against the file (tests/suite_plots.py)", full=True)
def plots_every_scene():
    plot = plot_module()
    for opts in sorted(glob.glob(os.path.join(SCENES, "*.opts"))):
        name = os.path.basename(opts)[:-5]
        h5 = scene_file(name)
        d = check_faces(plot, h5)
        if d["path"] is not None:
            check_history(plot, d, h5)
