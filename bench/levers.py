#!/usr/bin/python3
"""The levers of the whole-body path (-snes_ssstar_reduction none) measured side by side: examples/prism at each level
with one configuration after another (options added to the default), the configurations interleaved within every
repeat (their order rotated from repeat to repeat) so that a noisy spell of the shared machine hits them all, and the
AMG yardstick measured in the same repeat (bench/yardstick: one CG + GAMG solve of K, set-up + solve).

  bench/levers.py [--levels 8,12,16] [--ranks 2] [--repeat 3] [--set sweep|round2|round3|round4|nested|scale|krylov|rate|default] [--only "a;b;..."]
                  [--config name='-opt value ...'] [--extra '-opt value']

Per level and configuration, medians over the repeats: the whole run (the process's wall time, mesh to the -o file),
its ratio to the default configuration of the same repeats (the machine divided out), whole / yardstick, the phases of
-log_view (mesh, of it DMPlexInterpolate, assembly, SNESSolve; in it the Newton matrices, the multigrid set-ups and
the Krylov solves), the Newton iterations, the linear solves, the Krylov iterations per solve, the preconditioner
set-ups and the peak memory of the largest rank. And the checks against the default configuration of the first
repeat: converged, the same contact states, the displacement within 1e-8 (max |u - u_default| / max |u_default|).
Writes bench/output/levers.csv (one row per level and configuration) and levers.png (time and Krylov iterations
relative to the default). With --set rate (and no --only), each level starts with the levers on K alone: CG
iterations, set-up and solve flops and the peak of bench/yardstick's AMG solve of K with each (flops and iterations
are what the machine's load does not change; docs/guide/scale.md, "The multigrid's rate")."""
import argparse
import csv
import math
import os
import re
import resource
import shlex
import statistics
import subprocess
import sys
import time

from table2 import level_list, mpiexec, yardstick  # the same runs and yardstick as Table 2

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
WORK = os.path.join(OUT, "levers")

