#!/usr/bin/python3
"""The robustness families of issues 18 and 23, at the default settings. Every member runs on both paths (the dense
route, -snes_ssstar_reduction direct, and the whole body, none) on 1 to 4 ranks and must

  converge (every step of a load path),
  write a file whose every step passes tests/check_solution.py (the friction law as written, docs/derivation.md
  section 12), and
  agree with the exact discrete solution, the dense route on one rank at -snes_rtol 1e-13, to 1e-6 at every step (each
  relative to its own scale: the step's values and their change from the step before; tests/check_solution.py compare
  --steps).

  static: nearly floating bodies (soft springs against a stiff body) under tilted rollers and rigid balls, two-body
          pairs, sheared, friction from 0.1 to 2 (issue 18)
  paths:  load paths (issue 23): stiff blocks on soft springs pressed, sheared past sliding, released, reversed and
          released; a plane dragging a block forward and back (it sticks and returns; or slides back); a ball pressed
          and lifted off, a cylinder pressed and rolled forth and back; the tilted roller and the two-body pairs loaded
          forth and back
  sliding: large sliding (issue 24): balls, cylinders and flat punches dragged along a slab and back by several of
          their sizes (scenes/drag.opts, scenes/punch.opts), a punch off the slab's end, blocks slid across a block by
          twice their length and part of the way back (scenes/track.opts), node-to-surface and dual mortar
  floating: bodies held by contact alone, no spring (issue 25, docs/guide/floating-bodies.md): slopes at
          several phi / tan alpha, pushed slopes, stacks, squeezed balls, a slider pushed on its base. Where no
          equilibrium exists a member must instead stop before its first iteration on both paths (DIVERGED_DTOL, the
          line "no equilibrium: ..."), within EARLY seconds (mesh and set-up included)
  dynamics: -dynamics (issue 32, docs/guide/dynamics.md): a rod on a wall at several v0, steps and meshes and with the
          lumped mass, a ball dropped on a plane at two v0, blocks released on slopes at several phi / tan alpha, a
          block on a belt, a stack of floating bodies. Besides the law at every step, a member must gain no energy
          (energy_error <= 1e-9 of the energy) and its error to the exact solution is measured on the displacement
          and velocity fields and the normal force of every step, each relative to its path's largest (a reaction
          after a release is the inertial terms' round-off, not a scale of its own)
  finite_strain: hyperelastic bodies (issue 33, docs/guide/large-deformation.md): the unit cube compressed on the
          frictionless plane (10, 30, 50 %, both models; in one step and on a path), a block pushed into a rigid ball (the
          first step deep, and on a path with phi = 0.3), a cube pressed and dragged with phi = 0.3 by three times its
          width, a pair under a dead pressure of 0.5 E, rotations of 90 degrees (free, and standing on the plane). Their
          residual is nonlinear: the dense route must be refused by name; the whole body is checked against its own run
          on one rank at -snes_rtol 1e-13 and, where there is one, the closed form (the top's reaction of uniaxial stress,
          docs/derivation.md (18.6), or no stress after a rotation) to 1e-6

Prints a markdown table (and bench/output/robust.csv): per member and ranks, each path's iterations (Krylov iterations
of the whole body), reason, law (check_solution's largest distance to the law over the steps) and error (to the exact
solution), then "N members x ranks: converged C of R runs, the law holds in L, within 1e-6 of the exact solution E";
the exit status is 0 when every run passes.

  bench/robust.py [--family static|paths|sliding|floating|degenerate|dynamics|finite_strain|all] [--ranks 1,2,3,4] [--only SUBSTRING]

tests/suite_robust.py runs members of the first two families (FAMILY, PATHS below) as tests, tests/suite_sliding.py
the known answers of the third, tests/suite_floating.py the floating family's cases (FLOATING).
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from loadpath_check import mindlin_scene_args  # noqa: E402

OUT = os.path.join(ROOT, "bench", "output", "robust")
CONTACT = os.path.join(ROOT, "examples", "contact")
CHECK = ["/usr/bin/python3", os.path.join(ROOT, "tests", "check_solution.py")]
SUMMARY = re.compile(r"summary: .* iterations (\d+) states \S+ ([\d/]+) (\S+)")
KRYLOV = re.compile(r"last solve: \d+ linear solves, (\d+) Krylov iterations")
DISTANCE = re.compile(r"^distance to the law\s+(\S+)", re.M)
DIFFERENCE = re.compile(r"^(?:displacement|reaction|full field)\s+max difference\s+(\S+)", re.M)
TIMEOUT = 600  # seconds: a run this long at these sizes hangs
TOLERANCE = 1e-6  # the error to the exact discrete solution at the defaults (docs/guide/converged.md)


def scene(name):
    return ["-options_file", os.path.join(ROOT, "scenes", name + ".opts")]


def axis(degrees):
    a = math.radians(degrees)
    return "cylinder:0,0,10,%.6f,%.6f,0,10" % (math.cos(a), math.sin(a))


def history(*knots):
    """"t:x,y,z;..." of the knots (x, y, z) at t = 0, 1, 2, ..."""
    return ";".join("%d:%s" % (t, ",".join("%.10g" % v for v in k)) for t, k in enumerate(knots))


ROLLER = scene("tilted_roller")
BALL = ROLLER + ["-obstacle_top", "sphere:0,0,10,10"]

# static members: name -> options
FAMILY = {
    "roller 30°, shear 0.22": ROLLER,
    "roller 30°, shear -0.22": ROLLER + ["-traction_bottom", "-66,0,300"],
    "roller 0°, shear -0.22": ROLLER + ["-obstacle_top", axis(0), "-traction_bottom", "-66,0,300"],
    "roller 45°, shear 0.22 along y": ROLLER + ["-obstacle_top", axis(45), "-traction_bottom", "0,66,300"],
    "roller 60°, shear 0.4": ROLLER + ["-obstacle_top", axis(60), "-traction_bottom", "120,0,300"],
    "roller 30°, shear along the axis": ROLLER + ["-traction_bottom", "57.2,33,300"],
    "roller 30°, k = 1e-3": ROLLER + ["-spring_bottom", "1e-3"],
    "roller 30°, k = 1e-1": ROLLER + ["-spring_bottom", "1e-1"],
    "roller 30°, k = 1e2": ROLLER + ["-spring_bottom", "1e2"],
    "roller 30°, phi = 0.1 (slides)": ROLLER + ["-friction_top", "0.1"],
    "roller 30°, phi = 0.3": ROLLER + ["-friction_top", "0.3"],
    "roller 30°, phi = 1": ROLLER + ["-friction_top", "1"],
    "roller 30°, phi = 2": ROLLER + ["-friction_top", "2"],
    "ball, phi = 0.3, shear 0.22": BALL + ["-friction_top", "0.3"],
    "ball, phi = 0.1, shear 0.22 (slides)": BALL + ["-friction_top", "0.1"],
    "ball, phi = 2, shear 0.3 diagonal": BALL + ["-friction_top", "2", "-traction_bottom", "64,64,300"],
    "ball, k = 1e-3, phi = 0.5": BALL + ["-spring_bottom", "1e-3"],
    "ball, k = 1e-3, sheared obliquely": BALL + ["-spring_bottom", "1e-3", "-traction_bottom", "40,25,300"],
    "slider (pair), phi = 0.5": scene("slider"),
    "slider (pair), phi = 0.9 (sticks)": scene("slider") + ["-friction_slider_bottom", "0.9"],
    "mindlin (pair), Q = 0.5 phi P": scene("mindlin"),
    "mindlin (pair), Q = 0.9 phi P, phi = 0.1": scene("mindlin") + ["-friction_cap", "0.1", "-traction_block_top", "-3.534,0,0"],
}

# a block 1 x 1 x 0.5 (meshes/block.geo, level 2) on the plane z = 0, held sideways only by a spring on its top
# (k = 1000 per unit area): nearly rigid against it (E = 2e8, E/k = 2e5)
BLOCK = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2e8", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom"]
# pressed by P = 1, held there while the plane moves by d1 along x (it drags the block until the spring holds phi P)
# and then back to d2
def dragged(d1, d2):
    return BLOCK + ["-friction_bottom", "0.5", "-traction_top", history((0, 0, 0), (0, 0, -1)),
                    "-obstacle_bottom_motion", history((0, 0, 0), (0, 0, 0), (d1, 0, 0), (d2, 0, 0))]


# load-path members: name -> options
PATHS = {
    "block on a spring: press, shear 1.5 phi P, release, reverse, release (the README's)":
        BLOCK + ["-friction_bottom", "0.5", "-traction_top", history((0, 0, 0), (0, 0, -10), (7.5, 0, -10), (0, 0, -10), (-7.5, 0, -10), (0, 0, -10))],
    "stiff block, loads of order 1: press, shear both ways past sliding, release to zero, 20 steps":
        BLOCK + ["-friction_bottom", "0.4", "-traction_top", history((0, 0, 0), (0, 0, -1), (0.6, 0, -1), (0, 0, -1), (-0.6, 0, -1), (0, 0, -1), (0, 0, 0)),
                 "-steps", "20"],
    "plane drags a block forward, then back: it sticks and returns": dragged(0.002, 0.0015),
    "plane drags a block forward, then further back: it slides back": dragged(0.002, 0.0005),
    "plane drags a block forward and back in 8 steps": dragged(0.002, 0.0015) + ["-steps", "8"],
    "tilted roller: press, shear 0.22 P, reverse, release": ROLLER + ["-traction_bottom", history((0, 0, 0), (0, 0, 300), (66, 0, 300), (-66, 0, 300), (0, 0, 300))],
    "ball, k = 1e-3: press, shear obliquely, reverse": BALL + ["-spring_bottom", "1e-3", "-traction_bottom", history((0, 0, 0), (0, 0, 300), (40, 25, 300), (-40, -25, 300))],
    "ball pressed 0.02 into a held block, then lifted off, 8 steps": ["-geo", "meshes/indent.geo", "-level", "1", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "bottom",
        "-contact", "top", "-obstacle_top", "sphere:0,0,10,10", "-friction_top", "0.5", "-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (0, 0, 0.01)), "-steps", "8"],
    "cylinder pressed 0.02 into a held block, rolled forward and back by 0.01, 8 steps": ["-geo", "meshes/roller.geo", "-level", "1", "-E", "2.1e5", "-nu", "0.3",
        "-dirichlet", "bottom", "-contact", "top", "-obstacle_top", "cylinder:0,0,10,0,1,0,10", "-friction_top", "0.5",
        "-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (0.01, 0, -0.02), (-0.01, 0, -0.02), (0, 0, -0.02)), "-steps", "8"],
    # 1.3 phi N: it slides by 0.15 on its spring; at 1.6 phi N (0.3) large sliding takes it to the base's rim
    "slider (pair): push past sliding, release, reverse, release":
        scene("slider") + ["-traction_slider_top", history((0, 0, 0), (0, 0, -0.01), (0.0065, 0, -0.01), (0, 0, -0.01), (-0.0065, 0, -0.01), (0, 0, -0.01))],
    "mindlin (pair): P, then Q = 0.5 phi P forth and back, 4 steps per branch": mindlin_scene_args(1, 0.5, ROOT, steps_per_branch=4),
}


# large sliding: the slab of scenes/drag.opts (4 x 1 x 0.5, held at its bottom, level 1) with a ball (R = 1), a cylinder
# (R = 1, along y) or a flat punch (0.4 x 0.4) pressed into it and dragged along x by several of their sizes, and back;
# the block of scenes/track.opts slid across the long one by twice its length, and back (not past the base's end: a
# slave node beyond the master's rim meets its edge, where the measured normal turns and the step does not settle)
DRAG = scene("drag")
CYLINDER = DRAG + ["-obstacle_top", "cylinder:0.5,0,1,0,1,0,1"]
PUNCH = scene("punch")
TRACK = scene("track")
SLIDING = {
    "ball dragged by two radii (scenes/drag.opts)": DRAG,
    "ball dragged forward by 2 and back by 2, 40 steps": DRAG + ["-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (1, 0, -0.02), (2, 0, -0.02), (1, 0, -0.02), (0, 0, -0.02)), "-steps", "40"],
    "ball dragged diagonally by 1.5, phi = 0.6": DRAG + ["-friction_top", "0.6", "-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (0.75, 0.2, -0.02), (1.5, 0.4, -0.02)), "-steps", "24"],
    "cylinder slid across its axis by 2": CYLINDER + ["-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.01), (1, 0, -0.01), (2, 0, -0.01)), "-steps", "24"],
    "cylinder slid forward by 1.5 and back by 1.5": CYLINDER + ["-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.01), (1.5, 0, -0.01), (0, 0, -0.01)), "-steps", "24"],
    "punch dragged off the slab's end (scenes/punch.opts)": PUNCH,
    "punch dragged along the slab by 1 and back": PUNCH + ["-obstacle_top_motion", "0:2,0,0.001;1:2,0,-0.002;2:3,0,-0.002;3:2,0,-0.002", "-steps", "21"],
    "block slid across a block by twice its length (scenes/track.opts)": TRACK,
    "block slid across a block, dual mortar": TRACK + ["-pair_discretization", "dual_mortar"],
    "block slid forward by 1 and back by 0.5": TRACK + ["-traction_slider_top", history((0, 0, 0), (0, 0, -0.01), (1.005, 0, -0.01), (0.495, 0, -0.01)), "-steps", "24"],
}


SLOPE = scene("slope") + ["-level", "4"]
TAN = math.tan(math.radians(20))
DOWNHILL = (math.cos(math.radians(20)), 0, -math.sin(math.radians(20)))
SQUEEZE = scene("squeeze")
SLIDER = ["-geo", "meshes/slider.geo", "-level", "1", "-E", "1", "-nu", "0.3", "-dirichlet", "bottom", "-contact", "slider_bottom",
          "-contact_pair_slider_bottom", "base_top", "-friction_slider_bottom", "0.5"]
EARLY = 30  # seconds: a run without equilibrium stops within this, mesh and set-up included


def push(pressure):
    return "%g,0,%g" % (pressure * DOWNHILL[0], pressure * DOWNHILL[2])


# floating members: name -> (options, whether an equilibrium exists)
FLOATING = {
    "slope, phi = 0 (frictionless)": (SLOPE + ["-friction_bottom", "0"], False),
    "slope, phi / tan a = 0.5": (SLOPE + ["-friction_bottom", str(0.5 * TAN)], False),
    "slope, phi / tan a = 0.9": (SLOPE + ["-friction_bottom", str(0.9 * TAN)], False),
    "slope, phi / tan a = 0.999": (SLOPE + ["-friction_bottom", str(0.999 * TAN)], False),
    "slope, phi / tan a = 1.001": (SLOPE + ["-friction_bottom", str(1.001 * TAN)], True),
    "slope, phi / tan a = 1.02": (SLOPE + ["-friction_bottom", str(1.02 * TAN)], True),
    "slope, phi / tan a = 1.2": (SLOPE + ["-friction_bottom", str(1.2 * TAN)], True),
    "slope, phi / tan a = 1.37 (scene)": (SLOPE, True),
    "slope, phi / tan a = 3": (SLOPE + ["-friction_bottom", str(3 * TAN)], True),
    "slope, pushed downhill 400 Pa (holds)": (SLOPE + ["-traction_top", push(400)], True),
    "slope, pushed downhill 800 Pa (slides)": (SLOPE + ["-traction_top", push(800)], False),
    "stack, phi = 0.5": (scene("stack"), True),
    "stack, frictionless (least norm)": (scene("stack") + ["-snes_ssstar_friction", "0"], True),
    "stack, lid pushed by 0.4 of its weight": (scene("stack") + ["-traction_top", "1962,0,0"], True),
    "stack, lid pushed by 0.6 of its weight": (scene("stack") + ["-traction_top", "2943,0,0"], False),
    "squeeze, frictionless": (SQUEEZE, True),
    # two steps: with friction the path matters, and in one step the dense route halves it where the whole body does not
    "squeeze, phi = 0.3, two steps": (SQUEEZE + ["-friction_law_bottom_cap", "coulomb", "-friction_law_top_cap", "coulomb", "-snes_ssstar_friction", "0.3", "-steps", "2"], True),
    "slider (pair), push 0.8 of phi N (holds)": (SLIDER + ["-traction_slider_top", "0.004,0,-0.01"], True),
    "slider (pair), push 1.6 of phi N": (SLIDER + ["-traction_slider_top", "0.008,0,-0.01"], False),
}


ROD = ["-geo", "meshes/rod.geo", "-level", "2", "-E", "1", "-nu", "0", "-density", "1", "-dynamics", "-contact", "tip",
       "-friction_law_tip", "none", "-end_time", "3"]
DROP = ["-geo", "meshes/hertz.geo", "-level", "1", "-E", "1e4", "-nu", "0.3", "-density", "1", "-dynamics", "-contact", "cap",
        "-friction_law_cap", "none", "-end_time", "1.8", "-steps", "24"]
SLOPED = ["-geo", "meshes/incline.geo", "-level", "2", "-E", "1e7", "-nu", "0.3", "-density", "1000", "-gravity", "0,0,-9.81",
          "-contact", "bottom", "-obstacle_bottom", "0,0,0,0.3420201433256687,0,0.9396926207859084", "-dynamics", "-damping", "0,0.003",
          "-end_time", "1", "-steps", "100"]

# dynamics members: name -> options
DYNAMICS = {
    "rod on a wall, v0 0.01, 40 elements, 120 steps": ROD + ["-initial_velocity", "0,0,-0.01", "-steps", "120"],
    "rod on a wall, v0 0.1": ROD + ["-initial_velocity", "0,0,-0.1", "-steps", "120"],
    "rod on a wall, 60 steps (2 elements a step)": ROD + ["-initial_velocity", "0,0,-0.01", "-steps", "60"],
    "rod on a wall, 80 elements, 240 steps": ROD + ["-initial_velocity", "0,0,-0.01", "-steps", "240", "-level", "4"],
    "rod on a wall, lumped mass": ROD + ["-initial_velocity", "0,0,-0.01", "-steps", "120", "-dynamics_mass", "lumped"],
    "ball dropped, v0 0.3": DROP + ["-initial_velocity", "0,0,-0.3"],
    "ball dropped, v0 0.1": DROP + ["-initial_velocity", "0,0,-0.1"],
    "slope released, phi / tan a = 0.5": SLOPED + ["-friction_bottom", str(0.5 * TAN)],
    "slope released, phi / tan a = 0.9": SLOPED + ["-friction_bottom", str(0.9 * TAN)],
    "slope released, phi / tan a = 1.1": SLOPED + ["-friction_bottom", str(1.1 * TAN)],
    "slope released, phi / tan a = 2": SLOPED + ["-friction_bottom", str(2 * TAN)],
    "block on a belt (scenes/belt.opts)": scene("belt"),
    "stack of floating bodies dropped into place": scene("stack") + ["-level", "1", "-dynamics", "-damping", "0,1e-3", "-end_time", "0.2", "-steps", "20"],
}


def dynamics_error(reference, h5):
    """the largest difference of the displacement and velocity fields and the normal force over the steps, each
    relative to its largest over the reference's path; and the energy gained (energy_error over the energy scale)"""
    import h5py
    import numpy as np

    a, b = h5py.File(reference, "r"), h5py.File(h5, "r")
    steps = sorted((k for k in a["steps"] if k.isdigit()), key=int)
    if sorted((k for k in b["steps"] if k.isdigit()), key=int) != steps:
        return float("inf"), float("inf")
    order = lambda f: np.lexsort(f["geometry/vertices"][:].T[::-1])  # noqa: E731 (the partition orders the vertices)
    oa, ob = order(a), order(b)
    error = 0.0
    for field in ("displacement", "velocity"):
        x = np.array([a["steps/%s/fields/%s" % (k, field)][:][oa] for k in steps])
        y = np.array([b["steps/%s/fields/%s" % (k, field)][:][ob] for k in steps])
        error = max(error, np.abs(x - y).max() / max(np.abs(x).max(), 1e-300))
    N, M = a["steps/normal_force"][:], b["steps/normal_force"][:]
    error = max(error, np.abs(N - M).max() / max(np.abs(N).max(), 1e-300))
    st = b["steps"]
    scale = max(np.abs(st["kinetic_energy"][:]).max(), np.abs(st["external_work"][:]).max(), np.abs(st["strain_energy"][:]).max(), 1e-300)
    return error, st["energy_error"][:].max() / scale


