/*
   Two deformable bodies (README "Two bodies"): -contact_pair_<G> H makes the contact group G (the slave surface) meet
   the surface group H (the master) of another body. Node-to-surface: each slave node is projected onto the closest
   master triangle; its contact point compares the slave node with the master surface interpolated there (P1: the
   barycentric coordinates of the projection), in the frame of the master normal, with the normal distance as gap:
   B_i = R_i (E_{s_i} - sum_j w_ij E_{m_j}) (docs/contact-operator.md). Dual mortar (-pair_discretization dual_mortar,
   mortar.c) replaces the weights of the slave nodes the master covers. Frames and gaps at the reference configuration
   (small deformation).
*/
#include "pairs.h"

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

#define SSSTAR_TRIANGLE_PACKED 19 /* x[9], n[3], dof[3], tag[3], body */

/* The faces of the master group of pair g owned here, gathered on every rank */
static PetscErrorCode GatherMasters(SSStarScene scene, PetscInt g, PetscInt *ntri, SSStarMasterTriangle **tris)
{
  SSStarFaces  faces;
  DMLabel      label;
  PetscInt     nloc = 0;
  PetscReal   *loc, *all;
  PetscMPIInt  size, *counts, *displs, total = 0, mine;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(SSStarFacesBegin(scene, &faces));
  PetscCall(DMGetLabel(scene->dm, scene->contact[g].master, &label));
  PetscCall(PetscMalloc1(SSSTAR_TRIANGLE_PACKED * (faces.fEnd - faces.fStart) + 1, &loc));
  for (PetscInt f = faces.fStart; f < faces.fEnd; f++) {
    PetscInt   value, dof[3], tag[3], vertex;
    PetscReal *a = &loc[SSSTAR_TRIANGLE_PACKED * nloc], area;

    PetscCall(DMLabelGetValue(label, f, &value));
    if (value < 0 || faces.leaf[f]) continue;
    PetscCall(SSStarFaceTriangle(&faces, f, a, dof, tag, &vertex, &a[9], &area));
    for (PetscInt k = 0; k < 3; k++) {
      a[12 + k] = (PetscReal)dof[k];
      a[15 + k] = (PetscReal)tag[k];
    }
    a[18] = (PetscReal)scene->body[vertex - faces.vStart];
    nloc++;
  }
  PetscCall(SSStarFacesEnd(&faces));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  mine = (PetscMPIInt)(SSSTAR_TRIANGLE_PACKED * nloc);
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts, 1, MPI_INT, scene->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  PetscCall(PetscMalloc1(total + 1, &all));
  PetscCallMPI(MPI_Allgatherv(loc, mine, MPIU_REAL, all, counts, displs, MPIU_REAL, scene->comm));
  *ntri = total / SSSTAR_TRIANGLE_PACKED;
  PetscCall(PetscMalloc1(*ntri + 1, tris));
  for (PetscInt t = 0; t < *ntri; t++) {
    const PetscReal      *a  = &all[SSSTAR_TRIANGLE_PACKED * t];
    SSStarMasterTriangle *tr = &(*tris)[t];

    for (PetscInt k = 0; k < 9; k++) tr->x[k] = a[k];
    for (PetscInt k = 0; k < 3; k++) {
      tr->n[k]   = a[9 + k];
      tr->dof[k] = (PetscInt)a[12 + k];
      tr->tag[k] = (PetscInt)a[15 + k];
    }
    tr->body = (PetscInt)a[18];
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

/* Lexicographic order of the sorted file indices of two triangles (a tie between equally close triangles) */
static void Sort3(PetscInt a[3])
{
  for (PetscInt i = 1; i < 3; i++)
    for (PetscInt j = i; j > 0 && a[j - 1] > a[j]; j--) {
      const PetscInt t = a[j];

      a[j]     = a[j - 1];
      a[j - 1] = t;
    }
}

static PetscBool TriangleBefore(const SSStarMasterTriangle *s, const SSStarMasterTriangle *t)
{
  PetscInt a[3] = {s->tag[0], s->tag[1], s->tag[2]}, b[3] = {t->tag[0], t->tag[1], t->tag[2]};

  Sort3(a);
  Sort3(b);
  for (PetscInt k = 0; k < 3; k++)
    if (a[k] != b[k]) return (PetscBool)(a[k] < b[k]);
  return PETSC_FALSE;
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
   SSStarPairRows - the rows of B of the slave nodes of pair g: each node's closest master triangle gives its normal (the
   triangle's, out of the master body; where the node lies beyond the master's rim, the direction from the closest
   point), its gap and its master weights; with dual mortar, the mortar rows where the master covers the node (mortar.c).
   Refuses a pair whose two groups are on one body, and a master group without triangles.
*/
PetscErrorCode SSStarPairRows(SSStarScene scene, PetscInt g, SSStarMasters *masters)
{
  const SSStarContactGroup *cg = &scene->contact[g];
  PetscInt                  ntri = 0, bad = -1, *nodeBody, *nearest;
  SSStarMasterTriangle     *tris;
  PetscBool                *mortar;
  PetscReal                 tol, *weights;

  PetscFunctionBegin;
  PetscCall(SSStarSceneContactTolerance(scene, &tol));
  PetscCall(GatherMasters(scene, g, &ntri, &tris));
  PetscCheck(ntri > 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the master group has no triangles", cg->name, cg->master);
  PetscCall(NodeBodies(scene, &nodeBody));
  PetscCall(PetscMalloc3(scene->n + 1, &nearest, 3 * scene->n + 1, &weights, scene->n + 1, &mortar));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscReal *p    = &scene->coords[3 * i];
    PetscReal        best = PETSC_MAX_REAL, *w = &weights[3 * i], q[3];
    PetscInt         b    = -1;

    nearest[i] = -1;
    mortar[i]  = PETSC_FALSE;
    if (scene->group[i] != g) continue;
    for (PetscInt t = 0; t < ntri; t++) {
      PetscReal d = 0;

      if (tris[t].body == nodeBody[i]) {
        if (bad < 0) bad = scene->tag[i];
        continue;
      }
      SSStarClosestPointOnTriangle(p, &tris[t].x[0], &tris[t].x[3], &tris[t].x[6], NULL, q, NULL);
      for (PetscInt k = 0; k < 3; k++) d += PetscSqr(p[k] - (q[0] * tris[t].x[k] + q[1] * tris[t].x[3 + k] + q[2] * tris[t].x[6 + k]));
      d = PetscSqrtReal(d);
      if (d < best - tol || (d <= best + tol && b >= 0 && TriangleBefore(&tris[t], &tris[b]))) {
        best = PetscMin(best, d);
        b    = t;
      }
    }
    if (b < 0) continue; /* every master triangle on the slave's body: refused below */
    nearest[i] = b;
    {
      const SSStarMasterTriangle *t = &tris[b];
      PetscReal                   c[3], dc[3], n[3], len = 0, gap = 0;

      SSStarClosestPointOnTriangle(p, &t->x[0], &t->x[3], &t->x[6], NULL, w, NULL);
      for (PetscInt k = 0; k < 3; k++) {
        c[k]  = w[0] * t->x[k] + w[1] * t->x[3 + k] + w[2] * t->x[6 + k];
        dc[k] = p[k] - c[k];
        len += dc[k] * dc[k];
        gap += dc[k] * t->n[k];
      }
      len = PetscSqrtReal(len);
      /* inside the triangle (the normal projection), or on its rim within round-off: the face's normal and signed distance */
      if (PetscAbsReal(PetscAbsReal(gap) - len) <= tol * 1e2 + 1e-8 * len || len <= tol) {
        for (PetscInt k = 0; k < 3; k++) n[k] = t->n[k];
      } else if (gap > 0) { /* beyond the rim, outside: the direction from the closest point */
        for (PetscInt k = 0; k < 3; k++) n[k] = dc[k] / len;
        gap = len;
      } else {
        for (PetscInt k = 0; k < 3; k++) n[k] = t->n[k];
      }
      if (PetscAbsReal(gap) <= tol) gap = 0;
      scene->gap[i] = gap;
      for (PetscInt k = 0; k < 3; k++) scene->normal[3 * i + k] = n[k];
    }
  }
  PetscCall(PetscFree(nodeBody));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MAX, scene->comm));
  PetscCheck(bad < 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the groups \"%s\" and \"%s\" are on the same body (a contact pair is between two bodies: meshes that do not share nodes)", cg->name, cg->master, cg->name, cg->master);
  if (scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR) PetscCall(SSStarMortarRows(scene, g, ntri, tris, tol, mortar, masters));
  for (PetscInt i = 0; i < scene->n; i++) { /* node-to-surface: the vertices of the closest triangle that move */
    if (nearest[i] < 0 || mortar[i]) continue;
    for (PetscInt j = 0; j < 3; j++)
      if (tris[nearest[i]].dof[j] >= 0 && weights[3 * i + j] != 0) PetscCall(SSStarMastersAdd(masters, i, tris[nearest[i]].dof[j], weights[3 * i + j]));
  }
  PetscCall(PetscFree3(nearest, weights, mortar));
  PetscCall(PetscFree(tris));
  PetscFunctionReturn(0);
}