HYPRE = "-pc_type hypre -pc_hypre_type boomeramg -pc_hypre_boomeramg_coarsen_type HMIS -pc_hypre_boomeramg_interp_type ext+i -pc_hypre_boomeramg_P_max 4"
# GAMG's coarse operators have all-zero rows (aggregates too small for the six rigid-body modes): SOR divides by
# their zero diagonal unless it is shifted (the shift never acts elsewhere: those rows and columns are zero); ILU
# needs a shift for them too, and point-block Jacobi fails on their singular blocks (not in the sweep)
SOR_SHIFT = " -mg_levels_pc_sor_diagonal_shift 1e-8"
SETS = {
    "default": [("default", "")],
    "sweep": [
        ("default", ""),
        ("threshold 0", "-pc_gamg_threshold 0"),
        ("threshold 0.01", "-pc_gamg_threshold 0.01"),
        ("threshold 0.02", "-pc_gamg_threshold 0.02"),
        ("threshold 0.05", "-pc_gamg_threshold 0.05"),
        ("plain aggregation", "-pc_gamg_agg_nsmooths 0"),
        ("no square graph", "-pc_gamg_square_graph 0"),
        ("coarse 1000 eq", "-pc_gamg_coarse_eq_limit 1000"),
        ("Chebyshev 1", "-mg_levels_ksp_max_it 1"),
        ("Chebyshev 3", "-mg_levels_ksp_max_it 3"),
        ("SOR", "-mg_levels_pc_type sor" + SOR_SHIFT),
        ("SOR + Chebyshev 1", "-mg_levels_pc_type sor -mg_levels_ksp_max_it 1" + SOR_SHIFT),
        ("block Jacobi ILU", "-mg_levels_pc_type bjacobi -mg_levels_sub_pc_factor_shift_type nonzero"),
        ("ASM ILU", "-mg_levels_pc_type asm -mg_levels_sub_pc_type ilu -mg_levels_sub_pc_factor_shift_type nonzero"),
        ("no interpolation reuse", "-pc_gamg_reuse_interpolation 0"),
        ("SA eigenvalues", "-pc_gamg_use_sa_esteig 1"),
        ("BoomerAMG", HYPRE + " -pc_hypre_boomeramg_strong_threshold 0.5"),
        ("BoomerAMG nodal 0.5", HYPRE + " -pc_hypre_boomeramg_strong_threshold 0.5 -pc_hypre_boomeramg_nodal_coarsen 6 -pc_hypre_boomeramg_vec_interp_variant 2"),
        ("BoomerAMG nodal 0.7", HYPRE + " -pc_hypre_boomeramg_strong_threshold 0.7 -pc_hypre_boomeramg_nodal_coarsen 6 -pc_hypre_boomeramg_vec_interp_variant 2"),
        ("GMRES always", "-ksp_type gmres -ksp_pc_side right -ksp_norm_type unpreconditioned -ksp_gmres_restart 100"),
        ("eta_max 0.3", "-snes_ssstar_ksp_rtol_max 0.3"),
        ("eta_max 0.03", "-snes_ssstar_ksp_rtol_max 0.03"),
        ("pc_reuse 0", "-snes_ssstar_pc_reuse 0"),
        ("pc_reuse 0.6", "-snes_ssstar_pc_reuse 0.6"),
        ("pc_reuse 1", "-snes_ssstar_pc_reuse 1"),
    ],
}
# the second round: what helped at level 8 (Krylov iterations, set-up work), alone and combined
SOR = "-mg_levels_pc_type sor" + SOR_SHIFT
SETS["round2"] = [c for c in SETS["sweep"] if c[0] in (
    "default", "threshold 0.01", "plain aggregation", "coarse 1000 eq", "Chebyshev 1", "Chebyshev 3", "SOR", "SOR + Chebyshev 1",
    "block Jacobi ILU", "ASM ILU", "no interpolation reuse", "eta_max 0.3", "pc_reuse 0.6", "pc_reuse 1")] + [
    ("SOR + coarse 1000 eq", SOR + " -pc_gamg_coarse_eq_limit 1000"),
    ("SOR + plain aggregation", SOR + " -pc_gamg_agg_nsmooths 0"),
    ("SOR + threshold 0.01", SOR + " -pc_gamg_threshold 0.01"),
    ("SOR + pc_reuse 0.6", SOR + " -snes_ssstar_pc_reuse 0.6"),
    ("SOR + eta_max 0.3", SOR + " -snes_ssstar_ksp_rtol_max 0.3"),
]
# the third round: SOR as a Richardson smoother (one or two sweeps, no Chebyshev: no residual of its own, no eigenvalue
# estimates), alone and with what cuts the set-ups
RSOR = "-mg_levels_ksp_type richardson -mg_levels_pc_type sor" + SOR_SHIFT
SETS["round3"] = [c for c in SETS["round2"] if c[0] in ("default", "no interpolation reuse", "SOR + pc_reuse 0.6", "SOR + plain aggregation")] + [
    ("Richardson SOR", RSOR + " -mg_levels_ksp_max_it 1"),
    ("Richardson SOR 2", RSOR + " -mg_levels_ksp_max_it 2"),
    ("Richardson SOR + plain aggregation", RSOR + " -mg_levels_ksp_max_it 1 -pc_gamg_agg_nsmooths 0"),
    ("Richardson SOR 2 + plain aggregation", RSOR + " -mg_levels_ksp_max_it 2 -pc_gamg_agg_nsmooths 0"),
    ("Richardson SOR + no interpolation reuse", RSOR + " -mg_levels_ksp_max_it 1 -pc_gamg_reuse_interpolation 0"),
    ("Richardson SOR + pc_reuse 0.6", RSOR + " -mg_levels_ksp_max_it 1 -snes_ssstar_pc_reuse 0.6"),
]
# Rounds 1-3 were measured with GAMG's own smoothers (two Chebyshev steps preconditioned by Jacobi) as the default:
# they run on that base now that ssstar's default is one SOR sweep (an option given twice: the later one counts)
GAMG_SMOOTHERS = "-mg_levels_ksp_type chebyshev -mg_levels_pc_type jacobi -mg_levels_ksp_max_it 2 "
for name in ("sweep", "round2", "round3"):
    SETS[name] = [(n, GAMG_SMOOTHERS + o) for n, o in SETS[name]]