# the law's degenerate points (issue 34): steps that land exactly on a kink of the law, where the semismooth* Newton
# step's blocks are ambiguous and strict complementarity fails (docs/derivation.md section 19, docs/guide/kinks.md).
# The block of BLOCK (level 2, 1 x 1 x 0.5 on the plane z = 0) on a spring of k per unit area on its top, E = 2e8
# (stiff: E/k = 5e6 and 1e7) or 1e6 (soft), pressed by 1 against phi = 0.5
def block(E, k, level="2"):
    return ["-geo", "meshes/block.geo", "-level", level, "-E", E, "-nu", "0.3", "-spring_top", k, "-contact", "bottom", "-friction_bottom", "0.5"]


# pressed, sheared to 0.8 > phi P (it slides until the spring holds 0.3), released, sheared back, released: in 20 steps
# the step t = 3.25 lands exactly on the onset of sliding back (the shear -0.2 plus the spring's 0.3 is phi P = 0.5)
BACK = ["-traction_top", history((0, 0, 0), (0, 0, -1), (0.8, 0, -1), (0, 0, -1), (-0.8, 0, -1), (0, 0, -1)), "-steps", "20"]
DEGENERATE = {
    "onset of sliding back, stiff (E/k = 5e6), 20 steps (issue 34's)": block("2e8", "40") + BACK,
    "onset of sliding back, stiff (E/k = 1e7), 20 steps": block("2e8", "20") + BACK,
    "onset of sliding back, stiffer (E/k = 2e7), level 1, 20 steps": block("2e8", "10", level="1") + BACK,
    "onset of sliding back, soft (E/k = 2.5e4), 20 steps": block("1e6", "40") + BACK,
    "onset of sliding, static: sheared by exactly phi P, stiff (E/k = 1e7)": block("2e8", "20") + ["-traction_top", "0.5,0,-1"],
    "onset of sliding, static: sheared by exactly phi P, soft": block("1e6", "40") + ["-traction_top", "0.5,0,-1"],
    "onset of sliding on a path: pressed, sheared to exactly phi P in 4 steps, stiff (E/k = 1e7)":
        block("2e8", "20") + ["-traction_top", history((0, 0, 0), (0, 0, -1), (0.5, 0, -1)), "-steps", "4"],
    # the plane drags the block (BLOCK: k = 1000, E/k = 2e5) by exactly phi P/k: the spring holds exactly phi P
    "onset of sliding under displacement control: the plane moved by exactly phi P/k, then back": dragged(0.0005, 0),
    "touching, static: zero gap, no normal load, sheared by 0.1, stiff (E/k = 1e7)": block("2e8", "20") + ["-traction_top", "0.1,0,0"],
    "touching, static: zero gap, no normal load, sheared by 0.1, soft": block("1e6", "40") + ["-traction_top", "0.1,0,0"],
    # the plane 0.001 below the block raised by exactly its gap (touching, no force), then the block sheared, then pressed
    "touching on a path: the plane raised by exactly its gap, the block sheared, then pressed, stiff (E/k = 1e7)":
        block("2e8", "20") + ["-obstacle_bottom", "0,0,-0.001,0,0,1", "-obstacle_bottom_motion", history((0, 0, 0), (0, 0, 0.001), (0, 0, 0.001), (0, 0, 0.0011)),
                              "-traction_top", history((0, 0, 0), (0, 0, 0), (0.1, 0, 0), (0.1, 0, 0))],
    "release on a path: pressed, sheared by 0.3, the normal load released to exactly 0, pressed again, stiff (E/k = 1e7)":
        block("2e8", "20") + ["-traction_top", history((0, 0, 0), (0, 0, -1), (0.3, 0, -1), (0.3, 0, 0), (0.3, 0, -1))],
    "release on a path: a ball pressed 0.02 into a held block and lifted back to exactly touching, 4 steps": ["-geo", "meshes/indent.geo", "-level", "1", "-E", "2.1e5",
        "-nu", "0.3", "-dirichlet", "bottom", "-contact", "top", "-obstacle_top", "sphere:0,0,10,10", "-friction_top", "0.5",
        "-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (0, 0, 0)), "-steps", "4"],
}


# finite strain (issue 33, docs/guide/large-deformation.md): hyperelastic bodies, solved on the whole body (the default;
# the dense route is refused by name: the Schur complement would be computed again at every iterate). The unit cube
# (meshes/cube.geo level 1, E = 1000, nu = 0.3) on the frictionless plane z = 0, held on its planes of symmetry x = 0
# and y = 0, its top moved down (uniaxial stress: the top's reaction has a closed form, docs/derivation.md (18.6)); the
# neo-Hookean block of meshes/indent.geo pushed by its bottom into the rigid ball of radius 10 (first step deep, and on
# a path); the neo-Hookean cube pressed 20 % onto the plane with phi = 0.3 and dragged by its top sideways by 3 (three
# times its width: every node slides across the plane, the contact measured in the current configuration at every
# iterate); a prescribed rotation of 90 degrees (no stress: a closed form), free and standing on the plane
def compressed(model, *strains):
    """the cube compressed to the strains (one step each), its top's z prescribed"""
    knots = "0:free,free,0;" + ";".join("%d:free,free,%g" % (k + 1, -d) for k, d in enumerate(strains))
    return (["-geo", "meshes/cube.geo", "-level", "1", "-E", "1000", "-nu", "0.3", "-material_model", model, "-contact", "bottom",
             "-friction_law_bottom", "none", "-displacement_left", "0,free,free", "-displacement_front", "free,0,free", "-displacement_top", knots],
            ("uniaxial", model, (0.0,) + strains))


INDENT = ["-geo", "meshes/indent.geo", "-level", "1", "-E", "1000", "-nu", "0.3", "-material_model", "neo_hookean", "-contact", "top",
          "-obstacle_top", "sphere:0,0,10,10"]
ROTATED = ["-geo", "meshes/cube.geo", "-level", "1", "-E", "1000", "-nu", "0.3", "-rotation_center_top", "0.5,0.5,1",
           "-rotation_top", "0:0,0,0;1:0,0,30;2:0,0,60;3:0,0,90"]
# name -> (options, the closed form: ("uniaxial", model, the strains of the steps) or ("rigid",) or None)
FINITE_STRAIN = {
    "compression 10, 30, 50 %, neo-Hookean": compressed("neo_hookean", 0.1, 0.3, 0.5),
    # past its limit point (42 %) Saint Venant-Kirchhoff's tangent is indefinite and its equilibria not unique: the
    # homogeneous one with exact Newton steps (MUMPS' LU), another one by the default Krylov solver (GMRES after CG
    # found the matrix indefinite): the closed form and the reference differ there
    "compression 10, 30, 50 %, Saint Venant-Kirchhoff, -pc_type lu": (compressed("saint_venant_kirchhoff", 0.1, 0.3, 0.5)[0] + ["-pc_type", "lu", "-pc_factor_mat_solver_type", "mumps"],
                                                                      compressed("saint_venant_kirchhoff", 0.1, 0.3, 0.5)[1]),
    "compression 10, 30, 50 %, Saint Venant-Kirchhoff, the defaults (past its limit point)": compressed("saint_venant_kirchhoff", 0.1, 0.3, 0.5),
    "compression 50 % in one step, neo-Hookean": compressed("neo_hookean", 0.5),
    "compression 30 % in one step, Saint Venant-Kirchhoff": compressed("saint_venant_kirchhoff", 0.3),
    "block pushed 1.0 into a ball in one step (first step deep), frictionless": (INDENT + ["-friction_law_top", "none", "-displacement_bottom", "0:0,0,0;1:0,0,1"], None),
    "block pushed 0.25 into a ball in one step, frictionless": (INDENT + ["-friction_law_top", "none", "-displacement_bottom", "0:0,0,0;1:0,0,0.25"], None),
    "block pushed into a ball by 0.5, 1, 1.5 (a path), phi = 0.3": (INDENT + ["-friction_top", "0.3", "-displacement_bottom", "0:0,0,0;1:0,0,0.5;2:0,0,1;3:0,0,1.5"], None),
    "cube pressed 20 %, dragged sideways by 3 (3 widths), phi = 0.3, 13 steps": (["-geo", "meshes/cube.geo", "-level", "1", "-E", "1000", "-nu", "0.3",
        "-material_model", "neo_hookean", "-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", history((0, 0, 0), (0, 0, -0.2), (3, 0, -0.2)),
        "-steps", "13"], None),
    # below the lid's shear buckling under its dead load (about mu A = 0.5: at 0.5 E its equilibria are not unique, at
    # 0.8 E there is none near the flat one)
    "patch (pair): the lid (E = 1, nu = 0) pressed by a dead pressure 0.3 E, neo-Hookean": (scene("patch") + ["-material_model", "neo_hookean", "-traction_top", "0,0,-0.3"], None),
    "rotation 90 degrees in 3 steps, free (Newton's method, no contact)": (ROTATED + ["-material_model", "neo_hookean"], ("rigid",)),
    "rotation 90 degrees in 3 steps, standing on the frictionless plane, Saint Venant-Kirchhoff":
        (ROTATED + ["-material_model", "saint_venant_kirchhoff", "-contact", "bottom", "-friction_law_bottom", "none"], ("rigid",)),
}


def closed_form_error(h5, exact):
    """the largest error over the steps to the closed form: the top's reaction against P_33 A of uniaxial stress
    (relative), or the Cauchy stress of a rigid rotation (relative to E = 1000)"""
    import h5py
    import numpy as np
    from suite_hyperelastic import uniaxial

    f = h5py.File(h5, "r")
    if exact[0] == "rigid":
        return max(np.abs(f["steps/%s/fields/stress" % k][:]).max() / 1000 for k in f["steps"] if k.isdigit())
    top = f["steps/groups/top/reaction"][:]
    return max(abs(top[k][2] - uniaxial(exact[1], 1 - d)[1]) / max(abs(uniaxial(exact[1], 1 - d)[1]), 1e-300) if d else abs(top[k][2])
               for k, d in enumerate(exact[2]))


def displacement_error(reference, h5):
    """the largest difference of the displacement fields over the steps, relative to the reference's largest"""
    import h5py
    import numpy as np

    a, b = h5py.File(reference, "r"), h5py.File(h5, "r")
    order = lambda f: np.lexsort(f["geometry/vertices"][:].T[::-1])  # noqa: E731 (the partition orders the vertices)
    oa, ob = order(a), order(b)
    steps = sorted((k for k in a["steps"] if k.isdigit()), key=int)
    x = np.array([a["steps/%s/fields/displacement" % k][:][oa] for k in steps])
    y = np.array([b["steps/%s/fields/displacement" % k][:][ob] for k in steps])
    return np.abs(x - y).max() / max(np.abs(x).max(), 1e-300)


def run_finite_strain(name, member, ranks):
    """the whole body on the ranks against the reference (the whole body on one rank at -snes_rtol 1e-13) and the
    closed form where there is one; the dense route must be refused by name (a scene with contact) or is not used"""
    options, exact = member
    files = {p: os.path.join(OUT, "%s_%s_%d.h5" % (tag(name), p, ranks)) for p in ("direct", "none")}
    if name not in REFERENCES:
        reference = os.path.join(OUT, "%s_reference.h5" % tag(name))
        path = "none" if "-contact" in options or "-options_file" in options else None
        REFERENCES[name] = reference if solve(options, path, 1, reference, ("-snes_rtol", "1e-13"))["reason"].startswith("CONVERGED") else None
    result = {}
    if "-contact" in options or "-options_file" in options:  # the scenes have contact
        cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), CONTACT] + options + ["-snes_ssstar_reduction", "direct", "-o", files["direct"]]
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env(), timeout=TIMEOUT)
        refused = p.returncode != 0 and "is solved on the whole body" in p.stdout and not os.path.exists(files["direct"])
        result["direct"] = {"iters": 0, "reason": "refused by name" if refused else "NOT REFUSED", "krylov": None, "law": None, "error": None, "refused": refused}
    r = solve(options, "none" if "direct" in result else None, ranks, files["none"])
    if REFERENCES[name] is None:
        r["reason"] += " (no reference)"
    result["none"] = checked(dict(r, options=options), files["none"], REFERENCES[name]) if REFERENCES[name] else dict(r, law=None, error=None)
    if "direct" not in result and result["none"]["law"] is not None:  # no contact: the file's checks, the displacement's error
        result["none"]["law"] = 0.0
        result["none"]["error"] = displacement_error(REFERENCES[name], files["none"])
    if exact and result["none"]["law"] is not None:
        result["none"]["exact"] = closed_form_error(files["none"], exact)
    return result


