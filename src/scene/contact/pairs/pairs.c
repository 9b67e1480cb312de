/*
   Two deformable bodies (docs/guide/scenes.md, "Two bodies"): -contact_pair_<G> H makes the contact group G (the slave surface) meet
   the surface group H (the master) of another body. Node-to-surface: each slave node is projected onto the closest
   master triangle; its contact point compares the slave node with the master surface interpolated there (P1: the
   barycentric coordinates of the projection), in the frame of the master normal, with the normal distance as gap:
   B_i = R_i (E_{s_i} - sum_j w_ij E_{m_j}) (docs/contact-operator.md). Dual mortar (-pair_discretization dual_mortar,
   mortar.c) replaces the weights of the slave nodes the master covers. Frames and gaps at the reference configuration,
   or on a load path with large sliding at the current one of each step (sliding.c).
*/
#include "master.h"

const char *const SSStarPairDiscretizations[] = {"node_to_surface", "dual_mortar"};

/* -contact_pair_<G> H: the master surface of the contact group G */
PetscErrorCode SSStarPairsReadOption(SSStarScene scene, SSStarContactGroup *cg, const char option[])
{
  PetscBool set, same;

  PetscFunctionBegin;
  cg->master[0] = 0;
  PetscCall(PetscOptionsGetString(NULL, NULL, option, cg->master, sizeof(cg->master), &set));
  PetscCheck(cg->master[0], scene->comm, PETSC_ERR_ARG_WRONG, "Option %s needs the name of the master surface group H (-contact_pair_<G> H)", option);
  PetscCall(PetscStrcmp(cg->master, cg->name, &same));
  PetscCheck(!same, scene->comm, PETSC_ERR_ARG_WRONG, "Option %s %s: a surface cannot be its own master (the pair's groups must be on two bodies)", option, cg->master);
  scene->nPairs++;
  PetscFunctionReturn(0);
}

/* Contradictions of the pairs, once every option is read: an obstacle and a master for one group, a master that is a slave */
PetscErrorCode SSStarPairsCheckOptions(SSStarScene scene)
{
  PetscInt  method = SSSTAR_PAIR_NODE_TO_SURFACE;
  PetscBool set;

  PetscFunctionBegin;
  PetscCall(PetscOptionsGetEList(NULL, NULL, "-pair_discretization", SSStarPairDiscretizations, 2, &method, &set));
  scene->pairMethod = (SSStarPairDiscretization)method;
  for (PetscInt g = 0; g < scene->nContact; g++) {
    const SSStarContactGroup *cg = &scene->contact[g];
    char                      option[SSSTAR_GROUP_NAME_LEN + 16];
    PetscBool                 has, same;

    if (!cg->master[0]) continue;
    PetscCall(PetscSNPrintf(option, sizeof(option), "-obstacle_%s", cg->name));
    PetscCall(PetscOptionsHasName(NULL, NULL, option, &has));
    PetscCheck(!has, scene->comm, PETSC_ERR_ARG_WRONG, "Options -contact_pair_%s and %s contradict each other: the contact group \"%s\" meets either a rigid obstacle or a master surface", cg->name, option, cg->name);
    for (PetscInt h = 0; h < scene->nContact; h++) {
      PetscCall(PetscStrcmp(cg->master, scene->contact[h].name, &same));
      PetscCheck(!same, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the master \"%s\" is a contact group itself (in -contact); a surface is a slave or a master, not both", cg->name, cg->master, cg->master);
    }
    for (PetscInt d = 0; d < scene->nDirichlet; d++) {
      PetscCall(PetscStrcmp(cg->master, scene->dirichlet[d], &same));
      PetscCheck(!same, scene->comm, PETSC_ERR_ARG_WRONG, "Options -contact_pair_%s %s and -dirichlet contradict each other: the master \"%s\" is held fixed (use -obstacle_%s for a rigid obstacle)", cg->name, cg->master, cg->master, cg->name);
    }
  }
  PetscFunctionReturn(0);
}