# the fourth round, on the default of one SOR sweep: GAMG's smoothers against it, and the levers around it
SETS["round4"] = [
    ("default", ""),
    ("GAMG's Chebyshev/Jacobi", GAMG_SMOOTHERS),
    ("SOR 2 sweeps", "-mg_levels_ksp_max_it 2"),
    ("no interpolation reuse", "-pc_gamg_reuse_interpolation 0"),
    ("pc_reuse 0.6", "-snes_ssstar_pc_reuse 0.6"),
    ("pc_reuse 0.1", "-snes_ssstar_pc_reuse 0.1"),
    ("eta_max 0.3", "-snes_ssstar_ksp_rtol_max 0.3"),
    ("threshold 0.01", "-pc_gamg_threshold 0.01"),
    ("coarse 1000 eq", "-pc_gamg_coarse_eq_limit 1000"),
]
# the fifth round: nested iteration (-nested_levels: coarser meshes solved first; auto, the default, by the size)
SETS["nested"] = [
    ("default", ""),
    ("no nesting", "-nested_levels 0"),
    ("nested 1", "-nested_levels 1"),
    ("nested 2", "-nested_levels 2"),
    ("nested 3", "-nested_levels 3"),
    ("plain aggregation", "-pc_gamg_agg_nsmooths 0"),
    ("one multigrid", "-snes_ssstar_pc_reuse 1"),
]
# the sixth round (issue 34, docs/guide/scale.md): ssstar's multigrid defaults (plain aggregation, W-cycles on the two
# finest levels, the Galerkin products all at once) one by one against the former ones (smoothed aggregation, V-cycles,
# PETSc's scalable P^T A P), and the inexact Newton forcing on top of them
SETS["scale"] = [
    ("default", ""),
    ("former: smoothed, V, scalable PtAP", "-pc_gamg_agg_nsmooths 1 -pc_mg_cycle_type v -matptap_via scalable"),
    ("smoothed aggregation", "-pc_gamg_agg_nsmooths 1"),
    ("V-cycles", "-pc_mg_cycle_type v"),
    ("scalable PtAP", "-matptap_via scalable"),
    ("eta_max 0.3", "-snes_ssstar_ksp_rtol_max 0.3"),
    ("eta_max 0.03", "-snes_ssstar_ksp_rtol_max 0.03"),
    ("no nesting", "-nested_levels 0"),
]
# the seventh round (issue 34 item 3, docs/guide/scale.md "What the levers did"): the Krylov levers of the whole body's
# Newton steps against the default (the likely last step solved to half the stopping rule): the former floor of a
# tenth, the floor at the stopping rule itself, and the inexact forcing looser and tighter
SETS["krylov"] = [
    ("default", ""),
    ("floor 0.1 (before)", "-snes_ssstar_ksp_floor 0.1"),
    ("floor 1", "-snes_ssstar_ksp_floor 1"),
    ("eta_max 0.3", "-snes_ssstar_ksp_rtol_max 0.3"),
]
# the eighth round (h34u, docs/guide/scale.md "The multigrid's rate"): the rate of the plain-aggregation multigrid,
# first on K alone (K_ALONE: bench/yardstick's CG + GAMG solve of K with the lever, to 1e-8, the residual
# unpreconditioned as the Newton steps measure it), then in the whole prism; ranked by iterations, flops and memory,
# which the machine's load does not change
SETS["rate"] = [
    ("default", ""),
    ("no over-correction (before)", "-snes_ssstar_mg_overcorrection 1"),
    ("over-correction 1.5", "-snes_ssstar_mg_overcorrection 1.5"),
    ("over-correction 2", "-snes_ssstar_mg_overcorrection 2"),
    ("W on every level", "-snes_ssstar_mg_w_levels 99"),
    ("threshold 0.05", "-pc_gamg_threshold 0.05"),
    ("SOR 2 sweeps", "-mg_levels_ksp_max_it 2"),
]
SSSTAR_MG = ("-amg_pc_gamg_agg_nsmooths 0 -amg_mg_levels_ksp_type richardson -amg_mg_levels_pc_type sor -amg_mg_levels_ksp_max_it 1 "
             "-amg_mg_levels_pc_sor_diagonal_shift 1e-8 -amg_ksp_norm_type unpreconditioned")
