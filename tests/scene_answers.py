#!/usr/bin/python3
"""Known answers of the shipped scenes, measured from a solution file of examples/contact (-o file.h5).

  scene_answers.py hertz FILE.h5 [--E 2.1e5 --nu 0.3 --R 10 --group G]
      contact radius a and peak pressure p0 against Hertz's sphere on a rigid plane (the hertz scene) or a rigid ball
      on a block (the ball scene), the contact centred on the z axis, with the force F the obstacle carries (the
      length of the resultant of the contact reactions; with --group, those of the contact group G alone, as each
      plate of the squeeze scene): a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2),
      E* = E / (1 - nu^2). Measured: the pressure r_n / area of the nodes in contact well inside the contact zone
      (r < 0.8 a) fitted by p^2 = p0^2 (1 - r^2/a^2); and the bracket [outermost node in contact, innermost node out
      of contact]
  scene_answers.py line FILE.h5 [--E 2.1e5 --nu 0.3 --R 10]
      half-width b and peak pressure p0 against Hertz's line contact of a rigid cylinder along y touching the block
      on the line x = z = 0 (the roller scene: a mesh extruded along y in layers), in the section y = 0, with its
      force per unit length F' = (sum of r_n over the nodes of the section) / (layer thickness): b = sqrt(4 F' R /
      (pi E*)), p0 = 2 F' / (pi b). Measured: p^2 = p0^2 (1 - x^2/b^2) fitted to the section's nodes in contact
      with |x| < 0.8 b, and the bracket
  scene_answers.py von-mises FILE.h5 [--E 2.1e5 --nu 0.3 --R 10]
      Hertz's subsurface von Mises maximum (the hertz scene, /fields/von_mises): the largest cell value under the
      contact (centroid within a of the axis, above the depth 2 a) in p0 and its depth in a, against Hertz's on-axis
      maximum (0.620 p0 at 0.481 a for nu = 0.3), a and p0 Hertz's for the measured normal force
  scene_answers.py stick-radius FILE.h5 [--E 2.1e5 --nu 0.3 --R 10 --phi 0.3]
      Cattaneo-Mindlin (the mindlin scene: two bodies of one material, P then Q < phi P): Q/(phi P), Hertz's a
      (1/E* = 2 (1 - nu^2)/E), c = a (1 - Q/(phi P))^(1/3), the outermost sticking node's radius and the innermost
      sliding node's
  scene_answers.py friction FILE.h5
      the contact force of the plane(s): normal N, tangential |F_t|, their ratio, and the states
  scene_answers.py slide FILE.h5 tx,ty,tz
      the mean displacement of the contact nodes along t (the rigid slide of a block)
  scene_answers.py first-contact LINEAR.h5 CONTACT.h5
      the load factor at which a body first touches: min over the contact nodes of gap / (-u.n), with u the
      displacement without contact (LINEAR.h5, at the full load) and the gaps and normals of CONTACT.h5
  scene_answers.py sliding FILE.h5 [--from T]
      a load path's steps from time T on (default: every step), for large sliding: the normal force N, the ratio of
      the tangential force to phi N over the steps where every touching node slides (phi from /contact/friction),
      the contact area, and the contact's centroid (the pressure-weighted mean of the touching nodes' current
      positions x + u) less the moving obstacle's translation (/steps/motion/<G>: the patch follows the obstacle
      when that stays put); the mean and spread (max - min) of each
Prints "name value" lines; as a module, the functions return dictionaries.
"""
import argparse

import h5py
import numpy as np

TOUCHING = (1, 2, 3, 4, 5)  # states other than L (0) and LS (6)


def contact(name, group=None):
    f = h5py.File(name, "r")
    c = f["contact"]
    d = {k: c[k][:] for k in c}
    if group is not None:
        names = c["group"].attrs["names"]
        names = [n.split("->")[0] for n in (names.decode() if isinstance(names, bytes) else str(names)).split(",")]  # "G,H->M"
        mine = d["group"] == names.index(group)
        d = {k: (v[mine] if len(v) == len(mine) else v) for k, v in d.items()}
    d["touching"] = np.isin(d["state"], TOUCHING)
    d["rn"] = (d["reaction"] * d["normal"]).sum(axis=1)
    return d


def hertz(name, E=2.1e5, nu=0.3, R=10.0, group=None):
    d = contact(name, group)
    F = np.linalg.norm(d["reaction"].sum(axis=0))
    Es = E / (1 - nu ** 2)
    a = (3 * F * R / (4 * Es)) ** (1 / 3)
    p0 = 3 * F / (2 * np.pi * a ** 2)
    r = np.hypot(d["coordinates"][:, 0], d["coordinates"][:, 1])
    t = d["touching"]
    inside, outside = r[t].max(), r[~t].min()
    p = d["rn"] / d["area"]
    fit = t & (r < 0.8 * inside)
    A, B = np.linalg.lstsq(np.c_[np.ones(fit.sum()), -r[fit] ** 2], p[fit] ** 2, rcond=None)[0]
    p0_fit, a_fit = np.sqrt(A), np.sqrt(A / B)
    return {"force": F, "a_hertz": a, "p0_hertz": p0, "a_fit": a_fit, "p0_fit": p0_fit,
            "a_error": a_fit / a - 1, "p0_error": p0_fit / p0 - 1, "a_inside": inside, "a_outside": outside,
            "nodes_in_contact": int(t.sum())}


