/*
   Nested iteration: the contact problem solved on coarser meshes first, each solution carried to the next finer mesh
   (SSStarMeshInterpolate(): P1 by point location) as the start of its iteration, so that the finest mesh needs a few
   Newton steps instead of a dozen. The coarser meshes are the scene's own: one refinement fewer (-dm_refine), else
   the level of -geo halved (the prism's levels nest: level L's nodes are level 2L's). The coarse solves are quiet (no
   monitors, no views) and looser (SSSTAR_NESTED_RTOL); the finest solve is the user's, to the user's tolerance.
   Where the finest mesh aggregates plainly below the default size (SSSTAR_PLAIN_AGGREGATION_DOFS: because its estimate
   found no room for the smoothed aggregation, or a lowered -snes_ssstar_plain_aggregation_dofs asks for the memory
   lever), the coarse solves take the memory's side too: on the whole body with plain aggregation. auto would solve the
   coarsest mesh (up to 20 000 dofs) on the dense route, whose factors of its K outgrow such a finest mesh's plain
   solve (prism level 12 on 2 ranks: 0.19 GB per rank at the peak where the plain estimate is 0.148; measured 0.155 on
   the whole body); from the default size on, the coarsest mesh is a tenth of the finest and its dense solve fits
   beside the finest one's plain set-up (the estimate within 2 % at level 16).
*/
#include "sceneimpl.h"
#include "../sys/meminfo.h"

/* auto starts from a coarser mesh above this many dofs of K (the crossover measured: docs/guide/large-problems.md, "Nested iteration") */
#define SSSTAR_AUTO_NESTED_MIN_DOFS 50000
/* auto's coarsest mesh has at most this many dofs of K (a problem of about a second on either route) */
#define SSSTAR_NESTED_COARSEST_DOFS 20000
/* the relative tolerance of the coarse solves: a start needs no more digits than the finer mesh changes */
#define SSSTAR_NESTED_RTOL 1e-6

/* The options of a solver that print: the coarse solves leave them out */
static const char *const Printing[] = {"snes_view", "snes_monitor", "snes_monitor_short", "snes_converged_reason", "snes_ssstar_monitor_states", "snes_ssstar_monitor_progress", "ksp_monitor", "ksp_monitor_short", "ksp_monitor_true_residual", "ksp_view", "ksp_converged_reason", "snes_view_pre", "snes_linesearch_monitor", NULL};

/* Whether the scene's mesh has a coarser one: a refinement to undo, or a level of -geo to halve */
static PetscBool HasCoarser(SSStarScene scene)
{
  return (PetscBool)(scene->refine > 0 || (scene->geo[0] && scene->level >= 2));
}

/* The scene of the next coarser mesh: the same options, one refinement fewer, else the level of -geo halved */
static PetscErrorCode CreateCoarse(SSStarScene fine, SSStarScene *coarse)
{
  PetscFunctionBegin;
  PetscCall(SSStarSceneCreate(fine->comm, coarse));
  PetscCall(SSStarSceneSetFromOptions(*coarse));
  (*coarse)->progress = PETSC_FALSE;
  if (fine->refine > 0) {
    (*coarse)->refine = fine->refine - 1;
    (*coarse)->level  = fine->level;
  } else (*coarse)->level = fine->level / 2;
  PetscFunctionReturn(0);
}

/* A copy of the options database without the options that print (with the SNES's prefix) */
static PetscErrorCode QuietOptions(SNES snes, PetscOptions *quiet)
{
  char        *all;
  PetscOptions options;
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetOptions((PetscObject)snes, &options));
  PetscCall(PetscOptionsGetAll(options, &all));
  PetscCall(PetscOptionsCreate(quiet));
  PetscCall(PetscOptionsInsertString(*quiet, all));
  PetscCall(PetscFree(all));
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  for (PetscInt k = 0; Printing[k]; k++) {
    char name[256];

    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefix ? prefix : "", Printing[k]));
    PetscCall(PetscOptionsClearValue(*quiet, name));
  }
  PetscFunctionReturn(0);
}

