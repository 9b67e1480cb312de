/*
   The contact nodes of a scene: the vertices of its contact groups that are not held in every component (-dirichlet,
   -displacement_<G>: prescribed.c), owned by this rank, in
   vertex order (their global dofs increase), each with its group (the first listed in -contact when it is in two groups
   whose obstacles agree at the node), its coordinates, its dofs and its tributary area. Their gaps, normals and rows
   of the contact operator come from their groups' contact sources (operator.c).
*/
#include "../sceneimpl.h"

/* SSStarSceneContactTolerance - "on the obstacle up to round-off": relative to the size of the body */
PetscErrorCode SSStarSceneContactTolerance(SSStarScene scene, PetscReal *tol)
{
  PetscReal gmin[3], gmax[3];

  PetscFunctionBegin;
  PetscCall(DMGetBoundingBox(scene->dm, gmin, gmax));
  *tol = 0;
  for (PetscInt k = 0; k < 3; k++) *tol += PetscSqr(gmax[k] - gmin[k]);
  *tol = 1e-10 * PetscSqrtReal(*tol);
  PetscFunctionReturn(0);
}

/* A Vec of bs values per owned contact node, in their order (the per-node vectors of the SNES) */
PetscErrorCode SSStarSceneNodeVec(SSStarScene scene, PetscInt bs, const PetscReal values[], Vec *v)
{
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecCreateMPI(scene->comm, bs * scene->n, PETSC_DETERMINE, v));
  if (bs > 1) PetscCall(VecSetBlockSize(*v, bs));
  PetscCall(VecGetArrayWrite(*v, &a));
  for (PetscInt i = 0; i < bs * scene->n; i++) a[i] = values[i];
  PetscCall(VecRestoreArrayWrite(*v, &a));
  PetscFunctionReturn(0);
}

/* Tributary area of every local vertex on the contact groups (a third of each adjacent face), in the x-dofs of a global vector */
static PetscErrorCode ContactAreas(SSStarScene scene, Vec *areas)
{
  const PetscReal unit[3] = {1, 0, 0};
  Vec             loc;

  PetscFunctionBegin;
  PetscCall(DMGetLocalVector(scene->dm, &loc));
  PetscCall(VecZeroEntries(loc));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(SSStarAddTraction(scene->dm, scene->contact[g].name, unit, loc));
  PetscCall(DMCreateGlobalVector(scene->dm, areas));
  PetscCall(VecZeroEntries(*areas));
  PetscCall(DMLocalToGlobal(scene->dm, loc, ADD_VALUES, *areas));
  PetscCall(DMRestoreLocalVector(scene->dm, &loc));
  PetscFunctionReturn(0);
}

/*
   SSStarSceneObstacleGaps - the gaps and normals of n points against the obstacles of their contact groups (group[i]
   < 0: none, left as they are). Collective: every rank asks each group's obstacle, with its points of the group (a
   mesh obstacle's triangles are spread over the ranks).
*/
PetscErrorCode SSStarSceneObstacleGaps(SSStarScene scene, PetscInt n, const PetscInt group[], const PetscReal x[], PetscReal tol, PetscReal gap[], PetscReal normal[])
{
  PetscInt  *at;
  PetscReal *xg, *gg, *ng;

  PetscFunctionBegin;
  PetscCall(PetscMalloc4(n + 1, &at, 3 * n + 1, &xg, n + 1, &gg, 3 * n + 1, &ng));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    PetscInt m = 0;

    for (PetscInt i = 0; i < n; i++)
      if (group[i] == g) {
        at[m] = i;
        PetscCall(PetscArraycpy(&xg[3 * m++], &x[3 * i], 3));
      }
    PetscCall(SSStarObstacleGaps(scene->contact[g].obstacle, m, xg, tol, gg, ng));
    for (PetscInt j = 0; j < m; j++) {
      gap[at[j]] = gg[j];
      PetscCall(PetscArraycpy(&normal[3 * at[j]], &ng[3 * j], 3));
    }
  }
  PetscCall(PetscFree4(at, xg, gg, ng));
  PetscFunctionReturn(0);
}

/* The nodes in two contact groups (group[2 e], group[2 e + 1] for node e at x[3 e]): the first whose obstacles differ
   there (gap or normal), or none */
static PetscErrorCode SharedNodes(SSStarScene scene, PetscInt n, const PetscInt tag[], const PetscInt group[], const PetscReal x[], PetscReal tol, SSStarBadNode *twice)
{
  PetscInt  *ga, *gb;
  PetscReal *gap, *normal;

  PetscFunctionBegin;
  PetscCall(PetscMalloc4(n + 1, &ga, n + 1, &gb, 2 * n + 1, &gap, 6 * n + 1, &normal));
  for (PetscInt e = 0; e < n; e++) {
    ga[e] = group[2 * e];
    gb[e] = group[2 * e + 1];
  }
  PetscCall(SSStarSceneObstacleGaps(scene, n, ga, x, tol, gap, normal));
  PetscCall(SSStarSceneObstacleGaps(scene, n, gb, x, tol, &gap[n], &normal[3 * n]));
  for (PetscInt e = 0; e < n && twice->tag < 0; e++) {
    const PetscReal *na = &normal[3 * e], *nb = &normal[3 * (n + e)];

    if (PetscAbsReal(na[0] - nb[0]) + PetscAbsReal(na[1] - nb[1]) + PetscAbsReal(na[2] - nb[2]) <= 1e-12 && PetscAbsReal(gap[e] - gap[n + e]) <= tol) continue;
    twice->tag   = tag[e];
    twice->group = group[2 * e];
    twice->other = group[2 * e + 1];
    PetscCall(PetscArraycpy(twice->x, &x[3 * e], 3));
  }
  PetscCall(PetscFree4(ga, gb, gap, normal));
  PetscFunctionReturn(0);
}