K_ALONE = {"rate": [
    ("the yardstick: GAMG's defaults", ""),
    ("GAMG's defaults, unpreconditioned norm", "-amg_ksp_norm_type unpreconditioned"),
    ("smoothed, SOR 1", SSSTAR_MG.replace("-amg_pc_gamg_agg_nsmooths 0 ", "")),
    ("plain, SOR 1, V", SSSTAR_MG),
    ("plain, SOR 1, W on 2 (before)", SSSTAR_MG + " -amg_w_levels 2"),
    ("plain, W on 2, over-correction 1.5", SSSTAR_MG + " -amg_w_levels 2 -amg_overcorrection 1.5"),
    ("plain, W on 2, over-correction 1.8", SSSTAR_MG + " -amg_w_levels 2 -amg_overcorrection 1.8"),
    ("plain, W on 2, over-correction 2", SSSTAR_MG + " -amg_w_levels 2 -amg_overcorrection 2"),
    ("plain, W on all, over-correction 1.8", SSSTAR_MG + " -amg_w_levels 99 -amg_overcorrection 1.8"),
    ("plain, W on 2, threshold 0.05", SSSTAR_MG + " -amg_w_levels 2 -amg_pc_gamg_threshold 0.05"),
    ("plain, W on 2, SOR 2", SSSTAR_MG + " -amg_w_levels 2 -amg_mg_levels_ksp_max_it 2"),
    ("plain, W on 2, no square graph", SSSTAR_MG + " -amg_w_levels 2 -amg_pc_gamg_square_graph 0"),
    ("plain, W on 2, Chebyshev 2/Jacobi", SSSTAR_MG.replace("richardson", "chebyshev").replace("-amg_mg_levels_pc_type sor", "-amg_mg_levels_pc_type jacobi")
     .replace("-amg_mg_levels_ksp_max_it 1", "-amg_mg_levels_ksp_max_it 2") + " -amg_w_levels 2"),
]}
PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)")
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)", re.M)
KRYLOV = re.compile(r"last solve: (\d+) linear solves, (\d+) Krylov iterations \(\S+ per solve\), (\d+) preconditioner set-ups")
# -log_view events: name, count, ratio, max time
EVENTS = {"mesh": "SSStarMesh", "interpolate": "DMPlexInterp", "assembly": "SSStarAssembly", "snes": "SNESSolve",
          "newton_matrix": "SSStarNSAssemble", "pc_setup": "SSStarNSFactor", "krylov": "SSStarNSKrylov", "output": "SSStarOutput",
          "mesh_gmsh": "SSStarMeshGmsh", "mesh_cache": "SSStarMeshCache", "mesh_build": "SSStarMeshBuild", "mesh_faces": "SSStarMeshFaces",
          "mesh_label": "SSStarMeshLabel"}
LINEAR = re.compile(r"Linear solve (?:converged|did not converge) due to \S+ iterations (\d+)")
COLUMNS = ["level", "ranks", "config", "options", "runs", "whole", "rel_default", "cpu", "cpu_rel_default", "amg", "whole_per_amg", "mesh", "interpolate", "assembly",
           "snes", "snes_gflop", "newton_matrix", "pc_setup", "krylov", "output", "iters", "solves", "krylov_per_solve", "pc_setups", "peak_gb",
           "converged", "same_states", "du_rel", "states", "reason", "mesh_gmsh", "mesh_cache", "mesh_build", "mesh_faces", "mesh_label",
           "its_per_solve", "setup_gflop", "krylov_gflop"]


