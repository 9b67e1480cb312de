static const char help[] = "Contact of elastic bodies with rigid obstacles and with each other: solves the scene the options\n\
describe, and only what they name (no contact group: one linear solve; frictionless groups: no friction work; no\n\
-gravity: no body force).\n\
A scene is an options file: examples/contact -options_file scenes/hertz.opts (docs/guide/scenes.md).\n\
  -mesh <file.msh> | -geo <file.geo> -level <L>   the body (gmsh), physical groups by name; the options of the groups\n\
                                  (-dirichlet, -displacement_<G>, -contact, -traction_<G>, ...) are listed under\n\
                                  \"Scene\" below\n\
  -mesh_cache <folder>            where the meshes of -geo are made and kept (default $XDG_CACHE_HOME/ssstar, else\n\
                                  ~/.cache/ssstar; the mesh line names the file, e.g. meshes-1a2b3c4d/prism_L6.msh)\n\
  -load_steps <1>                 solve at the loads k/N of the given constant ones, k = 1..N (the last is written)\n\
  -steps <t1,t2,...|N>            a load path (histories -traction_<G> t:x,y,z;..., -gravity, -obstacle_<G>_motion,\n\
                                  -obstacle_<G>_rotation, -displacement_<G>): the times solved, or N equal steps from\n\
                                  the first knot to the last (default: the knots), each from the step before with\n\
                                  incremental friction (docs/load-paths.md); with -dynamics (-density,\n\
                                  -initial_velocity, ...: under \"Dynamics\" below) the times of the time steps from\n\
                                  t = 0 (docs/guide/dynamics.md)\n\
  -steps_max_cuts <4>             a step that does not converge is halved and retried, at most this many times\n\
  -o <file.h5>                    write the solution (HDF5 + XDMF; on a load path every step, /steps): displacement,\n\
                                  contact, the reaction of each held group (/groups/<G>/reaction), the cells' strain,\n\
                                  stress and von Mises stress, a nodal stress (docs/guide/displacements-and-stresses.md)\n\
  -ssstar_progress <true>         a line as each phase ends (mesh, contact nodes, assembly, the solver's set-up and each\n\
                                  Newton step, output), with seconds and the memory of the largest rank\n\
The solver's options (-snes_ssstar_*) apply. An option nothing reads is refused before any work. Exit status 0 when every\n\
solve converged, 2 when one did not (the load steps stop there; the -o file holds that step's iterate and says so:\n\
attributes converged_reason, residual_norm, iterations of \"/\", and on a load path failed_step, failed_time),\n\
PETSc's error code for bad input (one line naming the option or file; -ssstar_traceback adds PETSc's report). -help\n\
lists the options and does nothing else.\n";

#include <ssstar.h>
#include <ssstarscene.h>
#include <petscviewerhdf5.h>

/* What each load step gave, for the output file */
typedef struct {
  PetscInt   n;
  PetscReal *factor, *area, *normal_force, *iterations;
} LoadSteps;

/* The datasets /load_steps/{factor,area,normal_force,iterations}, held by rank 0 */
static PetscErrorCode WriteLoadSteps(PetscViewer viewer, void *ctx)
{
  LoadSteps       *steps    = (LoadSteps *)ctx;
  const char      *names[4] = {"factor", "area", "normal_force", "iterations"};
  const PetscReal *values[4] = {steps->factor, steps->area, steps->normal_force, steps->iterations};

  PetscFunctionBeginUser;
  PetscCall(SSStarWriteTable(viewer, "/load_steps", 4, names, steps->n, values));
  PetscFunctionReturn(0);
}

/* One line per step of a load path: time, load, forces, contact area, nodes sliding, iterations, obstacles' motion,
   the energies with -dynamics, the held groups' reactions */
