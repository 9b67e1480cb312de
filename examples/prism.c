static const char help[] = "The seed's test problem: an elastic prism pressed onto a rigid plane with Coulomb friction,\n\
solved by the semismooth* Newton method (SNES type ssstar) on the contact dofs.\n\
  -level <6>                 mesh level L of meshes/prism.geo: (4L+1)x(2L+1)x(2L+1) nodes\n\
  -mesh <file.msh>           any gmsh mesh with physical groups dirichlet, top, right, contact (instead of -geo, -level)\n\
  -geo <file.geo>            the geometry meshed for -level (default: meshes/prism.geo of the source tree)\n\
  -mesh_cache <folder>       where the meshes of -geo are made and kept: <folder>/<folder of the .geo>-<hash>/\n\
                             <name>_L<level>.msh (default $XDG_CACHE_HOME/ssstar, else ~/.cache/ssstar; the mesh\n\
                             line names the file); nothing is written into the source tree\n\
  -mesh_scale <1>            multiply the mesh coordinates by this (a change of length unit, e.g. 1e-3 for mm -> m)\n\
  -E <2.1e5> -nu <0.3>       Young's modulus and Poisson ratio\n\
  -traction_top <0,0,-500>   traction on the group top\n\
  -traction_right <-200,30,200> traction on the group right\n\
  -initial_guess <zero>      the solver's starting point: zero, elastic (K u = b, no contact) or random\n\
  -initial_guess_scale <1>   random: entries uniform in [-scale, scale]\n\
  -o <file.h5>               write the solution (HDF5 + XDMF): displacement, contact, the held group's reaction\n\
                             /groups/dirichlet/reaction, the cells' strain, stress and von Mises stress\n\
  -save_reduced <file.bin>   write P, f, the contact solution u_C and the contact nodes' coordinates (PETSc binary);\n\
                             it sets -snes_ssstar_reduction direct unless a reduction is given\n\
  -save_whole <file.bin>     write K, b and the contact nodes (their dofs, normals, gaps) before the solve (PETSc\n\
                             binary): the whole-body problem for a program of one's own (tests/test_nonlinear.c)\n\
  -summary_header <true>     print the header line of the summary table (its level reads 4r1 for level 4 refined\n\
                             once by -dm_refine 1: level 8's number of nodes; -1 for -mesh)\n\
  -ssstar_progress <true>    a line as each phase ends (mesh, contact nodes, assembly, the solver's set-up and each\n\
                             Newton step, output), with seconds and the memory of the largest rank; 0: the summary only\n\
The solver's options (-snes_ssstar_*, docs/options.md) apply: -snes_ssstar_reduction <auto> reduces K to the\n\
contact dofs by a Schur complement (direct: the seed's route) where that costs less than the whole body (none: Krylov\n\
+ multigrid, P never formed) by auto's estimate (docs/guide/choosing-a-route.md; the prism: up to level 7); the\n\
friction coefficient is -snes_ssstar_friction <0.3> (or -friction_contact). Every option of examples/contact applies\n\
too (docs/guide/scenes.md):\n\
the prism is the scene scenes/prism.opts. An option nothing reads is refused before any work. Exit status 0 when the\n\
solve converged, 2 when it did not (the -o file says so: attributes converged_reason, residual_norm, iterations of \"/\";\n\
no -save_reduced file), PETSc's error code for bad input (one\n\
line naming the option or file; -ssstar_traceback adds PETSc's report). -help lists the options and does nothing else.\n";

#include <ssstar.h>
#include <ssstarscene.h>

#ifndef SSSTAR_MESH_DIR
  #define SSSTAR_MESH_DIR "meshes"
#endif

/* The prism scene (docs/guide/prism.md) unless the options say otherwise; -mesh replaces -geo and -level; -save_reduced
   writes P: the dense route unless a reduction is named */
static PetscErrorCode SetPrismDefaults(void)
{
  const char *defaults[][2] = {{"-dirichlet", "dirichlet"}, {"-contact", "contact"}, {"-traction_top", "0,0,-500"}, {"-traction_right", "-200,30,200"}, {"-E", "2.1e5"}, {"-nu", "0.3"}, {"-geo", SSSTAR_MESH_DIR "/prism.geo"}, {"-level", "6"}};
  PetscBool   hasMesh, set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-save_reduced", &set));
  if (set) PetscCall(PetscOptionsHasName(NULL, NULL, "-snes_ssstar_reduction", &set));
  else set = PETSC_TRUE;
  if (!set) PetscCall(PetscOptionsSetValue(NULL, "-snes_ssstar_reduction", "direct"));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-mesh", &hasMesh));
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(defaults) - (hasMesh ? 2 : 0); k++) {
    PetscCall(PetscOptionsHasName(NULL, NULL, defaults[k][0], &set));
    if (!set) PetscCall(PetscOptionsSetValue(NULL, defaults[k][0], defaults[k][1]));
  }
  PetscFunctionReturn(0);
}