def event_time(log, name):
    m = re.search(r"^%s\s+(\d+)\s+\S+\s+(\S+)" % re.escape(name), log, re.M)
    return float(m.group(2)) if m else 0.0


def event_flops(log, name):
    """the flops of an event summed over the ranks: -log_view's last column (Mflop/s of the sum) times the max time"""
    m = re.search(r"^%s\s+\d+\s.*$" % re.escape(name), log, re.M)
    if not m:
        return math.nan
    f = m.group(0).split()
    return float(f[3]) * float(f[-1]) * 1e6


def k_alone(level, ranks, options):
    """bench/yardstick's AMG solve of K with the options: CG iterations, set-up and solve Gflop (-log_view's PCSetUp and
    KSPSolve, summed over the ranks), the peak per rank; None if it fails (an indefinite multigrid stops CG)"""
    cmd = mpiexec(ranks) + [os.path.join(ROOT, "bench", "yardstick"), "-yardstick", "amg", "-options_file", os.path.join(ROOT, "scenes", "prism.opts"),
                            "-level", str(level), "-log_view", "-memory_view"] + options
    out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    m = re.search(r"amg level .* its (\d+)", out)
    if not m:
        why = re.search(r"did not converge: (\S+)", out)
        return {"failed": why.group(1) if why else "failed"}
    return {"its": int(m.group(1)), "setup_gflop": event_flops(out, "PCSetUp") / 1e9, "solve_gflop": event_flops(out, "KSPSolve") / 1e9,
            "peak_gb": float(PEAK.search(out).group(2)) / 1e9}


def k_alone_table(level, ranks, configs):
    print("K alone, level %d, %d ranks: CG + the multigrid on K to 1e-8 (bench/yardstick -yardstick amg)" % (level, ranks))
    print("%-40s  its  set-up Gflop  solve Gflop  total / yardstick's  GB per rank" % "configuration")
    base = None
    for name, opts in configs:
        r = k_alone(level, ranks, shlex.split(opts))
        if "failed" in r:
            print("%-40s  %s" % (name[:40], r["failed"]), flush=True)
            continue
        total = r["setup_gflop"] + r["solve_gflop"]
        base = base or total
        print("%-40s %4d %12.3f %12.3f %15.2f %12.3f" % (name[:40], r["its"], r["setup_gflop"], r["solve_gflop"], total / base, r["peak_gb"]), flush=True)


def displacement(h5):
    import h5py
    with h5py.File(h5, "r") as f:
        return f["/fields/displacement"][...]