static PetscErrorCode StepLine(SSStarScene scene, SNES snes, PetscInt k, PetscInt n, PetscReal t, PetscInt cuts, Vec load, PetscBool hasContact)
{
  SSStarContactResult res = {0, 0, 0, 0, 0, 0, {0, 0, 0}, {0, 0, 0}, 0};
  PetscReal           R[3], T;
  PetscInt            its, ngroups;
  Vec                 r;
  const SSStarState  *states;
  char                motion[512] = "", cut[32] = "";

  PetscFunctionBeginUser;
  PetscCall(SSStarSceneGetLoadResultant(scene, load, R));
  PetscCall(SNESGetIterationNumber(snes, &its));
  if (hasContact) {
    PetscCall(SNESGetFunction(snes, &r, NULL, NULL));
    PetscCall(SNESSSStarGetStates(snes, &states, NULL));
    PetscCall(SSStarSceneGetContactResult(scene, -1, r, states, &res));
  }
  PetscCall(SSStarSceneGetContactGroupCount(scene, &ngroups));
  for (PetscInt g = 0; g < ngroups; g++) { /* the moving obstacles */
    const char *name;
    PetscReal   d[3], theta[3];
    PetscBool   moving;
    char        item[256];

    PetscCall(SSStarSceneGetMotion(scene, g, &name, d, theta, &moving));
    if (!moving) continue;
    PetscCall(PetscSNPrintf(item, sizeof(item), ", obstacle of %s at (%.6g, %.6g, %.6g)", name, (double)d[0], (double)d[1], (double)d[2]));
    PetscCall(PetscStrlcat(motion, item, sizeof(motion)));
    if (theta[0] != 0 || theta[1] != 0 || theta[2] != 0) {
      PetscCall(PetscSNPrintf(item, sizeof(item), " turned by (%.6g, %.6g, %.6g)", (double)theta[0], (double)theta[1], (double)theta[2]));
      PetscCall(PetscStrlcat(motion, item, sizeof(motion)));
    }
  }
  {
    SSStarEnergies e;
    PetscBool      dynamics;
    char           item[256];

    PetscCall(SSStarSceneGetEnergies(scene, &e, &dynamics)); /* -dynamics: the energies and their balance */
    if (dynamics) {
      PetscCall(PetscSNPrintf(item, sizeof(item), ", energy: kinetic %.6g strain %.6g work %.6g friction %.6g damping %.6g impact %.6g balance %.3g", (double)e.kinetic, (double)e.strain, (double)e.work, (double)e.friction, (double)e.damping, (double)e.impact, (double)e.error));
      PetscCall(PetscStrlcat(motion, item, sizeof(motion)));
    }
  }
  { /* the held groups' reactions */
    PetscInt           nheld;
    const char *const *held;
    PetscReal         *reaction;
    Vec                u;

    PetscCall(SSStarSceneGetHeldGroups(scene, &nheld, &held));
    PetscCall(SNESGetSolution(snes, &u));
    PetscCall(PetscMalloc1(3 * nheld + 1, &reaction));
    PetscCall(SSStarSceneGetReactions(scene, snes, u, reaction));
    for (PetscInt h = 0; h < nheld; h++) {
      char item[256];

      PetscCall(PetscSNPrintf(item, sizeof(item), ", reaction of %s (%.6g, %.6g, %.6g)", held[h], (double)reaction[3 * h], (double)reaction[3 * h + 1], (double)reaction[3 * h + 2]));
      PetscCall(PetscStrlcat(motion, item, sizeof(motion)));
    }
    PetscCall(PetscFree(reaction));
  }
  T = PetscSqrtReal(res.tangential_force[0] * res.tangential_force[0] + res.tangential_force[1] * res.tangential_force[1] + res.tangential_force[2] * res.tangential_force[2]);
  if (cuts) PetscCall(PetscSNPrintf(cut, sizeof(cut), " (halved %" PetscInt_FMT "x)", cuts));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT "/%" PetscInt_FMT " t %g%s: load (%.6g, %.6g, %.6g) normal force %.6g tangential force %.6g (%.6g, %.6g, %.6g) area %.6g sliding %" PetscInt_FMT " of %" PetscInt_FMT " touching, %" PetscInt_FMT " iterations%s\n", k + 1, n, (double)t, cut, (double)R[0], (double)R[1], (double)R[2], (double)res.normal_force, (double)T,
                        (double)res.tangential_force[0], (double)res.tangential_force[1], (double)res.tangential_force[2], (double)res.area, res.sliding, res.sliding + res.sticking, its, motion));
  PetscFunctionReturn(0);
}

/* Time spent in a log event, max over the ranks */
static PetscErrorCode EventTime(PetscLogEvent event, PetscReal *t)
{
  PetscEventPerfInfo info;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventGetPerfInfo(PETSC_DETERMINE, event, &info));
  PetscCall(MPIU_Allreduce(&info.time, t, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscFunctionReturn(0);
}

/* The iterations of the solve just done: none for one linear solve (ksponly) */
static PetscErrorCode Iterations(SNES snes, PetscInt *its)
{
  PetscBool linear;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESKSPONLY, &linear));
  *its = 0;
  if (!linear) PetscCall(SNESGetIterationNumber(snes, its));
  PetscFunctionReturn(0);
}