def hertz_on_axis(z, nu):
    """Hertz's stresses on the axis under a sphere, in p0 (Johnson, Contact Mechanics, (3.45)): the von Mises stress
    |sigma_r - sigma_z| at the depth z in a"""
    sz = -1 / (1 + z ** 2)
    sr = -(1 + nu) * (1 - z * np.arctan(1 / z)) + 0.5 / (1 + z ** 2)
    return np.abs(sr - sz)


def von_mises(name, E=2.1e5, nu=0.3, R=10.0):
    """Hertz's subsurface maximum: the largest von Mises stress of the cells under the contact (centroid within a of
    the axis, depth below 2 a) in p0 and its depth in a, against Hertz's on-axis maximum (0.620 p0 at 0.481 a for
    nu = 0.3), a and p0 Hertz's for the measured normal force"""
    f = h5py.File(name, "r")
    F = f["contact/reaction"][:, 2].sum()
    a = (3 * F * R / (4 * E / (1 - nu ** 2))) ** (1 / 3)
    p0 = 3 * F / (2 * np.pi * a ** 2)
    x, cells, vm = f["geometry/vertices"][:], f["viz/topology/cells"][:], f["fields/von_mises"][:]
    centre = x[cells].mean(axis=1)
    under = (np.hypot(centre[:, 0], centre[:, 1]) < a) & (centre[:, 2] < 2 * a)
    j = np.argmax(vm[under])
    z = np.linspace(0.01, 3, 30000)
    theory = hertz_on_axis(z, nu)
    value, depth = vm[under][j] / p0, centre[under][j, 2] / a
    return {"vm_max": value, "vm_depth": depth, "vm_hertz": theory.max(), "depth_hertz": z[theory.argmax()],
            "vm_error": value / theory.max() - 1, "vm_depth_error": depth / z[theory.argmax()] - 1}


def stick_radius(name, phi, E, nu=0.3, R=10.0):
    """Cattaneo-Mindlin (two bodies of one material, P then Q < phi P): Q/(phi P), Hertz's a, the stick radius
    c = a (1 - Q/(phi P))^(1/3), the outermost sticking node's radius and the innermost sliding node's (in contact)"""
    d = contact(name)
    force = d["reaction"].sum(axis=0)
    P, Q = force[2], np.hypot(force[0], force[1])
    a = (3 * P * R / (4 * E / (2 * (1 - nu ** 2)))) ** (1 / 3)
    r = np.hypot(d["coordinates"][:, 0], d["coordinates"][:, 1])
    stick, slide = r[np.isin(d["state"], (3, 4))], r[np.isin(d["state"], (1, 2))]
    outer = stick.max() if len(stick) else 0.0
    inner = slide[slide > outer].min() if (slide > outer).any() else a
    return {"ratio": Q / (phi * P), "a": a, "c": a * (1 - Q / (phi * P)) ** (1 / 3), "stick_outer": outer, "slide_inner": inner}


def line(name, E=2.1e5, nu=0.3, R=10.0):
    d = contact(name)
    x, y = d["coordinates"][:, 0], d["coordinates"][:, 1]
    hy = np.abs(y)[np.abs(y) > 1e-9].min()
    section = np.abs(y) <= 1e-9
    F = d["rn"][section].sum() / hy
    Es = E / (1 - nu ** 2)
    b = np.sqrt(4 * F * R / (np.pi * Es))
    p0 = 2 * F / (np.pi * b)
    t = d["touching"] & section
    inside, outside = np.abs(x[t]).max(), np.abs(x[section & ~d["touching"]]).min()
    p = d["rn"] / d["area"]
    fit = t & (np.abs(x) < 0.8 * inside)
    A, B = np.linalg.lstsq(np.c_[np.ones(fit.sum()), -x[fit] ** 2], p[fit] ** 2, rcond=None)[0]
    p0_fit, b_fit = np.sqrt(A), np.sqrt(A / B)
    return {"force_per_length": F, "layer": hy, "b_hertz": b, "p0_hertz": p0, "b_fit": b_fit, "p0_fit": p0_fit,
            "b_error": b_fit / b - 1, "p0_error": p0_fit / p0 - 1, "b_inside": inside, "b_outside": outside,
            "nodes_in_contact": int(t.sum())}