/* SSStarSceneFindContactNodes - the owned contact nodes (tag, group, coordinates, dofs, area), the nodes per group */
PetscErrorCode SSStarSceneFindContactNodes(SSStarScene scene)
{
  DM                 dm = scene->dm, cdm;
  DMLabel           *labels;
  PetscSection       sec, gsec, csec;
  PetscInt           vStart, vEnd, n = 0, *dofs, rstart, nshared = 0, maxShared, *sharedTag, *sharedGroup;
  PetscReal         *sharedX;
  Vec                coordinates, areas;
  const PetscScalar *ta, *xa, *aa;
  PetscReal          tol;
  SSStarBadNode      twice = {-1, -1, -1, {0, 0, 0}, 0};
  PetscBool          found;

  PetscFunctionBegin;
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(ContactAreas(scene, &areas));
  PetscCall(PetscMalloc1(scene->nContact, &labels));
  for (PetscInt g = 0; g < scene->nContact; g++) PetscCall(DMGetLabel(dm, scene->contact[g].name, &labels[g]));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(PetscMalloc4(vEnd - vStart, &scene->tag, vEnd - vStart, &scene->group, 3 * (vEnd - vStart), &scene->coords, 3 * (vEnd - vStart), &scene->normal));
  PetscCall(PetscMalloc2(vEnd - vStart, &scene->gap, vEnd - vStart, &scene->area));
  PetscCall(PetscFree(scene->contactHeld));
  PetscCall(PetscMalloc1(3 * (vEnd - vStart) + 1, &scene->contactHeld));
  PetscCall(PetscMalloc1(3 * (vEnd - vStart), &dofs));
  maxShared = PetscMax(0, scene->nContact - 1) * (vEnd - vStart); /* a node in k groups: k - 1 pairs to compare */
  PetscCall(PetscMalloc3(maxShared + 1, &sharedTag, 2 * maxShared + 1, &sharedGroup, 3 * maxShared + 1, &sharedX));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetArrayRead(areas, &aa));
  PetscCall(VecGetOwnershipRange(areas, &rstart, NULL));
  for (PetscInt g = 0; g < scene->nContact; g++) scene->contact[g].nodes = 0;
  /* vertices in point order have increasing global offsets, so the dofs are sorted */
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt        off, ncon, coff, group = -1;
    PetscReal       x[3];
    const PetscInt *held = &scene->heldBy[3 * (v - vStart)];

    PetscCall(PetscSectionGetOffset(gsec, v, &off));
    PetscCall(PetscSectionGetConstraintDof(sec, v, &ncon));
    if (off < 0 || ncon || (held[0] >= 0 && held[1] >= 0 && held[2] >= 0)) continue; /* not owned, or held in every component */
    PetscCall(PetscSectionGetOffset(csec, v, &coff));
    for (PetscInt k = 0; k < 3; k++) x[k] = PetscRealPart(xa[coff + k]);
    for (PetscInt g = 0; g < scene->nContact; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(labels[g], v, &value));
      if (value < 0) continue;
      if (group < 0) {
        group = g;
        continue;
      }
      /* in two groups: their obstacles must agree at the node (SharedNodes()) */
      sharedTag[nshared]           = (PetscInt)PetscRealPart(ta[v - vStart]);
      sharedGroup[2 * nshared]     = group;
      sharedGroup[2 * nshared + 1] = g;
      PetscCall(PetscArraycpy(&sharedX[3 * nshared++], x, 3));
    }
    if (group < 0) continue;
    scene->tag[n]   = (PetscInt)PetscRealPart(ta[v - vStart]);
    scene->group[n] = group;
    scene->area[n]  = PetscRealPart(aa[off - rstart]); /* in the x-dof */
    for (PetscInt k = 0; k < 3; k++) {
      scene->coords[3 * n + k]      = x[k];
      dofs[3 * n + k]               = off + k;
      scene->contactHeld[3 * n + k] = held[k];
    }
    scene->contact[group].nodes++;
    n++;
  }
  PetscCall(VecRestoreArrayRead(areas, &aa));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecDestroy(&areas));
  PetscCall(PetscFree(labels));
  scene->n = n;
  PetscCall(ISCreateGeneral(scene->comm, 3 * n, dofs, PETSC_OWN_POINTER, &scene->isC));

  PetscCall(SharedNodes(scene, nshared, sharedTag, sharedGroup, sharedX, tol, &twice));
  PetscCall(PetscFree3(sharedTag, sharedGroup, sharedX));
  PetscCall(SSStarSceneShareBadNode(scene->comm, &twice, &found));
  PetscCheck(!found, scene->comm, PETSC_ERR_ARG_WRONG, "Mesh node %" PetscInt_FMT " (0-based, file order) at (%g, %g, %g) is in the contact groups \"%s\" and \"%s\" whose obstacles (-obstacle_%s, -obstacle_%s) differ at this node: a node touches one obstacle", twice.tag, (double)twice.x[0], (double)twice.x[1], (double)twice.x[2], scene->contact[twice.group].name, scene->contact[twice.other].name, scene->contact[twice.group].name, scene->contact[twice.other].name);
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactGroup *cg = &scene->contact[g];

    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cg->nodes, 1, MPIU_INT, MPI_SUM, scene->comm));
    PetscCheck(cg->nodes > 0, scene->comm, PETSC_ERR_ARG_WRONG, "Contact group \"%s\" (option -contact) has no nodes once the nodes held in every component (-dirichlet, -displacement_<G>) are removed", cg->name);
  }
  PetscCall(MPIU_Allreduce(&n, &scene->nGlobal, 1, MPIU_INT, MPI_SUM, scene->comm));
  PetscFunctionReturn(0);
}
