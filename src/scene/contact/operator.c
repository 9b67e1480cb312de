/*
   The contact operator of a scene (docs/contact-operator.md): every contact node i, whatever its contact source, is a
   row block B_i = R_i (E_i - sum_j w_ij E_{m_j}) with an initial gap g_i, so that w_i = B_i u + g_i is its relative
   displacement in its frame R_i (rows t1, t2, n), w_n >= 0. Each source gives its nodes' gap, normal and masters:

     a rigid obstacle (obstacle.c, obstacles/)  the node's gap and normal from the shape, no masters;
     a contact pair (pairs.c, mortar.c)         the master surface's normal and gap, the master vertices and weights
                                                (node-to-surface: the closest master triangle; dual mortar: M's row / D).

   The scene declares its contact to the solver through B alone (SNESSSStarSetContactOperator()).
*/
#include "../sceneimpl.h"

/*
   The rows of the nodes of rigid obstacles: gap and normal from the shape, at the positions x (3 per node) against the
   obstacles where their motions put them in the step (motion.c), and the point of the obstacle each node faces (where
   the obstacle's option puts it: its friction sees that point move); at the reference configuration (reference)
   refuses a node that starts inside its obstacle
*/
static PetscErrorCode ObstacleRows(SSStarScene scene, const PetscReal x[], PetscBool reference, PetscReal tol)
{
  SSStarBadNode inside = {-1, -1, -1, {0, 0, 0}, 0};
  PetscBool     found;
  PetscInt     *group;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(scene->n + 1, &group));
  if (!scene->obstaclePoint) PetscCall(PetscCalloc1(3 * scene->n + 1, &scene->obstaclePoint));
  for (PetscInt i = 0; i < scene->n; i++) group[i] = scene->contact[scene->group[i]].master[0] ? -1 : scene->group[i];
  PetscCall(SSStarSceneObstacleGaps(scene, scene->n, group, x, NULL, tol, scene->gap, scene->normal));
  for (PetscInt i = 0; i < scene->n; i++) {
    const SSStarMotion *motion = &scene->contact[scene->group[i]].motion;
    PetscReal           y[3];

    if (group[i] < 0) continue;
    for (PetscInt k = 0; k < 3; k++) y[k] = x[3 * i + k] - scene->gap[i] * scene->normal[3 * i + k]; /* the closest point */
    SSStarPlacementInverse(&motion->now, motion->center, y, &scene->obstaclePoint[3 * i]);
    if (reference && scene->gap[i] < -tol && inside.tag < 0) {
      inside.tag   = scene->tag[i];
      inside.group = scene->group[i];
      inside.gap   = scene->gap[i];
      PetscCall(PetscArraycpy(inside.x, &scene->coords[3 * i], 3));
    }
    if (PetscAbsReal(scene->gap[i]) <= tol) scene->gap[i] = 0.0; /* on the obstacle up to round-off: touching */
  }
  PetscCall(PetscFree(group));
  PetscCall(SSStarSceneShareBadNode(scene->comm, &inside, &found));
  PetscCheck(!found, scene->comm, PETSC_ERR_ARG_OUTOFRANGE, "Mesh node %" PetscInt_FMT " (0-based, file order) of contact group \"%s\" at (%g, %g, %g) starts %g inside the obstacle of -obstacle_%s (%s)", inside.tag, scene->contact[inside.group].name, (double)inside.x[0], (double)inside.x[1], (double)inside.x[2], (double)-inside.gap, scene->contact[inside.group].name, SSStarObstacleInsideHint(scene->contact[inside.group].obstacle));
  PetscFunctionReturn(0);
}

/* The masters of every node as compressed rows (masterStart, masterDof, masterWeight), in the order they were added */
static PetscErrorCode CompressMasters(SSStarScene scene, const SSStarMasters *m)
{
  PetscInt *next;

  PetscFunctionBegin;
  PetscCall(PetscFree3(scene->masterStart, scene->masterDof, scene->masterWeight));
  PetscCall(PetscMalloc3(scene->n + 1, &scene->masterStart, m->n + 1, &scene->masterDof, m->n + 1, &scene->masterWeight));
  PetscCall(PetscArrayzero(scene->masterStart, scene->n + 1));
  for (PetscInt e = 0; e < m->n; e++) scene->masterStart[m->node[e] + 1]++;
  for (PetscInt i = 0; i < scene->n; i++) scene->masterStart[i + 1] += scene->masterStart[i];
  PetscCall(PetscMalloc1(scene->n + 1, &next));
  PetscCall(PetscArraycpy(next, scene->masterStart, scene->n + 1));
  for (PetscInt e = 0; e < m->n; e++) {
    const PetscInt at = next[m->node[e]]++;

    scene->masterDof[at]    = m->dof[e];
    scene->masterWeight[at] = m->weight[e];
  }
  PetscCall(PetscFree(next));
  PetscFunctionReturn(0);
}