/* -load_steps N: static solves at the loads k/N of the constant ones, each from the previous solution (continuation) */
static PetscErrorCode SolveLoadSteps(SSStarScene scene, SNES snes, Vec b, Vec load, Vec u, PetscBool hasContact, LoadSteps *steps, PetscInt *its, SNESConvergedReason *reason)
{
  PetscInt nsteps = steps->n, ncontact;

  PetscFunctionBeginUser;
  PetscCall(SSStarSceneGetSizes(scene, NULL, &ncontact));
  steps->n = 0;
  for (PetscInt k = 1; k <= nsteps; k++) {
    const PetscReal     factor = (PetscReal)k / nsteps;
    PetscInt            stepIts;
    SSStarContactResult res = {0, 0, 0, 0, 0, 0, {0, 0, 0}, {0, 0, 0}, 0};

    PetscCall(VecCopy(b, load));
    PetscCall(VecScale(load, factor));
    if (nsteps == 1 && hasContact) PetscCall(SSStarSceneSolveNested(scene, snes, u)); /* -nested_levels */
    PetscCall(SNESSolve(snes, NULL, u)); /* from the previous step's solution */
    PetscCall(SNESGetConvergedReason(snes, reason));
    PetscCall(Iterations(snes, &stepIts));
    *its += stepIts;
    if (hasContact) {
      Vec                r;
      const SSStarState *states;

      PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */
      PetscCall(SNESSSStarGetStates(snes, &states, NULL));
      PetscCall(SSStarSceneGetContactResult(scene, -1, r, states, &res));
    }
    steps->factor[k - 1]       = factor;
    steps->area[k - 1]         = res.area;
    steps->normal_force[k - 1] = res.normal_force;
    steps->iterations[k - 1]   = stepIts;
    steps->n                   = k;
    if (nsteps > 1)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "load step %" PetscInt_FMT "/%" PetscInt_FMT ": factor %g, %" PetscInt_FMT " iterations, %" PetscInt_FMT " of %" PetscInt_FMT " contact nodes touching, contact area %.6g, normal force %.6g%s%s\n", k, nsteps, (double)factor, stepIts, res.sliding + res.sticking, ncontact, (double)res.area,
                            (double)res.normal_force, *reason > 0 ? "" : ", not converged: ", *reason > 0 ? "" : SNESConvergedReasons[*reason]));
    if (*reason <= 0) break; /* the next steps would start from a point that is no solution */
  }
  PetscFunctionReturn(0);
}