/* The body of each owned contact node, through its file index */
static PetscErrorCode NodeBodies(SSStarScene scene, PetscInt **nodeBody)
{
  PetscInt           vStart, vEnd, *vtag, *vidx;
  const PetscScalar *ta;

  PetscFunctionBegin;
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc2(vEnd - vStart + 1, &vtag, vEnd - vStart + 1, &vidx));
  PetscCall(PetscMalloc1(scene->n + 1, nodeBody));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt v = 0; v < vEnd - vStart; v++) {
    vtag[v] = (PetscInt)PetscRealPart(ta[v]);
    vidx[v] = v;
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(PetscSortIntWithArray(vEnd - vStart, vtag, vidx));
  for (PetscInt i = 0; i < scene->n; i++) {
    PetscInt k;

    PetscCall(PetscFindInt(scene->tag[i], vEnd - vStart, vtag, &k));
    PetscCheck(k >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Contact node %" PetscInt_FMT " is not a local vertex", scene->tag[i]);
    (*nodeBody)[i] = scene->body[vidx[k]];
  }
  PetscCall(PetscFree2(vtag, vidx));
  PetscFunctionReturn(0);
}

/*
   SSStarPairRows - the rows of B of the slave nodes of pair g: each node's closest master triangle (over the ranks; of
   the triangles within the contact tolerance of the closest distance, the first by sorted file indices) gives its
   normal (the triangle's, out of the master body; where the node lies beyond the master's rim, the direction from the
   closest point), its gap and its master weights; with dual mortar, the mortar rows where the master covers the node
   (mortar.c). At the configuration of x (3 per contact node: the slave nodes' positions) and u (the displacement of
   the master surface: a global displacement, or NULL for the reference). Refuses a pair whose two groups are on one
   body, and a master group without triangles.
*/
PetscErrorCode SSStarPairRows(SSStarScene scene, PetscInt g, const PetscReal xs[], Vec u, SSStarMasters *masters)
{
  const SSStarContactGroup *cg = &scene->contact[g];
  PetscInt                  ntri, bad = -1, *nodeBody, nbodies, *bodies, np = 0, *at;
  SSStarSearch              search;
  SSStarSearchHit          *hit;
  PetscBool                *mortar;
  PetscReal                 tol, *p, *data;

  PetscFunctionBegin;
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(SSStarMasterSearchCreate(scene, g, u, &search, &nbodies, &bodies));
  PetscCall(SSStarSearchGetSize(search, NULL, &ntri, NULL));
  if (!ntri) {
    PetscCall(SSStarSearchDestroy(&search));
    PetscCall(PetscFree(bodies));
  }
  PetscCheck(ntri > 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the master group has no triangles", cg->name, cg->master);
  PetscCall(NodeBodies(scene, &nodeBody));
  PetscCall(PetscMalloc3(scene->n + 1, &at, 3 * scene->n + 1, &p, scene->n + 1, &mortar));
  for (PetscInt i = 0; i < scene->n; i++) {
    PetscInt found;

    mortar[i] = PETSC_FALSE;
    if (scene->group[i] != g) continue;
    PetscCall(PetscFindInt(nodeBody[i], nbodies, bodies, &found));
    if (found >= 0 && bad < 0) bad = scene->tag[i];
    at[np] = i;
    PetscCall(PetscArraycpy(&p[3 * np++], &xs[3 * i], 3));
  }
  PetscCall(PetscFree(nodeBody));
  PetscCall(PetscFree(bodies));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, scene->comm));
  if (bad >= 0) {
    PetscCall(SSStarSearchDestroy(&search));
    PetscCall(PetscFree3(at, p, mortar));
  }
  PetscCheck(bad < 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the groups \"%s\" and \"%s\" are on the same body (a contact pair is between two bodies: meshes that do not share nodes)", cg->name, cg->master, cg->name, cg->master);
  PetscCall(PetscMalloc2(np + 1, &hit, SSSTAR_MASTER_DATA * np + 1, &data));
  PetscCall(SSStarSearchClosest(search, np, p, tol, hit, data));
  for (PetscInt j = 0; j < np; j++) {
    const PetscInt       i = at[j];
    const PetscReal     *x = &xs[3 * i], *w = hit[j].w;
    SSStarMasterTriangle t;
    PetscReal            c[3], dc[3], n[3], len = 0, gap = 0;

    SSStarMasterTriangleFromHit(&hit[j], &data[SSSTAR_MASTER_DATA * j], &t);
    for (PetscInt k = 0; k < 3; k++) {
      c[k]  = w[0] * t.x[k] + w[1] * t.x[3 + k] + w[2] * t.x[6 + k];
      dc[k] = x[k] - c[k];
      len += dc[k] * dc[k];
      gap += dc[k] * t.n[k];
    }
    len = PetscSqrtReal(len);
    /* inside the triangle (the normal projection), or on its rim within round-off: the face's normal and signed distance */
    if (PetscAbsReal(PetscAbsReal(gap) - len) <= tol * 1e2 + 1e-8 * len || len <= tol) {
      for (PetscInt k = 0; k < 3; k++) n[k] = t.n[k];
    } else if (gap > 0) { /* beyond the rim, outside: the direction from the closest point */
      for (PetscInt k = 0; k < 3; k++) n[k] = dc[k] / len;
      gap = len;
    } else {
      for (PetscInt k = 0; k < 3; k++) n[k] = t.n[k];
    }
    if (PetscAbsReal(gap) <= tol) gap = 0;
    scene->gap[i] = gap;
    for (PetscInt k = 0; k < 3; k++) scene->normal[3 * i + k] = n[k];
  }
  if (scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR) PetscCall(SSStarMortarRows(scene, g, xs, u, search, tol, mortar, masters));
  for (PetscInt j = 0; j < np; j++) { /* node-to-surface: the vertices of the closest triangle that move */
    const PetscReal *dof = &data[SSSTAR_MASTER_DATA * j + 3];

    if (mortar[at[j]]) continue;
    for (PetscInt k = 0; k < 3; k++)
      if (dof[k] >= 0 && hit[j].w[k] != 0) PetscCall(SSStarMastersAdd(masters, at[j], (PetscInt)dof[k], hit[j].w[k]));
  }
  PetscCall(PetscFree2(hit, data));
  PetscCall(PetscFree3(at, p, mortar));
  PetscCall(SSStarSearchDestroy(&search));
  PetscFunctionReturn(0);
}
