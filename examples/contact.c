static const char help[] = "Contact of elastic bodies with rigid obstacles and with each other: solves the scene the options\n\
describe, and only what they name (no contact group: one linear solve; frictionless groups: no friction work; no\n\
-gravity: no body force).\n\
A scene is an options file: examples/contact -options_file scenes/hertz.opts (README \"Scenes\").\n\
  -mesh <file.msh> | -geo <file.geo> -level <L>   the body (gmsh), physical groups by name; the options of the groups\n\
                                  (-dirichlet, -contact, -traction_<G>, ...) are listed under \"Scene\" below\n\
  -load_steps <1>                 solve at the loads k/N of the given ones, k = 1..N (the last is written)\n\
  -o <file.h5>                    write the solution (HDF5 + XDMF)\n\
The solver's options (-snes_ssstar_*) apply. An option nothing reads is refused before any work. Exit status 0 when every\n\
solve converged, 2 when one did not (the load steps stop there; the -o file holds that step's iterate and says so:\n\
attributes converged_reason, residual_norm, iterations of \"/\"), PETSc's error code for bad input (one\n\
line naming the option or file; -ssstar_traceback adds PETSc's report). -help lists the options and does nothing else.\n";

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
  LoadSteps       *steps = (LoadSteps *)ctx;
  const char      *names[4] = {"factor", "area", "normal_force", "iterations"};
  const PetscReal *values[4] = {steps->factor, steps->area, steps->normal_force, steps->iterations};
  PetscMPIInt      rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)viewer), &rank));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/load_steps"));
  for (PetscInt k = 0; k < 4; k++) {
    Vec v;

    PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)viewer), rank ? 0 : steps->n, steps->n, &v));
    PetscCall(PetscObjectSetName((PetscObject)v, names[k]));
    if (!rank)
      for (PetscInt i = 0; i < steps->n; i++) PetscCall(VecSetValue(v, i, values[k][i], INSERT_VALUES));
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
    PetscCall(VecView(v, viewer));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
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