/*
   A load path (docs/load-paths.md): the steps at the times of -steps (default the knots of the histories), each from
   the solution of the step before with incremental friction, by the scene library's stepper (SSStarSceneAdvance():
   a step that does not converge is retried at the midpoint and goes on to its time in sub-steps of that size, at most
   maxCuts halvings per step, then the path stops). One line per accepted step; with out, every step (and sub-step)
   into the file.
*/
static PetscErrorCode SolvePath(SSStarScene scene, SNES snes, Vec load, Vec u, PetscInt nsteps, const PetscReal times[], PetscInt maxCuts, PetscBool hasContact, const char out[], PetscInt *its, SNESConvergedReason *reason)
{
  PetscBool stopped = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(SSStarSceneCheckSteps(scene, nsteps, times)); /* the motions of every step, before any solve and file */
  if (out) PetscCall(SSStarSceneOutputBegin(scene, out));
  for (PetscInt k = 0; k < nsteps && !stopped; k++) {
    SSStarStep step;

    do {
      PetscCall(SSStarSceneAdvance(scene, snes, u, times[k], maxCuts, &step));
      *its += step.iterations; /* none for a linear solve (ksponly) */
      *reason = step.reason;
      if (step.accepted) PetscCall(StepLine(scene, snes, k, nsteps, step.time, step.cuts, load, hasContact));
      else if (!step.stopped) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT "/%" PetscInt_FMT " t %g: not converged (%s), retried at t %g\n", k + 1, nsteps, (double)step.time, step.why, (double)step.retry));
      else if (step.noEquilibrium) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT "/%" PetscInt_FMT " t %g: no equilibrium (%s): the path stops here\n", k + 1, nsteps, (double)step.time, step.why));
      else PetscCall(PetscPrintf(PETSC_COMM_WORLD, "step %" PetscInt_FMT "/%" PetscInt_FMT " t %g: not converged (%s) after %" PetscInt_FMT " halvings (-steps_max_cuts %" PetscInt_FMT "): the path stops here\n", k + 1, nsteps, (double)step.time, step.why, step.cuts, maxCuts));
    } while (!step.stopped && !step.reached);
    stopped = step.stopped;
  }
  if (out) PetscCall(SNESSSStarReleaseWork(snes)); /* the last step solved: the file's memory out of the Newton steps' */
  if (out) PetscCall(SSStarSceneOutputEnd(scene, snes, u, NULL, NULL));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  SSStarScene         scene;
  Mat                 K;
  Vec                 b, load; /* the load b of the scene, and the one of a step: a fraction of b, or b(t) of a path */
  SNES                snes;
  Vec                 u, r = NULL;
  PetscInt            nodes, ncontact, its = 0, maxCuts = 4, nLoadSteps, nsteps = 0, counts[SSSTAR_NUM_STATES] = {0, 0, 0, 0, 0, 0, 0};
  PetscReal          *times = NULL; /* the times of a load path */
  PetscReal           t0, t_assembly, t_schur = 0, t_recovery = 0, t_solve;
  PetscLogDouble      peak;
  PetscBool           hasOut, hasContact, hasHelp, hasLoadSteps, hasSteps, path = PETSC_FALSE, affine;
  char                out[PETSC_MAX_PATH_LEN] = "", stepsText[4096] = "";
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  const SSStarState  *states = NULL;
  LoadSteps           steps = {1, NULL, NULL, NULL, NULL};

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(SSStarPushErrorHandler());
  PetscCall(PetscLogDefaultBegin()); /* the phases of the summary are read from the log events */

  /* every option, before any work: the program's, the scene's, the solver's */
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Contact driver", "ssstar");
  PetscCall(PetscOptionsInt("-load_steps", "Solve at the loads k/N of the given constant ones, k = 1..N", NULL, steps.n, &steps.n, &hasLoadSteps));
  PetscCall(PetscOptionsString("-steps", "A load path: the times t1,t2,... solved, or N equal steps from the first knot to the last (default: the knots of the histories)", NULL, stepsText, stepsText, sizeof(stepsText), &hasSteps));
  PetscCall(PetscOptionsInt("-steps_max_cuts", "Halvings of a step of a load path that does not converge before the path stops", NULL, maxCuts, &maxCuts, NULL));
  PetscCall(PetscOptionsString("-o", "Output file (HDF5; an XDMF file is written beside it)", NULL, out, out, sizeof(out), &hasOut));
  PetscOptionsEnd();
  PetscCheck(steps.n >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-load_steps %" PetscInt_FMT ": needs at least one step", steps.n);
  PetscCheck(maxCuts >= 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-steps_max_cuts %" PetscInt_FMT ": must be >= 0", maxCuts);
  if (hasOut) PetscCall(SSStarCheckOutputFile(PETSC_COMM_WORLD, out)); /* before the work, not after */
  PetscCall(SSStarSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(SSStarSceneSetProgress(scene, PETSC_TRUE));
  PetscCall(SSStarSceneSetFromOptions(scene));
  PetscCall(SSStarSceneHasContact(scene, &hasContact));
  PetscCall(SSStarSceneIsAffine(scene, &affine));
  PetscCall(PetscOptionsHasHelp(NULL, &hasHelp));
  if (!hasHelp) {
    PetscCall(SSStarSceneHasPath(scene, &path));
    path = (PetscBool)(path || hasSteps);
    PetscCheck(!(path && hasLoadSteps), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "Option -load_steps scales the constant loads of a static problem; a load path is -steps with histories (-traction_<G> t:x,y,z;..., -gravity, -obstacle_<G>_motion): give one of them");
    if (path) PetscCall(SSStarSceneGetPathTimes(scene, hasSteps ? stepsText : NULL, &nsteps, &times)); /* -steps refused before the mesh */
  }
  /* contact: ssstar on the whole body; no contact: one linear solve, or Newton's method (newtonls, LU of the tangent)
     for a hyperelastic body, its line search cp: F is the gradient of the energy (dead loads, springs), and the
     norm of F that bt minimizes grows along the Newton step of a body that bends or turns (-snes_linesearch_type
     overrides it); -help lists the options of ssstar */
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  if (hasContact || hasHelp) PetscCall(SNESSetType(snes, SNESSSSTAR));
  else {
    KSP ksp;
    PC  pc;

    PetscCall(SNESSetType(snes, affine ? SNESKSPONLY : SNESNEWTONLS));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, affine ? PCCHOLESKY : PCLU));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    if (!affine) {
      SNESLineSearch ls;

      PetscCall(SNESGetLineSearch(snes, &ls));
      PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHCP));
    }
  }
  PetscCall(SNESSetFromOptions(snes));
  if (hasHelp) { /* the options are listed: no mesh, no solve, no file */
    PetscCall(SNESDestroy(&snes));
    PetscCall(SSStarSceneDestroy(&scene));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(SSStarSceneCheckOptionsUsed(scene, help, snes));

  /* the scene: mesh, groups, contact nodes, K and b */
  PetscCall(PetscTime(&t0));
  PetscCall(SSStarSceneSetUp(scene));
  PetscCall(SSStarSceneAssemble(scene, &K, &b));
  PetscCall(PetscTimeSubtract(&t0));
  t_assembly = -t0;
  PetscCall(SSStarSceneView(scene, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(SSStarSceneGetSizes(scene, &nodes, &ncontact));

  PetscCall(VecDuplicate(b, &load));
  PetscCall(SSStarSceneSetSolver(scene, snes, K, load)); /* F(u) = K u - load (or a hyperelastic body's f(u) - load), the load set at each step; the contact */
  {
    DM dm;

    PetscCall(SSStarSceneGetDM(scene, &dm));
    PetscCall(DMCreateGlobalVector(dm, &u));
  }
  PetscCall(VecZeroEntries(u));

  nLoadSteps = steps.n; /* steps.n: the steps solved */
  PetscCall(PetscMalloc4(steps.n, &steps.factor, steps.n, &steps.area, steps.n, &steps.normal_force, steps.n, &steps.iterations));
  PetscCall(PetscTime(&t0));
  if (path) PetscCall(SolvePath(scene, snes, load, u, nsteps, times, maxCuts, hasContact, hasOut ? out : NULL, &its, &reason));
  else PetscCall(SolveLoadSteps(scene, snes, b, load, u, hasContact, &steps, &its, &reason));
  if (hasContact) {
    PetscCall(SNESGetFunction(snes, &r, NULL, NULL));
    PetscCall(SNESSSStarGetStates(snes, &states, counts));
  }
  PetscCall(PetscTimeSubtract(&t0));
  if (hasContact) {
    PetscCall(EventTime(SSSTAR_Schur, &t_schur));
    PetscCall(EventTime(SSSTAR_Recovery, &t_recovery));
  }
  t_solve = -t0 - t_schur - t_recovery; /* the contact iterations: the SNESSolve()s less the reduction and the recovery */

  if (hasContact) PetscCall(SSStarSceneContactView(scene, r, states, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(SSStarMemoryGetUsage(PETSC_COMM_WORLD, NULL, &peak));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "summary: nodes %" PetscInt_FMT " contact %" PetscInt_FMT " assembly %.3f s schur %.3f s solve %.3f s iterations %" PetscInt_FMT " states L/M1/M2/M3+/M3-/M4/LS %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT " %s%s peak %.3f GB per rank\n", nodes, ncontact, (double)t_assembly,
                        (double)t_schur, (double)t_solve, its, counts[0], counts[1], counts[2], counts[3], counts[4], counts[5], counts[6], SNESConvergedReasons[reason], hasContact ? "" : affine ? " (one linear solve)" : " (Newton's method, no contact)", peak / 1e9));
  if (hasOut && !path) PetscCall(SNESSSStarReleaseWork(snes)); /* the file's memory out of the Newton steps' work */
  if (hasOut && !path) PetscCall(SSStarSceneWriteSolution(scene, snes, out, u, nLoadSteps > 1 ? WriteLoadSteps : NULL, &steps));
  if (hasContact) PetscCall(SSStarSceneViewNoEquilibrium(scene, snes, PETSC_VIEWER_STDOUT_WORLD));
  if (reason <= 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "The solve did not converge (%s): exit status %d\n", SNESConvergedReasons[reason], SSSTAR_EXIT_NOT_CONVERGED));

  PetscCall(PetscFree4(steps.factor, steps.area, steps.normal_force, steps.iterations));
  PetscCall(PetscFree(times));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&load));
  PetscCall(SSStarSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : SSSTAR_EXIT_NOT_CONVERGED;
}