/* The number of coarser meshes to solve first: -nested_levels, or auto's choice for this K and solver */
static PetscErrorCode NestedLevels(SSStarScene scene, SNES snes, PetscInt *levels)
{
  SSStarReductionType type;
  PetscBool           isauto, isnone;
  PetscInt            dofs;
  Vec                 v;

  PetscFunctionBegin;
  *levels = 0;
  if (!HasCoarser(scene)) PetscFunctionReturn(0);
  if (scene->nested >= 0) {
    *levels = scene->nested;
    PetscFunctionReturn(0);
  }
  PetscCall(SNESSSStarGetReductionType(snes, &type));
  PetscCall(PetscStrcmp(type, SSSTARREDUCTIONAUTO, &isauto));
  PetscCall(PetscStrcmp(type, SSSTARREDUCTIONNONE, &isnone));
  PetscCall(DMGetGlobalVector(scene->dm, &v));
  PetscCall(VecGetSize(v, &dofs));
  PetscCall(DMRestoreGlobalVector(scene->dm, &v));
  /* auto: on problems above SSSTAR_AUTO_NESTED_MIN_DOFS, coarser meshes down to SSSTAR_NESTED_COARSEST_DOFS; not for a
     hyperelastic scene: its coarse solves are as nonlinear as its own */
  if (!(isauto || isnone) || dofs < SSSTAR_AUTO_NESTED_MIN_DOFS || !scene->affine) PetscFunctionReturn(0);
  for (PetscReal d = dofs; d > SSSTAR_NESTED_COARSEST_DOFS; d /= 8) (*levels)++;
  PetscFunctionReturn(0);
}

/* A coarse solve of a finest mesh that aggregates plainly for the memory's sake: plain aggregation, and the whole body where auto chooses */
static PetscErrorCode FollowMemory(SNES coarse)
{
  SSStarReductionType type;
  PetscBool           isauto;

  PetscFunctionBegin;
  PetscCall(SNESSSStarSetSmoothedAggregationFits(coarse, PETSC_FALSE));
  PetscCall(SNESSSStarGetReductionType(coarse, &type));
  PetscCall(PetscStrcmp(type, SSSTARREDUCTIONAUTO, &isauto));
  if (isauto) PetscCall(SNESSSStarSetReductionType(coarse, SSSTARREDUCTIONNONE));
  PetscFunctionReturn(0);
}