int main(int argc, char **argv)
{
  SSStarScene         scene;
  Mat                 K;
  Vec                 b, load; /* the load b of the scene, and the one of a load step, a fraction of it */
  PetscReal           factor = 1.0;
  SNES                snes;
  Vec                 u, r = NULL;
  PetscInt            nsteps = 1, nodes, ncontact, its = 0, counts[SSSTAR_NUM_STATES] = {0, 0, 0, 0, 0, 0, 0};
  PetscReal           t0, t_assembly, t_schur = 0, t_recovery = 0, t_solve;
  PetscBool           hasOut, hasContact, hasHelp;
  char                out[PETSC_MAX_PATH_LEN] = "";
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  const SSStarState  *states = NULL;
  LoadSteps           steps;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(SSStarPushErrorHandler());
  PetscCall(PetscLogDefaultBegin()); /* the phases of the summary are read from the log events */

  /* every option, before any work: the program's, the scene's, the solver's */
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Contact driver", "ssstar");
  PetscCall(PetscOptionsInt("-load_steps", "Solve at the loads k/N of the given ones, k = 1..N", NULL, nsteps, &nsteps, NULL));
  PetscCall(PetscOptionsString("-o", "Output file (HDF5; an XDMF file is written beside it)", NULL, out, out, sizeof(out), &hasOut));
  PetscOptionsEnd();
  PetscCheck(nsteps >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-load_steps %" PetscInt_FMT ": needs at least one step", nsteps);
  if (hasOut) PetscCall(SSStarCheckOutputFile(PETSC_COMM_WORLD, out)); /* before the work, not after */
  PetscCall(SSStarSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(SSStarSceneSetFromOptions(scene));
  PetscCall(SSStarSceneHasContact(scene, &hasContact));
  PetscCall(PetscOptionsHasHelp(NULL, &hasHelp));
  /* contact: ssstar on the whole body; no contact: one linear solve; -help lists the options of ssstar */
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  if (hasContact || hasHelp) PetscCall(SNESSetType(snes, SNESSSSTAR));
  else {
    KSP ksp;
    PC  pc;

    PetscCall(SNESSetType(snes, SNESKSPONLY));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
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
  PetscCall(SNESSSStarSetLinearProblem(snes, K, load)); /* F(u) = K u - load, the load set at each step */
  if (hasContact) PetscCall(SSStarSceneSetContact(scene, snes));
  {
    DM dm;

    PetscCall(SSStarSceneGetDM(scene, &dm));
    PetscCall(DMCreateGlobalVector(dm, &u));
  }
  PetscCall(VecZeroEntries(u));

  steps.n = 0;
  PetscCall(PetscMalloc4(nsteps, &steps.factor, nsteps, &steps.area, nsteps, &steps.normal_force, nsteps, &steps.iterations));
  PetscCall(PetscTime(&t0));
  for (PetscInt k = 1; k <= nsteps; k++) {
    PetscInt            stepIts;
    SSStarContactResult res = {0, 0, 0, 0, 0, 0, {0, 0, 0}};

    factor = (PetscReal)k / nsteps;
    PetscCall(VecCopy(b, load));
    PetscCall(VecScale(load, factor));
    PetscCall(SNESSolve(snes, NULL, u)); /* from the previous step's solution */
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESGetIterationNumber(snes, &stepIts));
    its += hasContact ? stepIts : 0;
    if (hasContact) {
      PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */
      PetscCall(SNESSSStarGetStates(snes, &states, counts));
      PetscCall(SSStarSceneGetContactResult(scene, -1, r, states, &res));
    }
    steps.factor[k - 1]       = factor;
    steps.area[k - 1]         = res.area;
    steps.normal_force[k - 1] = res.normal_force;
    steps.iterations[k - 1]   = hasContact ? stepIts : 0;
    steps.n                   = k;
    if (nsteps > 1)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "load step %" PetscInt_FMT "/%" PetscInt_FMT ": factor %g, %" PetscInt_FMT " iterations, %" PetscInt_FMT " of %" PetscInt_FMT " contact nodes touching, contact area %.6g, normal force %.6g%s%s\n", k, nsteps, (double)factor, hasContact ? stepIts : 0, res.sliding + res.sticking, ncontact, (double)res.area,
                            (double)res.normal_force, reason > 0 ? "" : ", not converged: ", reason > 0 ? "" : SNESConvergedReasons[reason]));
    if (reason <= 0) break; /* the next steps would start from a point that is no solution */
  }
  PetscCall(PetscTimeSubtract(&t0));
  if (hasContact) {
    PetscCall(EventTime(SSSTAR_Schur, &t_schur));
    PetscCall(EventTime(SSSTAR_Recovery, &t_recovery));
  }
  t_solve = -t0 - t_schur - t_recovery; /* the contact iterations: the SNESSolve()s less the reduction and the recovery */

  if (hasContact) PetscCall(SSStarSceneContactView(scene, r, states, PETSC_VIEWER_STDOUT_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "summary: nodes %" PetscInt_FMT " contact %" PetscInt_FMT " assembly %.3f s schur %.3f s solve %.3f s iterations %" PetscInt_FMT " states L/M1/M2/M3+/M3-/M4/LS %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT " %s%s\n", nodes, ncontact, (double)t_assembly,
                        (double)t_schur, (double)t_solve, its, counts[0], counts[1], counts[2], counts[3], counts[4], counts[5], counts[6], SNESConvergedReasons[reason], hasContact ? "" : " (one linear solve)"));
  if (hasOut) PetscCall(SSStarSceneWriteSolution(scene, snes, out, u, nsteps > 1 ? WriteLoadSteps : NULL, &steps));
  if (reason <= 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "The solve did not converge (%s): exit status %d\n", SNESConvergedReasons[reason], SSSTAR_EXIT_NOT_CONVERGED));

  PetscCall(PetscFree4(steps.factor, steps.area, steps.normal_force, steps.iterations));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&load));
  PetscCall(SSStarSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : SSSTAR_EXIT_NOT_CONVERGED;
}