/* The elastic body: F(u) = K u - b, Jacobian K */
typedef struct {
  Mat K;
  Vec b;
} Body;

/* The starting point of the solve: zero, the linear-elastic solution without contact, or a random point */
typedef enum {
  INITIAL_GUESS_ZERO,
  INITIAL_GUESS_ELASTIC,
  INITIAL_GUESS_RANDOM
} InitialGuessType;
static const char *const InitialGuessTypes[] = {"zero", "elastic", "random", "InitialGuess", "INITIAL_GUESS_", NULL};

typedef struct {
  InitialGuessType type;
  PetscReal        scale; /* random: entries uniform in [-scale, scale] */
  KSP              ksp;   /* elastic: solves K u = b                    */
} InitialGuess;

/* Reads the options of the starting point (and of its solver) before any work */
static PetscErrorCode InitialGuessSetFromOptions(InitialGuess *guess)
{
  PetscFunctionBeginUser;
  guess->type  = INITIAL_GUESS_ZERO;
  guess->scale = 1;
  guess->ksp   = NULL;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Initial guess", "prism");
  PetscCall(PetscOptionsEnum("-initial_guess", "Starting point: zero, elastic (K u = b) or random", NULL, InitialGuessTypes, (PetscEnum)guess->type, (PetscEnum *)&guess->type, NULL));
  PetscCall(PetscOptionsReal("-initial_guess_scale", "Random starting point: entries uniform in [-scale, scale]", NULL, guess->scale, &guess->scale, NULL));
  PetscOptionsEnd();
  PetscCheck(guess->type != INITIAL_GUESS_RANDOM || (guess->scale > 0 && !PetscIsInfOrNanReal(guess->scale)), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-initial_guess_scale %g: must be a number > 0", (double)guess->scale);
  if (guess->type == INITIAL_GUESS_ELASTIC) {
    PC pc;

    PetscCall(KSPCreate(PETSC_COMM_WORLD, &guess->ksp));
    PetscCall(KSPSetOptionsPrefix(guess->ksp, "initial_"));
    PetscCall(KSPSetType(guess->ksp, KSPPREONLY));
    PetscCall(KSPGetPC(guess->ksp, &pc));
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    PetscCall(KSPSetFromOptions(guess->ksp));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode InitialGuessCompute(InitialGuess *guess, const Body *body, Vec u)
{
  PetscFunctionBeginUser;
  switch (guess->type) {
  case INITIAL_GUESS_ZERO:
    PetscCall(VecZeroEntries(u));
    break;
  case INITIAL_GUESS_ELASTIC:
    PetscCall(KSPSetOperators(guess->ksp, body->K, body->K));
    PetscCall(KSPSolve(guess->ksp, body->b, u));
    break;
  case INITIAL_GUESS_RANDOM: {
    PetscRandom rnd;

    PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
    PetscCall(PetscRandomSetInterval(rnd, -guess->scale, guess->scale));
    PetscCall(VecSetRandom(u, rnd));
    PetscCall(PetscRandomDestroy(&rnd));
  } break;
  }
  PetscCall(KSPDestroy(&guess->ksp));
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

/* P, f (in the solver's node order: nodes sorted by their first dof), u_C and the coordinates in the same order */
static PetscErrorCode SaveReduced(const char file[], SSStarScene scene, SNES snes, Vec u)
{
  Mat              P;
  Vec              f, uC, xC;
  IS               isC;
  PetscInt         n;
  const PetscReal *coords;
  PetscBool        sorted;
  PetscViewer      viewer;

  PetscFunctionBeginUser;
  PetscCall(SNESSSStarGetReducedProblem(snes, &P, &f));
  PetscCall(SSStarSceneGetContactDofs(scene, &isC));
  PetscCall(SSStarSceneGetContactNodes(scene, &n, &coords, NULL, NULL, NULL));
  PetscCall(ISSorted(isC, &sorted));
  PetscCheck(sorted, PETSC_COMM_SELF, PETSC_ERR_SUP, "-save_reduced: the contact dofs of this mesh are not in increasing order");
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
  PetscCall(MatView(P, viewer));
  PetscCall(VecView(f, viewer));
  PetscCall(VecGetSubVector(u, isC, &uC));
  PetscCall(VecView(uC, viewer));
  PetscCall(VecRestoreSubVector(u, isC, &uC));
  PetscCall(VecCreateMPIWithArray(PETSC_COMM_WORLD, 3, 3 * n, PETSC_DETERMINE, coords, &xC));
  PetscCall(VecView(xC, viewer));
  PetscCall(VecDestroy(&xC));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

/*
   K, b and the contact nodes of the whole-body problem, before the solve: the global indices of their dofs (3 per node,
   as reals), their obstacle normals (3 per node) and gaps, each a Vec laid out by the nodes
*/
static PetscErrorCode SaveWhole(const char file[], SSStarScene scene, Body *body)
{
  IS                 isC;
  PetscInt           n;
  const PetscInt    *idx;
  const PetscReal   *normals, *gaps;
  PetscScalar       *a;
  Vec                v;
  PetscViewer        viewer;

  PetscFunctionBeginUser;
  PetscCall(SSStarSceneGetContactDofs(scene, &isC));
  PetscCall(SSStarSceneGetContactNodes(scene, &n, NULL, &normals, &gaps, NULL));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
  PetscCall(MatView(body->K, viewer));
  PetscCall(VecView(body->b, viewer));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, 3 * n, PETSC_DETERMINE, &v));
  PetscCall(ISGetIndices(isC, &idx));
  PetscCall(VecGetArrayWrite(v, &a));
  for (PetscInt k = 0; k < 3 * n; k++) a[k] = (PetscScalar)idx[k];
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscCall(ISRestoreIndices(isC, &idx));
  PetscCall(VecView(v, viewer));
  PetscCall(VecGetArrayWrite(v, &a));
  for (PetscInt k = 0; k < 3 * n; k++) a[k] = normals[k];
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &v));
  PetscCall(VecGetArrayWrite(v, &a));
  for (PetscInt k = 0; k < n; k++) a[k] = gaps[k];
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  SSStarScene         scene;
  PetscInt            level = -1, refine = 0, nnodes, counts[SSSTAR_NUM_STATES], its, ncontact;
  PetscReal           t_assembly, t_schur, t_solve, t_recovery, t0;
  PetscLogDouble      peak;
  char                out[PETSC_MAX_PATH_LEN] = "", reduced[PETSC_MAX_PATH_LEN] = "", whole[PETSC_MAX_PATH_LEN] = "", levelText[32];
  PetscBool           hasMesh, hasOut, hasReduced, hasWhole, header = PETSC_TRUE, isssstar, hasHelp;
  DM                  dm;
  Vec                 u, r;
  Body                body;
  SNES                snes;
  SNESConvergedReason reason;
  PetscMPIInt         size;
  InitialGuess        guess;
  const SSStarState  *states = NULL;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(SSStarPushErrorHandler());
  PetscCall(PetscLogDefaultBegin()); /* the phases of the summary row are read from the log events */
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));

  /* every option, before any work: the program's, the scene's (SetPrismDefaults), the solver's */
  PetscCall(SetPrismDefaults());
  PetscCall(PetscOptionsHasName(NULL, NULL, "-mesh", &hasMesh));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-level", &level, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-dm_refine", &refine, NULL));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Prism contact problem", "ssstar");
  PetscCall(PetscOptionsString("-o", "Output file (HDF5; an XDMF file is written beside it)", NULL, out, out, sizeof(out), &hasOut));
  PetscCall(PetscOptionsString("-save_reduced", "Write P, f, u_C and the contact coordinates to this PETSc binary file", NULL, reduced, reduced, sizeof(reduced), &hasReduced));
  PetscCall(PetscOptionsString("-save_whole", "Write K, b and the contact nodes (dofs, normals, gaps) to this PETSc binary file", NULL, whole, whole, sizeof(whole), &hasWhole));
  PetscCall(PetscOptionsBool("-summary_header", "Print the header of the summary table", NULL, header, &header, NULL));
  PetscOptionsEnd();
  PetscCall(InitialGuessSetFromOptions(&guess));
  if (hasOut) PetscCall(SSStarCheckOutputFile(PETSC_COMM_WORLD, out)); /* before the work, not after */
  if (hasReduced) PetscCall(SSStarCheckOutputFile(PETSC_COMM_WORLD, reduced));
  if (hasWhole) PetscCall(SSStarCheckOutputFile(PETSC_COMM_WORLD, whole));
  PetscCall(SSStarSceneCreate(PETSC_COMM_WORLD, &scene));
  PetscCall(SSStarSceneSetProgress(scene, PETSC_TRUE));
  PetscCall(SSStarSceneSetFromOptions(scene));
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(PetscOptionsHasHelp(NULL, &hasHelp));
  if (hasHelp) { /* the options are listed: no mesh, no solve, no file */
    PetscCall(KSPDestroy(&guess.ksp));
    PetscCall(SNESDestroy(&snes));
    PetscCall(SSStarSceneDestroy(&scene));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(SSStarSceneCheckOptionsUsed(scene, help, snes));

  /* mesh, FEM: the scene of the options */
  PetscCall(PetscTime(&t0));
  PetscCall(SSStarSceneSetUp(scene));
  PetscCall(SSStarSceneAssemble(scene, &body.K, &body.b));
  PetscCall(SSStarSceneGetDM(scene, &dm));
  PetscCall(PetscTimeSubtract(&t0));
  t_assembly = -t0;

  /* the whole body with its contact nodes: SNESSolve reduces K to them, solves, recovers u */
  PetscCall(SNESSSStarSetLinearProblem(snes, body.K, body.b));
  PetscCall(SSStarSceneSetContact(scene, snes));
  if (hasWhole) PetscCall(SaveWhole(whole, scene, &body));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  PetscCall(DMCreateGlobalVector(dm, &u));
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(InitialGuessCompute(&guess, &body, u));
  PetscCall(PetscTime(&t0));
  if (guess.type == INITIAL_GUESS_ZERO && isssstar) PetscCall(SSStarSceneSolveNested(scene, snes, u)); /* -nested_levels */
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(PetscTimeSubtract(&t0));
  PetscCall(EventTime(SSSTAR_Schur, &t_schur));
  PetscCall(EventTime(SSSTAR_Recovery, &t_recovery));
  t_solve = -t0 - t_schur - t_recovery; /* the contact iterations: SNESSolve less the reduction and the recovery */
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* K u - b: the contact forces at the contact dofs */

  /* summary in the shape of Table 2 */
  PetscCall(SSStarSceneGetSizes(scene, &nnodes, &ncontact));
  if (isssstar) PetscCall(SNESSSStarGetStates(snes, &states, counts));
  else PetscCall(PetscArrayzero(counts, SSSTAR_NUM_STATES));
  PetscCall(SSStarMemoryGetUsage(PETSC_COMM_WORLD, NULL, &peak));
  if (header) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "level ranks  nodes assembly[s] schur[s] contact solve[s] iters  L/M1/M2/M3+/M3-/M4  separated/sliding/sticking reason peak[GB/rank]\n"));
  if (refine > 0) PetscCall(PetscSNPrintf(levelText, sizeof(levelText), "%" PetscInt_FMT "r%" PetscInt_FMT, hasMesh ? -1 : level, refine)); /* 4r1: level 4 refined once */
  else PetscCall(PetscSNPrintf(levelText, sizeof(levelText), "%" PetscInt_FMT, hasMesh ? -1 : level));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%5s %5d %6" PetscInt_FMT " %11.3f %8.3f %7" PetscInt_FMT " %8.3f %5" PetscInt_FMT "  %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT "  %" PetscInt_FMT "/%" PetscInt_FMT "/%" PetscInt_FMT " %s %.3f\n",
                        levelText, size, nnodes, (double)t_assembly, (double)t_schur, ncontact, (double)t_solve, its, counts[0], counts[1], counts[2], counts[3], counts[4], counts[5], counts[0], counts[1] + counts[2], counts[3] + counts[4] + counts[5],
                        SNESConvergedReasons[reason], peak / 1e9));

  /* the solution file says how the solve ended (its memory out of the Newton steps' freed work, not beside it); the
     reduced problem's u_C is written only as a solution */
  PetscCall(SNESSSStarReleaseWork(snes));
  if (hasOut) PetscCall(SSStarSceneWriteSolution(scene, snes, out, u, NULL, NULL));
  if (hasReduced && isssstar && reason > 0) PetscCall(SaveReduced(reduced, scene, snes, u));
  if (reason <= 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "The solve did not converge (%s): exit status %d%s\n", SNESConvergedReasons[reason], SSSTAR_EXIT_NOT_CONVERGED, hasReduced ? ", no -save_reduced file" : ""));

  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&u));
  PetscCall(MatDestroy(&body.K));
  PetscCall(VecDestroy(&body.b));
  PetscCall(SSStarSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : SSSTAR_EXIT_NOT_CONVERGED;
}