/* The solution on the coarser mesh of fine (itself started from levels - 1 coarser ones), interpolated into u */
static PetscErrorCode SolveCoarse(SSStarScene fine, SNES snes, PetscInt levels, Vec u, SNESConvergedReason *reason, PetscInt *its, PetscInt *nodes)
{
  SSStarScene         coarse;
  SNES                sc;
  PetscOptions        quiet;
  Mat                 K;
  Vec                 b, uc;
  const char         *prefix;
  PetscReal           atol, rtol, stol;
  PetscInt            maxit, maxf;
  SNESConvergedReason inner;
  PetscInt            innerIts, innerNodes;

  PetscFunctionBegin;
  PetscCall(CreateCoarse(fine, &coarse));
  PetscCall(SSStarSceneSetUp(coarse));
  PetscCall(SSStarSceneAssemble(coarse, &K, &b));
  PetscCall(QuietOptions(snes, &quiet));
  PetscCall(SNESCreate(fine->comm, &sc));
  PetscCall(PetscObjectSetOptions((PetscObject)sc, quiet));
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  PetscCall(SNESSetOptionsPrefix(sc, prefix));
  PetscCall(SNESSetType(sc, SNESSSSTAR));
  PetscCall(SNESSetFromOptions(sc));
  PetscCall(SNESGetTolerances(snes, &atol, &rtol, &stol, &maxit, &maxf));
  PetscCall(SNESSetTolerances(sc, atol, PetscMax(rtol, SSSTAR_NESTED_RTOL), stol, maxit, maxf));
  PetscCall(SSStarSceneSetProblem(coarse, sc, K, b));
  PetscCall(SSStarSceneSetContact(coarse, sc));
  if (fine->plain && (!fine->smoothedFits || 3.0 * fine->nodesGlobal < SSSTAR_PLAIN_AGGREGATION_DOFS)) PetscCall(FollowMemory(sc));
  PetscCall(DMCreateGlobalVector(coarse->dm, &uc));
  PetscCall(VecZeroEntries(uc));
  if (levels > 1 && HasCoarser(coarse)) PetscCall(SolveCoarse(coarse, sc, levels - 1, uc, &inner, &innerIts, &innerNodes));
  PetscCall(SNESSolve(sc, NULL, uc));
  PetscCall(SNESGetConvergedReason(sc, reason));
  PetscCall(SNESGetIterationNumber(sc, its));
  *nodes = coarse->nodesGlobal;
  if (*reason > 0) { /* the start, and the load's scale: the finer mesh's solve needs no linear solve before its first Newton step */
    PetscCall(SSStarMeshInterpolate(coarse->dm, uc, fine->dm, u));
    PetscCall(SNESSSStarSetCoarseLoadScale(snes, sc));
  }
  PetscCall(VecDestroy(&uc));
  PetscCall(SNESDestroy(&sc));
  PetscCall(PetscOptionsDestroy(&quiet));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(SSStarSceneDestroy(&coarse));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSolveNested - the start of the scene's solve by nested iteration: the problem solved on the scene's
   coarser meshes first, each solution the start of the next finer one, the last interpolated into u

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetContact()
-  snes  - its solver (the coarse solves take its options, less those that print, and a looser tolerance)

   Output Parameter:
.  u - the start on the scene's mesh (unchanged when no coarser mesh is solved, or a coarse solve did not converge)

   Options Database Key:
.  -nested_levels <auto> - the coarser meshes to solve first: 0 none; auto (the default) those that halve the mesh
   size down to 20 000 dofs of K (a problem of about a second), on problems above 50 000 dofs solved on the whole
   body (-snes_ssstar_reduction none) or by auto, of linear scenes

   Notes:
   A coarser mesh is the scene's with one refinement fewer (-dm_refine), else -geo at half the level. The finest
   solve (the caller's SNESSolve() from u) decides the answer: nested iteration changes its start, not its tolerance.
   Each finer mesh's solver gets the load's scale of the coarser one's solve with its start
   (SNESSSStarSetCoarseLoadScale()): on the whole body it solves no linear system before its first Newton step.

   Level: intermediate

.seealso: `SSStarSceneSetContact()`, `SSStarSceneSetUp()`
@*/
PetscErrorCode SSStarSceneSolveNested(SSStarScene scene, SNES snes, Vec u)
{
  PetscInt            levels, its = 0, nodes = 0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  PetscLogDouble      t;
  char                line[256];

  PetscFunctionBegin;
  PetscCall(NestedLevels(scene, snes, &levels));
  if (!levels) PetscFunctionReturn(0);
  PetscCall(PetscTime(&t));
  PetscCall(SolveCoarse(scene, snes, levels, u, &reason, &its, &nodes));
  PetscCall(PetscSNPrintf(line, sizeof(line), "nested: %" PetscInt_FMT " coarser mesh%s, the finest of %" PetscInt_FMT " nodes in %" PetscInt_FMT " iterations (%s)%s", levels, levels > 1 ? "es" : "", nodes, its, SNESConvergedReasons[reason], reason > 0 ? ", interpolated" : ": not used"));
  PetscCall(SSStarSceneProgress(scene, &t, line));
  PetscFunctionReturn(0);
}