/* B from the frames and the masters: R_i at the node's own dofs, -w_ij R_i at the dofs of its master m_j */
static PetscErrorCode AssembleOperator(SSStarScene scene)
{
  PetscInt        m, rstart, cstart, cend, *dnz, *onz, remote = 0;
  const PetscInt *own;
  Vec             x;

  PetscFunctionBegin;
  PetscCall(DMCreateGlobalVector(scene->dm, &x));
  PetscCall(VecGetLocalSize(x, &m));
  PetscCall(VecGetOwnershipRange(x, &cstart, &cend));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscMalloc2(3 * scene->n + 1, &dnz, 3 * scene->n + 1, &onz));
  for (PetscInt i = 0; i < scene->n; i++) {
    PetscInt d = 3, o = 0;

    for (PetscInt e = scene->masterStart[i]; e < scene->masterStart[i + 1]; e++) {
      if (scene->masterDof[e] >= cstart && scene->masterDof[e] < cend) d += 3;
      else o += 3;
    }
    for (PetscInt c = 0; c < 3; c++) {
      dnz[3 * i + c] = d;
      onz[3 * i + c] = o;
    }
    remote += o > 0;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &remote, 1, MPIU_INT, MPI_SUM, scene->comm));
  PetscCall(PetscInfo(NULL, "contact operator: %" PetscInt_FMT " of %" PetscInt_FMT " contact nodes compared with master vertices of other ranks\n", remote, scene->nGlobal));
  PetscCall(MatDestroy(&scene->B));
  PetscCall(MatCreate(scene->comm, &scene->B));
  PetscCall(MatSetSizes(scene->B, 3 * scene->n, m, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(scene->B, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(scene->B, 0, dnz));
  PetscCall(MatMPIAIJSetPreallocation(scene->B, 0, dnz, 0, onz));
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(MatGetOwnershipRange(scene->B, &rstart, NULL));
  PetscCall(ISGetIndices(scene->isC, &own));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscReal *R = &scene->frame[9 * i];

    for (PetscInt c = 0; c < 3; c++) {
      const PetscInt row = rstart + 3 * i + c;

      for (PetscInt k = 0; k < 3; k++) PetscCall(MatSetValue(scene->B, row, own[3 * i + k], R[3 * c + k], ADD_VALUES));
      for (PetscInt e = scene->masterStart[i]; e < scene->masterStart[i + 1]; e++)
        for (PetscInt k = 0; k < 3; k++)
          if (R[3 * c + k] != 0) PetscCall(MatSetValue(scene->B, row, scene->masterDof[e] + k, -scene->masterWeight[e] * R[3 * c + k], ADD_VALUES));
    }
  }
  PetscCall(ISRestoreIndices(scene->isC, &own));
  PetscCall(MatAssemblyBegin(scene->B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(scene->B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/*
   SSStarSceneBuildContactOperator - the rows of B of every contact node from its group's contact source (gap, normal,
   masters), the frames and B: at the reference configuration (u NULL; then also the gap range of each group), or at
   the configuration displaced by u (a global displacement) with the obstacles where their motions put them in the
   step (large sliding, sliding.c): the gaps are then those of the displaced nodes
*/
PetscErrorCode SSStarSceneBuildContactOperator(SSStarScene scene, Vec u)
{
  SSStarMasters masters = {0, 0, NULL, NULL, NULL};
  PetscReal     tol, *x;

  PetscFunctionBegin;
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(PetscMalloc1(3 * scene->n + 1, &x)); /* the positions of the contact nodes */
  PetscCall(PetscArraycpy(x, scene->coords, 3 * scene->n));
  if (u) {
    const PetscScalar *ua;
    Vec                uC;

    PetscCall(VecGetSubVector(u, scene->isC, &uC));
    PetscCall(VecGetArrayRead(uC, &ua));
    for (PetscInt k = 0; k < 3 * scene->n; k++) x[k] += PetscRealPart(ua[k]);
    PetscCall(VecRestoreArrayRead(uC, &ua));
    PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  }
  for (PetscInt i = 0; i < scene->n; i++) { /* a pair's node without a master triangle keeps these (refused later) */
    scene->gap[i]            = 0;
    scene->normal[3 * i]     = 0;
    scene->normal[3 * i + 1] = 0;
    scene->normal[3 * i + 2] = 1;
  }
  PetscCall(ObstacleRows(scene, x, (PetscBool)!u, tol));
  scene->pairFallback = 0;
  for (PetscInt g = 0; g < scene->nContact; g++)
    if (scene->contact[g].master[0]) PetscCall(SSStarPairRows(scene, g, x, u, &masters));
  PetscCall(PetscFree(x));
  PetscCall(CompressMasters(scene, &masters));
  PetscCall(SSStarMastersDestroy(&masters));
  PetscCall(PetscFree(scene->frame));
  PetscCall(PetscMalloc1(9 * scene->n + 1, &scene->frame));
  for (PetscInt i = 0; i < scene->n; i++) SSStarNodeFrame(&scene->normal[3 * i], &scene->frame[9 * i]);
  if (!u) { /* the reference's gaps, which the output keeps as the initial gaps */
    PetscCall(PetscFree(scene->gapInitial));
    PetscCall(PetscMalloc1(scene->n + 1, &scene->gapInitial));
    PetscCall(PetscArraycpy(scene->gapInitial, scene->gap, scene->n));
  }
  for (PetscInt g = 0; g < scene->nContact && !u; g++) {
    SSStarContactGroup *cg       = &scene->contact[g];
    PetscReal           range[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL};

    for (PetscInt i = 0; i < scene->n; i++)
      if (scene->group[i] == g) {
        range[0] = PetscMin(range[0], scene->gap[i]);
        range[1] = PetscMin(range[1], -scene->gap[i]);
      }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 2, MPIU_REAL, MPIU_MIN, scene->comm));
    cg->gapMin = range[0];
    cg->gapMax = -range[1];
  }
  PetscCall(AssembleOperator(scene));
  PetscFunctionReturn(0);
}

/*@C
   SSStarSceneSetContact - declares the contact of the scene to an "ssstar" SNES: the contact operator B of every
   contact node (SNESSSStarSetContactOperator(): a rigid obstacle's node in the frame of the obstacle's normal, a pair's
   slave node against the master surface, node-to-surface or dual mortar, -pair_discretization), their initial gaps,
   the friction laws of their groups, and the verdict of the memory estimate printed before the work on the
   multigrid's aggregation (SNESSSStarSetSmoothedAggregationFits())

   Collective

   Input Parameters:
+  scene - the scene, after SSStarSceneSetUp(), with contact groups
-  snes  - an SNES of type ssstar

   Notes:
   A group's -<parameter>_<G> (-friction_<G>, -slip_bound_<G>, -friction_1_<G>, ...: every parameter of the table of
   laws) gives its nodes their own value (SNESSSStarSetNodeLawParameter()); the nodes of groups without one keep the
   solver's (SNESSSStarSetLawParameter(), -snes_ssstar_<parameter>: coulomb's friction 0.3 by default), whether it is
   set before or after this call (their entries are SSSTAR_NOT_GIVEN). One law for all groups is set with
   SNESSSStarSetFrictionLaw(), several with SNESSSStarSetNodeFrictionLaws().

   Level: beginner

.seealso: `SNESSSStarSetContactOperator()`, `SSStarSceneWriteSolution()`
@*/
PetscErrorCode SSStarSceneSetContact(SSStarScene scene, SNES snes)
{
  Vec       gaps = NULL;
  PetscBool anyGap = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCheck(scene->nContact > 0, scene->comm, PETSC_ERR_ARG_WRONGSTATE, "The scene has no contact group (-contact): solve K u = b without ssstar");
  for (PetscInt i = 0; i < scene->n; i++)
    if (scene->gap[i] != 0) anyGap = PETSC_TRUE;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &anyGap, 1, MPIU_BOOL, MPI_LOR, scene->comm));
  if (anyGap) PetscCall(SSStarSceneNodeVec(scene, 1, scene->gap, &gaps));
  PetscCall(SNESSSStarSetContactOperator(snes, scene->isC, scene->B, gaps));
  PetscCall(VecDestroy(&gaps));
  PetscCall(SSStarSceneSetContactLaws(scene, snes)); /* grouplaws.c */
  PetscCall(SNESSSStarSetSmoothedAggregationFits(snes, scene->smoothedFits));
  if (scene->progress) PetscCall(SNESSSStarMonitorProgressAdd(snes));
  PetscFunctionReturn(0);
}