def friction(name):
    d = contact(name)
    n = d["normal"][0]
    force = d["reaction"].sum(axis=0)
    N = force.dot(n)
    Ft = np.linalg.norm(force - N * n)
    s = d["state"]
    return {"normal_force": N, "tangential_force": Ft, "ratio": Ft / N, "separated": int(np.isin(s, (0, 6)).sum()),
            "sliding": int(np.isin(s, (1, 2)).sum()), "sticking": int(np.isin(s, (3, 4, 5)).sum()), "nodes": len(s)}


def slide(name, direction):
    """The mean displacement of the contact nodes along a direction (the rigid slide of a block)"""
    d = contact(name)
    return {"slide": float((d["displacement"] @ np.asarray(direction, float)).mean())}


def first_contact(linear, with_contact):
    d = contact(with_contact)
    f = h5py.File(linear, "r")
    x, u = f["geometry/vertices"][:], f["fields/displacement"][:]
    index = {tuple(np.round(v, 12)): i for i, v in enumerate(x)}
    un = np.array([u[index[tuple(np.round(v, 12))]].dot(n) for v, n in zip(d["coordinates"], d["normal"])])
    closing = un < 0
    return {"factor": float(np.min(d["gap"][closing] / -un[closing])) if closing.any() else np.inf}


def sliding(name, start=-np.inf):
    f = h5py.File(name, "r")
    st, x = f["steps"], f["contact/coordinates"][:]
    phi = f["contact/friction"][:].max()
    t, N, T, A = st["time"][:], st["normal_force"][:], np.linalg.norm(st["tangential_force"][:], axis=1), st["area"][:]
    motion = next(iter(st["motion"].values()))[:] if "motion" in st and len(st["motion"]) else np.zeros((len(t), 3))
    rows = np.flatnonzero(t >= start)
    full = [k for k in rows if st["sticking"][k] == 0 and st["sliding"][k] > 0]
    lag = []
    for k in rows:
        c = st["%d/contact" % k]
        touching = np.isin(c["state"][:], TOUCHING)
        p = (c["reaction"][:] * c["normal"][:]).sum(axis=1)[touching]
        if p.sum() > 0:
            lag.append(((x + c["displacement"][:])[touching] * p[:, None]).sum(axis=0) / p.sum() - motion[k])
    lag = np.array(lag)
    spread = lambda v: float(v.max() - v.min()) if len(v) else np.nan
    ratio = T[full] / (phi * N[full]) if full else np.array([np.nan])
    return {"steps": len(rows), "sliding_steps": len(full), "normal_force_mean": float(N[rows].mean()),
            "normal_force_spread": spread(N[rows]), "friction_ratio_min": float(ratio.min()),
            "friction_ratio_max": float(ratio.max()), "area_mean": float(A[rows].mean()), "area_spread": spread(A[rows]),
            "centroid_lag_x_spread": spread(lag[:, 0]) if len(lag) else np.nan, "centroid_lag_y_spread": spread(lag[:, 1]) if len(lag) else np.nan}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="cmd", required=True)
    h = sub.add_parser("hertz")
    h.add_argument("file")
    h.add_argument("--E", type=float, default=2.1e5)
    h.add_argument("--nu", type=float, default=0.3)
    h.add_argument("--R", type=float, default=10.0)
    h.add_argument("--group", default=None)
    li = sub.add_parser("line")
    li.add_argument("file")
    li.add_argument("--E", type=float, default=2.1e5)
    li.add_argument("--nu", type=float, default=0.3)
    li.add_argument("--R", type=float, default=10.0)
    for name in ("von-mises", "stick-radius"):
        v = sub.add_parser(name)
        v.add_argument("file")
        v.add_argument("--E", type=float, default=2.1e5)
        v.add_argument("--nu", type=float, default=0.3)
        v.add_argument("--R", type=float, default=10.0)
        v.add_argument("--phi", type=float, default=0.3)
    fr = sub.add_parser("friction")
    fr.add_argument("file")
    sl = sub.add_parser("slide")
    sl.add_argument("file")
    sl.add_argument("direction")
    sd = sub.add_parser("sliding")
    sd.add_argument("file")
    sd.add_argument("--from", dest="start", type=float, default=-np.inf)
    fc = sub.add_parser("first-contact")
    fc.add_argument("linear")
    fc.add_argument("contact")
    args = parser.parse_args()
    if args.cmd == "hertz":
        result = hertz(args.file, args.E, args.nu, args.R, args.group)
    elif args.cmd == "line":
        result = line(args.file, args.E, args.nu, args.R)
    elif args.cmd == "von-mises":
        result = von_mises(args.file, args.E, args.nu, args.R)
    elif args.cmd == "stick-radius":
        result = stick_radius(args.file, args.phi, args.E, args.nu, args.R)
    elif args.cmd == "friction":
        result = friction(args.file)
    elif args.cmd == "slide":
        result = slide(args.file, [float(v) for v in args.direction.split(",")])
    elif args.cmd == "sliding":
        result = sliding(args.file, args.start)
    else:
        result = first_contact(args.linear, args.contact)
    for k, v in result.items():
        print("%-18s %.6g" % (k, v))


if __name__ == "__main__":
    main()