def measure(level, ranks, name, options, h5):
    cmd = mpiexec(ranks) + [os.path.join(ROOT, "examples", "prism"), "-level", str(level), "-snes_ssstar_reduction", "none",
                            "-summary_header", "0", "-memory_view", "-snes_view", "-log_view", "-ksp_converged_reason", "-o", h5] + options
    t0, u0 = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    whole, u1 = time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    m = ROW.search(p.stdout)
    if p.returncode or not m:
        print("  level %d, %s: failed (exit status %d)\n%s" % (level, name, p.returncode, p.stdout[-1500:]), flush=True)
        return None
    k = KRYLOV.search(p.stdout)
    r = {"whole": whole, "cpu": u1.ru_utime + u1.ru_stime - u0.ru_utime - u0.ru_stime, "iters": int(m.group(8)), "states": m.group(10), "reason": m.group(11),
         "solves": int(k.group(1)) if k else 0, "krylov_per_solve": int(k.group(2)) / int(k.group(1)) if k else math.nan,
         "pc_setups": int(k.group(3)) if k else 0, "peak_gb": float(PEAK.search(p.stdout).group(2)) / 1e9}
    for key, event in EVENTS.items():
        r[key] = event_time(p.stdout, event)
    r["snes_gflop"] = event_flops(p.stdout, "SNESSolve") / 1e9
    r["setup_gflop"] = event_flops(p.stdout, "SSStarNSFactor") / 1e9
    r["krylov_gflop"] = event_flops(p.stdout, "SSStarNSKrylov") / 1e9
    r["its_per_solve"] = "/".join(LINEAR.findall(p.stdout))
    return r


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default="8,12,16")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--set", default="sweep", choices=sorted(SETS))
    parser.add_argument("--only", default="", help="configuration names of the set, separated by semicolons (default kept)")
    parser.add_argument("--config", action="append", default=[], help="name='options': an extra configuration")
    parser.add_argument("--extra", default="", help="options added to every configuration")
    parser.add_argument("--csv", default="levers", help="base name of the CSV and PNG in bench/output")
    parser.add_argument("--k-alone", action="store_true", help="with --set rate: only the levers on K alone")
    parser.add_argument("--progress", action="store_true", help="a line per run on stderr")
    args = parser.parse_args()
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    os.makedirs(WORK, exist_ok=True)
    configs = list(SETS[args.set])
    if args.only:
        keep = set(n.strip() for n in args.only.split(";"))
        configs = [c for c in configs if c[0] == "default" or c[0] in keep]
    for spec in args.config:
        name, _, opts = spec.partition("=")
        configs.append((name, opts))
    configs = [(name, shlex.split(opts) + shlex.split(args.extra)) for name, opts in configs]
    rows = []
    print("medians of %d repeats, %d ranks, seconds; rel = whole / whole of the default in the same repeats; amg = the yardstick (one CG + GAMG solve of K) of the same repeats" % (args.repeat, args.ranks))
    print("level config                    whole   rel   cpu   rel  amg  whole/amg  mesh (interp) assembly  snes Gflop matrix setup krylov output  its solves kry/solve setups  GB   check")
    for level in level_list(args.levels):
        if args.set in K_ALONE and not args.only:
            k_alone_table(level, args.ranks, K_ALONE[args.set])
        if args.k_alone:
            continue
        runs = {name: [] for name, _ in configs}
        sticks = []
        reference = None
        for rep in range(args.repeat):
            sticks.append(sum(yardstick(level, args.ranks, "amg")))  # set-up + solve
            order = configs[rep % len(configs):] + configs[:rep % len(configs)]
            if rep == 0:  # the default first: the reference of the checks
                order = configs
            for name, options in order:
                h5 = os.path.join(WORK, "L%d_%s.h5" % (level, re.sub(r"\W+", "_", name)))
                r = measure(level, args.ranks, name, options, h5)
                if r is None:
                    continue
                r["converged"] = r["reason"].startswith("CONVERGED")
                u = displacement(h5) if r["converged"] else None
                if name == "default" and reference is None and u is not None:
                    reference = (u, r["states"])
                if reference is not None and u is not None:
                    r["du_rel"] = float(abs(u - reference[0]).max() / abs(reference[0]).max())
                    r["same_states"] = r["states"] == reference[1]
                else:
                    r["du_rel"], r["same_states"] = math.nan, False
                r["rep"] = rep
                runs[name].append(r)
                if args.progress:
                    print("  level %d repeat %d %-24s %6.2f s (cpu %6.1f s), %d its, %.1f Krylov its per solve, %s" % (
                        level, rep, name, r["whole"], r["cpu"], r["iters"], r["krylov_per_solve"], r["reason"]), file=sys.stderr, flush=True)
                for f in (h5, h5[:-3] + ".xmf"):
                    if os.path.exists(f):
                        os.remove(f)
        amg = statistics.median(sticks)
        default_whole = {r["rep"]: r["whole"] for r in runs["default"]}
        default_cpu = {r["rep"]: r["cpu"] for r in runs["default"]}
        for name, options in configs:
            rs = runs[name]
            if not rs:
                print("%5d %-24s failed" % (level, name), flush=True)
                continue
            row = {"level": level, "ranks": args.ranks, "config": name, "options": " ".join(options), "runs": len(rs), "amg": amg,
                   "its_per_solve": rs[0]["its_per_solve"],
                   "iters": max(r["iters"] for r in rs), "states": rs[0]["states"], "reason": rs[0]["reason"],
                   "converged": all(r["converged"] for r in rs), "same_states": all(r["same_states"] for r in rs),
                   "du_rel": max(r["du_rel"] for r in rs)}
            for key in ("whole", "cpu", "peak_gb", "solves", "krylov_per_solve", "pc_setups", "snes_gflop", "setup_gflop", "krylov_gflop") + tuple(EVENTS):
                row[key] = statistics.median(r[key] for r in rs)
            ratios = [r["whole"] / default_whole[r["rep"]] for r in rs if r["rep"] in default_whole]
            row["rel_default"] = statistics.median(ratios) if ratios else math.nan
            ratios = [r["cpu"] / default_cpu[r["rep"]] for r in rs if r["rep"] in default_cpu]
            row["cpu_rel_default"] = statistics.median(ratios) if ratios else math.nan
            row["whole_per_amg"] = row["whole"] / amg
            check = "ok" if row["converged"] and row["same_states"] and row["du_rel"] <= 1e-8 else \
                "NOT CONVERGED" if not row["converged"] else "states differ" if not row["same_states"] else "du %.1e" % row["du_rel"]
            print("%5d %-24s %6.2f %5.2f %6.1f %5.2f %5.2f %6.1f %7.2f (%5.2f) %6.2f %7.2f %5.1f %6.2f %5.2f %6.2f %5.2f %5d %5d %8.1f %6d %6.2f  %s" % (
                level, name[:24], row["whole"], row["rel_default"], row["cpu"], row["cpu_rel_default"], amg, row["whole_per_amg"], row["mesh"], row["interpolate"],
                row["assembly"], row["snes"], row["snes_gflop"], row["newton_matrix"], row["pc_setup"], row["krylov"], row["output"], row["iters"],
                row["solves"], row["krylov_per_solve"], row["pc_setups"], row["peak_gb"], check), flush=True)
            print("%5d %-24s Newton multigrid set-ups %.3f Gflop, Krylov solves %.3f Gflop, SNESSolve %.3f Gflop" % (
                level, name[:24], row["setup_gflop"], row["krylov_gflop"], row["snes_gflop"]), flush=True)
            rows.append(row)
    if args.k_alone:
        return
    with open(os.path.join(OUT, args.csv + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    plot(rows, args.csv)
    print("wrote %s/%s.csv and %s.png" % (OUT, args.csv, args.csv))


def plot(rows, name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    levels = sorted({r["level"] for r in rows})
    names = list(dict.fromkeys(r["config"] for r in rows))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(13, 0.3 * len(names) + 2), sharey=True)
    height = 0.8 / max(len(levels), 1)
    for i, level in enumerate(levels):
        by = {r["config"]: r for r in rows if r["level"] == level}
        default = by.get("default")
        ys = [k + i * height for k in range(len(names))]
        a1.barh(ys, [by[n]["rel_default"] if n in by else 0 for n in names], height, label="level %d" % level)
        a2.barh(ys, [by[n]["krylov_per_solve"] * by[n]["solves"] / (default["krylov_per_solve"] * default["solves"]) if n in by and default else 0
                     for n in names], height, label="level %d" % level)
    a1.set_yticks([k + 0.4 - height / 2 for k in range(len(names))])
    a1.set_yticklabels(names, fontsize=7)
    for ax, title in ((a1, "whole run / default's (same repeats)"), (a2, "Krylov iterations / default's")):
        ax.axvline(1.0, color="black", lw=0.8)
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=7)
    a1.invert_yaxis()  # shared by a2
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, name + ".png"), dpi=110)


if __name__ == "__main__":
    main()