def env():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def tag(name):
    return re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")[:60]


def solve(options, path, ranks, h5, extra=()):
    """one run: its iterations (summed over the steps), reason, Krylov iterations"""
    reduction = ["-snes_ssstar_reduction", path] if path else []  # None: a scene without contact (Newton's method)
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), CONTACT] + options + reduction + ["-snes_view", "-ssstar_progress", "0", "-o", h5] + list(extra)
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env(), timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return {"iters": -1, "reason": "HUNG (killed after %d s)" % TIMEOUT, "krylov": None, "seconds": TIMEOUT, "unbalanced": False}
    m = SUMMARY.search(p.stdout)
    if not m:
        tail = p.stdout.strip().splitlines()[-1:] or ["no output"]
        return {"iters": -1, "reason": "ERROR: " + tail[0][:60], "krylov": None, "seconds": time.time() - t0, "unbalanced": False}
    krylov = [int(k) for k in KRYLOV.findall(p.stdout)]
    return {"iters": int(m.group(1)), "reason": m.group(3) if p.returncode == 0 else "%s (exit %d)" % (m.group(3), p.returncode), "krylov": sum(krylov) if krylov else None,
            "seconds": time.time() - t0, "unbalanced": p.returncode == 2 and "no equilibrium: " in p.stdout}


def checked(result, h5, reference):
    """the file's law (every step) and its error to the reference (every step)"""
    if not result["reason"].startswith("CONVERGED"):
        result.update(law=None, error=None)
        return result
    law = subprocess.run(CHECK + ["coulomb", h5, "--steps"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    result["law"] = max(float(x) for x in DISTANCE.findall(law.stdout)) if law.returncode in (0, 1) and DISTANCE.search(law.stdout) else float("inf")
    result["law_ok"] = law.returncode == 0
    if "-dynamics" in result.get("options", ()):
        result["error"], result["gain"] = dynamics_error(reference, h5)
        return result
    cmp = subprocess.run(CHECK + ["compare", reference, h5, "--steps", "--tol", str(TOLERANCE)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    found = DIFFERENCE.findall(cmp.stdout)
    result["error"] = max(float(x) for x in found) if found else float("inf")
    return result


REFERENCES = {}  # member -> its reference file, or None where it did not converge


def run_member(name, options, ranks):
    """the reference (dense, one rank, rtol 1e-13; once per member), then both paths at the defaults on the ranks"""
    files = {p: os.path.join(OUT, "%s_%s_%d.h5" % (tag(name), p, ranks)) for p in ("direct", "none")}
    if name not in REFERENCES:
        reference = os.path.join(OUT, "%s_reference.h5" % tag(name))
        REFERENCES[name] = reference if solve(options, "direct", 1, reference, ("-snes_rtol", "1e-13"))["reason"].startswith("CONVERGED") else None
    if REFERENCES[name] is None:
        return None
    return {p: checked(dict(solve(options, p, ranks, files[p]), options=options), files[p], REFERENCES[name]) for p in ("direct", "none")}


def run_unbalanced(name, options, ranks):
    """a member without equilibrium: both paths must stop before their first iteration, saying so, within EARLY s"""
    result = {}
    for p in ("direct", "none"):
        r = solve(options, p, ranks, os.path.join(OUT, "%s_%s_%d.h5" % (tag(name), p, ranks)))
        r["early"] = r["unbalanced"] and r["iters"] == 0 and r["reason"].startswith("DIVERGED_DTOL") and r["seconds"] <= EARLY
        r.update(law=None, error=None)
        result[p] = r
    return result


def passed(r):
    if "early" in r:
        return r["early"]
    if "refused" in r:
        return r["refused"]
    return r["reason"].startswith("CONVERGED") and r.get("law_ok") and r["error"] <= TOLERANCE and r.get("gain", 0.0) <= 1e-9


def cell(r):
    if "early" in r:
        return "%s, %d its, %.1f s%s" % ("no equilibrium" if r["unbalanced"] else r["reason"], r["iters"], r["seconds"], "" if r["early"] else " NOT EARLY")
    if "refused" in r:
        return r["reason"]
    if r["law"] is None:
        return "%d, %s" % (r["iters"], r["reason"])
    krylov = "" if r["krylov"] is None else " (%d)" % r["krylov"]
    gain = "" if "gain" not in r else ", energy %+.1e%s" % (r["gain"], "" if r["gain"] <= 1e-9 else " GAINED")
    exact = "" if "exact" not in r else ", closed form %.1e%s" % (r["exact"], "" if r["exact"] <= TOLERANCE else " OFF")
    return "%d%s, law %.1e%s, error %.1e%s%s" % (r["iters"], krylov, r["law"], "" if r["law_ok"] else " VIOLATED", r["error"], gain, exact)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--family", choices=("static", "paths", "sliding", "floating", "degenerate", "dynamics", "finite_strain", "all"), default="all")
    parser.add_argument("--ranks", default="1,2,3,4")
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    ranks = [int(r) for r in args.ranks.split(",")]
    floating = {name: options for name, (options, exists) in FLOATING.items() if exists}
    families = [(f, m) for f, m in (("static", FAMILY), ("paths", PATHS), ("sliding", SLIDING), ("floating", floating), ("degenerate", DEGENERATE), ("dynamics", DYNAMICS), ("finite_strain", FINITE_STRAIN)) if args.family in (f, "all")]
    print("| family | member | ranks | dense route: its, law, error | whole body: its (Krylov), law, error |")
    print("|---|---|---|---|---|")
    rows, total, converged, lawful, exact, unbalanced, early, refusals, refused = [], 0, 0, 0, 0, 0, 0, 0, 0
    for name, (options, exists) in FLOATING.items():  # the members without equilibrium: stopped early
        if exists or args.family not in ("floating", "all") or args.only not in name:
            continue
        for r in ranks:
            result = run_unbalanced(name, options, r)
            print("| floating | %s | %d | %s | %s |" % (name, r, cell(result["direct"]), cell(result["none"])), flush=True)
            for path, res in result.items():
                unbalanced += 1
                early += res["early"]
                rows.append(["floating", name, r, path, res["iters"], res["krylov"], res["reason"], None, None, res["early"]])
    for family, members in families:
        for name, options in members.items():
            if args.only not in name:
                continue
            for r in ranks:
                result = run_finite_strain(name, options, r) if family == "finite_strain" else run_member(name, options, r)
                if result is None:
                    print("| %s | %s | %d | the reference did not converge | |" % (family, name, r), flush=True)
                    total += 1 if family == "finite_strain" else 2
                    continue
                print("| %s | %s | %d | %s | %s |" % (family, name, r, cell(result["direct"]) if "direct" in result else "not used (no contact)", cell(result["none"])), flush=True)
                for path, res in result.items():
                    rows.append([family, name, r, path, res["iters"], res["krylov"], res["reason"], res["law"], res["error"], passed(res)])
                    if "refused" in res:  # the dense route of a nonlinear residual: refused by name (finite_strain)
                        refusals += 1
                        refused += res["refused"]
                        continue
                    total += 1
                    converged += res["reason"].startswith("CONVERGED")
                    lawful += bool(res.get("law_ok"))
                    exact += res["error"] is not None and res["error"] <= TOLERANCE and res.get("exact", 0.0) <= TOLERANCE
    with open(os.path.join(ROOT, "bench", "output", "robust.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["family", "member", "ranks", "path", "iterations", "krylov", "reason", "law", "error", "passed"])
        w.writerows(rows)
    print("%d members x ranks: converged %d of %d runs, the law holds in %d, within %g of the exact solution %d" % (len({(row[1], row[2]) for row in rows if row[0] != "floating"}), converged, total, lawful, TOLERANCE, exact))
    if unbalanced:
        print("%d members x ranks without equilibrium: stopped early in %d of %d runs" % (unbalanced // 2, early, unbalanced))
    if refusals:
        print("%d runs of the dense route on a nonlinear residual: refused by name in %d" % (refusals, refused))
    sys.exit(0 if converged == lawful == exact == total and early == unbalanced and refused == refusals else 1)


if __name__ == "__main__":
    main()
