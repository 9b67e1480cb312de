/*
   Two deformable bodies (README "Contact pairs"): -contact_pair_<G> H makes the contact group G (the slave surface)
   meet the surface group H (the master) of another body. Node-to-surface: each slave node is projected onto the
   closest master triangle; its contact point compares the slave node with the master surface interpolated there
   (P1: the barycentric coordinates of the projection), in the frame of the master normal, with the normal distance
   as gap: B_i = R_i (E_{s_i} - sum_j w_ij E_{m_j}), declared through SNESSSStarSetContactOperator()
   (docs/contact-operator.md). Frames and gaps at the reference configuration (small deformation).

   Also here, for every scene: the bodies (connected components of the mesh), each of which must be held by a
   -dirichlet or -spring_<G> group, and the contact kinematics written to /contact (gap at the solution, pressure,
   tangential traction, slip).
*/
#include "sceneimpl.h"
#include <petscsf.h>

#define SSSTAR_MAX_VOLUME_GROUPS 62

const char *const SSStarPairDiscretizations[] = {"node_to_surface", "dual_mortar"}; /* bits of the body's volume-group mask */

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

/* union-find with path halving */
static PetscInt Find(PetscInt parent[], PetscInt v)
{
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v         = parent[v];
  }
  return v;
}

/* Is the label the group of a -dirichlet or -spring_<G> option? */
static PetscErrorCode HoldingLabels(SSStarScene scene, PetscInt *n, DMLabel **labels)
{
  PetscFunctionBegin;
  PetscCall(PetscMalloc1(scene->nDirichlet + scene->nSprings + 1, labels));
  *n = 0;
  for (PetscInt g = 0; g < scene->nDirichlet; g++) PetscCall(DMGetLabel(scene->dm, scene->dirichlet[g], &(*labels)[(*n)++]));
  for (PetscInt g = 0; g < scene->nSprings; g++) PetscCall(DMGetLabel(scene->dm, scene->springs[g].name, &(*labels)[(*n)++]));
  PetscFunctionReturn(0);
}

/*
   The bodies: connected components of the mesh (cells sharing a vertex), each named by the smallest file index of
   its nodes; scene->body[v] for every local vertex. Each body must touch a -dirichlet or -spring_<G> group, or its
   rigid-body motions are held by contact alone (K singular): refused, naming the body.
*/
PetscErrorCode SSStarSceneFindBodies(SSStarScene scene)
{
  DM                 dm = scene->dm;
  PetscSF            sf;
  PetscInt           pStart, pEnd, vStart, vEnd, cStart, cEnd, nroots, nhold = 0, nlabels, nvol = 0, nloc = 0;
  PetscInt          *parent, *comp, *copy, *setMin;
  DMLabel           *hold, vol[SSSTAR_MAX_VOLUME_GROUPS];
  const char        *volName[SSSTAR_MAX_VOLUME_GROUPS];
  long long         *loc, *all;
  PetscMPIInt        size, *counts, *displs, total = 0;
  const PetscScalar *ta;
  PetscBool          changed = PETSC_TRUE;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc4(vEnd - vStart, &parent, pEnd - pStart, &comp, pEnd - pStart, &copy, vEnd - vStart, &setMin));
  for (PetscInt v = 0; v < vEnd - vStart; v++) parent[v] = v;
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt v[4], first;

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    first = Find(parent, v[0] - vStart);
    for (PetscInt k = 1; k < 4; k++) parent[Find(parent, v[k] - vStart)] = first;
  }
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt p = 0; p < pEnd - pStart; p++) comp[p] = PETSC_MAX_INT;
  for (PetscInt v = vStart; v < vEnd; v++) comp[v - pStart] = (PetscInt)PetscRealPart(ta[v - vStart]);
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  /* the smallest index of each local component, then across the ranks through the shared vertices, until stable */
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, NULL, NULL, NULL));
  while (changed) {
    changed = PETSC_FALSE;
    for (PetscInt v = 0; v < vEnd - vStart; v++) setMin[v] = PETSC_MAX_INT;
    for (PetscInt v = 0; v < vEnd - vStart; v++) {
      const PetscInt r = Find(parent, v);

      setMin[r] = PetscMin(setMin[r], comp[v + vStart - pStart]);
    }
    for (PetscInt v = 0; v < vEnd - vStart; v++) {
      const PetscInt m = setMin[Find(parent, v)];

      if (comp[v + vStart - pStart] != m) changed = PETSC_TRUE;
      comp[v + vStart - pStart] = m;
    }
    if (size > 1 && nroots >= 0) {
      PetscCall(PetscArraycpy(copy, comp, pEnd - pStart));
      PetscCall(PetscSFReduceBegin(sf, MPIU_INT, copy, comp, MPI_MIN));
      PetscCall(PetscSFReduceEnd(sf, MPIU_INT, copy, comp, MPI_MIN));
      PetscCall(PetscArraycpy(copy, comp, pEnd - pStart));
      PetscCall(PetscSFBcastBegin(sf, MPIU_INT, copy, comp, MPI_REPLACE));
      PetscCall(PetscSFBcastEnd(sf, MPIU_INT, copy, comp, MPI_REPLACE));
      for (PetscInt v = vStart; v < vEnd && !changed; v++)
        if (comp[v - pStart] != copy[v - pStart]) changed = PETSC_TRUE;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_BOOL, MPI_LOR, scene->comm));
  }
  PetscCall(PetscFree(scene->body));
  PetscCall(PetscMalloc1(vEnd - vStart, &scene->body));
  for (PetscInt v = vStart; v < vEnd; v++) scene->body[v - vStart] = comp[v - pStart];

  /* the volume groups (labels on cells somewhere), to name the bodies */
  PetscCall(DMGetNumLabels(dm, &nlabels));
  for (PetscInt l = 0; l < nlabels; l++) {
    const char *name;
    DMLabel     label;
    PetscBool   cells = PETSC_FALSE, skip;

    PetscCall(DMGetLabelName(dm, l, &name));
    PetscCall(PetscStrcmp(name, "depth", &skip));
    if (!skip) PetscCall(PetscStrcmp(name, "celltype", &skip));
    if (!skip) {
      PetscCall(DMGetLabel(dm, name, &label));
      for (PetscInt c = cStart; c < cEnd && !cells; c++) {
        PetscInt value;

        PetscCall(DMLabelGetValue(label, c, &value));
        cells = (PetscBool)(value >= 0);
      }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cells, 1, MPIU_BOOL, MPI_LOR, scene->comm));
    if (cells && nvol < SSSTAR_MAX_VOLUME_GROUPS) {
      volName[nvol] = name;
      PetscCall(DMGetLabel(dm, name, &vol[nvol++]));
    }
  }

  /* per local component: (body, held, volume groups), merged over the ranks */
  PetscCall(HoldingLabels(scene, &nhold, &hold));
  PetscCall(PetscCalloc1(3 * (vEnd - vStart) + 3, &loc));
  for (PetscInt v = 0; v < vEnd - vStart; v++) setMin[v] = -1; /* the entry of each local set */
  for (PetscInt v = vStart; v < vEnd; v++) {
    const PetscInt r = Find(parent, v - vStart);
    PetscBool      held = PETSC_FALSE;

    if (setMin[r] < 0) {
      setMin[r]        = nloc++;
      loc[3 * setMin[r]] = comp[v - pStart];
    }
    for (PetscInt g = 0; g < nhold && !held; g++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(hold[g], v, &value));
      held = (PetscBool)(value >= 0);
    }
    if (held) loc[3 * setMin[r] + 1] = 1;
  }
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt v[4], e;

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    e = setMin[Find(parent, v[0] - vStart)];
    for (PetscInt l = 0; l < nvol && e >= 0; l++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(vol[l], c, &value));
      if (value >= 0) loc[3 * e + 2] |= 1LL << l;
    }
  }
  PetscCall(PetscFree(hold));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  {
    PetscMPIInt mine = (PetscMPIInt)(3 * nloc);

    PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts, 1, MPI_INT, scene->comm));
  }
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  PetscCall(PetscMalloc1(total + 3, &all));
  PetscCallMPI(MPI_Allgatherv(loc, 3 * (PetscMPIInt)nloc, MPI_LONG_LONG, all, counts, displs, MPI_LONG_LONG, scene->comm));
  /* merge: the same body on several ranks */
  scene->nBodies = 0;
  for (PetscMPIInt e = 0; e < total / 3; e++) {
    PetscBool first = PETSC_TRUE;

    for (PetscMPIInt f = 0; f < e && first; f++)
      if (all[3 * f] == all[3 * e]) first = PETSC_FALSE;
    if (!first) continue;
    for (PetscMPIInt f = e + 1; f < total / 3; f++)
      if (all[3 * f] == all[3 * e]) {
        all[3 * e + 1] |= all[3 * f + 1];
        all[3 * e + 2] |= all[3 * f + 2];
      }
    for (PetscMPIInt f = e + 1; f < total / 3; f++) /* the merged verdict in every entry of the body */
      if (all[3 * f] == all[3 * e]) all[3 * f + 1] = all[3 * e + 1];
    scene->nBodies++;
  }
  for (PetscMPIInt e = 0; e < total / 3; e++) {
    char names[1024] = "";

    if (all[3 * e + 1]) continue;
    for (PetscInt l = 0; l < nvol; l++)
      if (all[3 * e + 2] & (1LL << l)) {
        if (names[0]) PetscCall(PetscStrlcat(names, ", ", sizeof(names)));
        PetscCall(PetscStrlcat(names, "\"", sizeof(names)));
        PetscCall(PetscStrlcat(names, volName[l], sizeof(names)));
        PetscCall(PetscStrlcat(names, "\"", sizeof(names)));
      }
    SETERRQ(scene->comm, PETSC_ERR_ARG_WRONG, "The body of volume group %s (the mesh nodes connected to node %lld, 0-based file order; one of %" PetscInt_FMT " bodies) is held only by contact: nothing holds its rigid-body motions. Hold it with -dirichlet or -spring_<G> on one of its groups", names[0] ? names : "(none)", all[3 * e], scene->nBodies);
  }
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(loc));
  PetscCall(PetscFree4(parent, comp, copy, setMin));
  PetscFunctionReturn(0);
}

/* A master triangle: its vertices, their global dofs (-1: held fixed), file indices and body, its outward unit normal */
#define TRI_LEN 23 /* x[9], normal[3], dof[3], tag[3], body, pair, pad */
typedef struct {
  PetscReal x[9], n[3];
  PetscInt  dof[3], tag[3], body, pair;
} Triangle;

static void TriangleFromPacked(const PetscReal *a, Triangle *t)
{
  for (PetscInt k = 0; k < 9; k++) t->x[k] = a[k];
  for (PetscInt k = 0; k < 3; k++) {
    t->n[k]   = a[9 + k];
    t->dof[k] = (PetscInt)a[12 + k];
    t->tag[k] = (PetscInt)a[15 + k];
  }
  t->body = (PetscInt)a[18];
  t->pair = (PetscInt)a[19];
}

/* The faces of the master groups owned here, packed (TRI_LEN reals each), gathered on every rank */
static PetscErrorCode GatherMasters(SSStarScene scene, PetscInt *ntri, Triangle **tris)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       gsec, csec;
  PetscSF            sf;
  PetscInt           fStart, fEnd, vStart, vEnd, nleaves, nloc = 0;
  const PetscInt    *ilocal;
  PetscBool         *leaf;
  Vec                coordinates;
  const PetscScalar *xa, *ta;
  PetscReal         *loc, *all;
  PetscMPIInt        size, *counts, *displs, total = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(scene->comm, &size));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscCalloc1(fEnd, &leaf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, NULL));
  for (PetscInt l = 0; l < nleaves; l++) {
    const PetscInt p = ilocal ? ilocal[l] : l;

    if (p < fEnd) leaf[p] = PETSC_TRUE;
  }
  PetscCall(PetscMalloc1(TRI_LEN * (fEnd - fStart) * PetscMax(scene->nPairs, 1) + 1, &loc));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  PetscCall(VecGetArrayRead(scene->tags, &ta));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    DMLabel label;

    if (!scene->contact[g].master[0]) continue;
    PetscCall(DMGetLabel(dm, scene->contact[g].master, &label));
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt        value, *closure = NULL, nc, nv = 0, vert[3], ns;
      const PetscInt *support;
      PetscReal      *a = &loc[TRI_LEN * nloc], cc[3] = {0, 0, 0}, e1[3], e2[3], len, side = 0;

      PetscCall(DMLabelGetValue(label, f, &value));
      if (value < 0 || leaf[f]) continue;
      PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0; k < nc; k++)
        if (closure[2 * k] >= vStart && closure[2 * k] < vEnd && nv < 3) vert[nv++] = closure[2 * k];
      PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0; k < 3; k++) {
        PetscInt off, dof, coff;

        PetscCall(PetscSectionGetOffset(csec, vert[k], &coff));
        for (PetscInt c = 0; c < 3; c++) a[3 * k + c] = PetscRealPart(xa[coff + c]);
        PetscCall(PetscSectionGetDof(gsec, vert[k], &dof));
        PetscCall(PetscSectionGetOffset(gsec, vert[k], &off));
        if (dof < 0) dof = -(dof + 1);
        if (off < 0) off = -(off + 1);
        a[12 + k] = dof == 3 ? (PetscReal)off : -1;
        a[15 + k] = PetscRealPart(ta[vert[k] - vStart]);
      }
      /* the cell's centroid: the normal points away from it, out of the master body */
      PetscCall(DMPlexGetSupportSize(dm, f, &ns));
      PetscCall(DMPlexGetSupport(dm, f, &support));
      PetscCheck(ns >= 1, PETSC_COMM_SELF, PETSC_ERR_PLIB, "A face of group \"%s\" has no cell", scene->contact[g].master);
      PetscCall(DMPlexGetTransitiveClosure(dm, support[0], PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0, m = 0; k < nc; k++)
        if (closure[2 * k] >= vStart && closure[2 * k] < vEnd) {
          PetscInt coff;

          PetscCall(PetscSectionGetOffset(csec, closure[2 * k], &coff));
          for (PetscInt c = 0; c < 3; c++) cc[c] += PetscRealPart(xa[coff + c]) / 4;
          m++;
        }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, support[0], PETSC_TRUE, &nc, &closure));
      for (PetscInt c = 0; c < 3; c++) {
        e1[c] = a[3 + c] - a[c];
        e2[c] = a[6 + c] - a[c];
      }
      a[9]  = e1[1] * e2[2] - e1[2] * e2[1];
      a[10] = e1[2] * e2[0] - e1[0] * e2[2];
      a[11] = e1[0] * e2[1] - e1[1] * e2[0];
      len   = PetscSqrtReal(a[9] * a[9] + a[10] * a[10] + a[11] * a[11]);
      for (PetscInt c = 0; c < 3; c++) side += a[9 + c] * ((a[c] + a[3 + c] + a[6 + c]) / 3 - cc[c]);
      for (PetscInt c = 0; c < 3; c++) a[9 + c] /= side < 0 ? -len : len;
      a[18] = (PetscReal)scene->body[vert[0] - vStart];
      a[19] = (PetscReal)g;
      a[20] = a[21] = a[22] = 0;
      nloc++;
    }
  }
  PetscCall(VecRestoreArrayRead(scene->tags, &ta));
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(PetscFree(leaf));
  PetscCall(PetscMalloc2(size, &counts, size, &displs));
  {
    PetscMPIInt mine = (PetscMPIInt)(TRI_LEN * nloc);

    PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts, 1, MPI_INT, scene->comm));
  }
  for (PetscMPIInt r = 0; r < size; r++) {
    displs[r] = total;
    total += counts[r];
  }
  PetscCall(PetscMalloc1(total + 1, &all));
  PetscCallMPI(MPI_Allgatherv(loc, TRI_LEN * (PetscMPIInt)nloc, MPIU_REAL, all, counts, displs, MPIU_REAL, scene->comm));
  *ntri = total / TRI_LEN;
  PetscCall(PetscMalloc1(*ntri + 1, tris));
  for (PetscInt t = 0; t < *ntri; t++) TriangleFromPacked(&all[TRI_LEN * t], &(*tris)[t]);
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(counts, displs));
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

/* The closest point of the triangle a, b, c to p (Ericson, Real-Time Collision Detection 5.1.5): its barycentric coordinates */
static void ClosestPoint(const PetscReal x[9], const PetscReal p[3], PetscReal w[3])
{
  const PetscReal *a = x, *b = x + 3, *c = x + 6;
  PetscReal        ab[3], ac[3], ap[3], bp[3], cp[3], d1 = 0, d2 = 0, d3 = 0, d4 = 0, d5 = 0, d6 = 0, va, vb, vc, v, t, den;

  for (PetscInt k = 0; k < 3; k++) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
    d1 += ab[k] * ap[k];
    d2 += ac[k] * ap[k];
    d3 += ab[k] * bp[k];
    d4 += ac[k] * bp[k];
    d5 += ab[k] * cp[k];
    d6 += ac[k] * cp[k];
  }
  w[0] = 1, w[1] = w[2] = 0;
  if (d1 <= 0 && d2 <= 0) return;
  w[0] = 0, w[1] = 1;
  if (d3 >= 0 && d4 <= d3) return;
  vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    v    = d1 / (d1 - d3);
    w[0] = 1 - v, w[1] = v, w[2] = 0;
    return;
  }
  w[0] = w[1] = 0, w[2] = 1;
  if (d6 >= 0 && d5 <= d6) return;
  vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    t    = d2 / (d2 - d6);
    w[0] = 1 - t, w[1] = 0, w[2] = t;
    return;
  }
  va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    t    = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    w[0] = 0, w[1] = 1 - t, w[2] = t;
    return;
  }
  den  = 1 / (va + vb + vc);
  w[1] = vb * den;
  w[2] = vc * den;
  w[0] = 1 - w[1] - w[2];
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

static PetscBool TriangleBefore(const Triangle *s, const Triangle *t)
{
  PetscInt a[3] = {s->tag[0], s->tag[1], s->tag[2]}, b[3] = {t->tag[0], t->tag[1], t->tag[2]};

  Sort3(a);
  Sort3(b);
  for (PetscInt k = 0; k < 3; k++)
    if (a[k] != b[k]) return (PetscBool)(a[k] < b[k]);
  return PETSC_FALSE;
}


/* The 2D barycentric coordinates of p in the triangle a, b, c (any orientation) */
static void Barycentric2(const PetscReal a[2], const PetscReal b[2], const PetscReal c[2], const PetscReal p[2], PetscReal l[3])
{
  const PetscReal det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);

  l[1] = ((p[0] - a[0]) * (c[1] - a[1]) - (p[1] - a[1]) * (c[0] - a[0])) / det;
  l[2] = ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / det;
  l[0] = 1 - l[1] - l[2];
}

/* Sutherland-Hodgman: the polygon P (n vertices, 2D) clipped by the counterclockwise triangle T; at most 9 vertices */
static PetscInt ClipByTriangle(PetscInt n, PetscReal P[][2], const PetscReal T[3][2])
{
  PetscReal Q[12][2];

  for (PetscInt e = 0; e < 3 && n > 0; e++) {
    const PetscReal *A = T[e], *B = T[(e + 1) % 3];
    PetscInt         m = 0;

    for (PetscInt k = 0; k < n; k++) {
      const PetscReal *S = P[(k + n - 1) % n], *E = P[k];
      const PetscReal  dS = (B[0] - A[0]) * (S[1] - A[1]) - (B[1] - A[1]) * (S[0] - A[0]);
      const PetscReal  dE = (B[0] - A[0]) * (E[1] - A[1]) - (B[1] - A[1]) * (E[0] - A[0]);

      if ((dE >= 0) != (dS >= 0) && m < 12) { /* the edge S E crosses the line A B */
        const PetscReal t = dS / (dS - dE);

        Q[m][0]   = S[0] + t * (E[0] - S[0]);
        Q[m++][1] = S[1] + t * (E[1] - S[1]);
      }
      if (dE >= 0 && m < 12) {
        Q[m][0]   = E[0];
        Q[m++][1] = E[1];
      }
    }
    for (PetscInt k = 0; k < m; k++) P[k][0] = Q[k][0], P[k][1] = Q[k][1];
    n = m;
  }
  return n;
}

/*
   Dual mortar (Wohlmuth): per slave node i, D_i = int N_i over the slave faces, and per master node j
   M_ij = int_overlap psi_i N_j, psi_i = 4 lambda_i - 1 the dual basis of the slave triangle (int psi_i N_k = delta_ik
   int N_k), the integrals on the slave triangle's plane, the master triangle projected onto it along the slave normal
   (the overlap polygon by clipping, split in triangles, the three edge midpoints: exact for the quadratic psi_i N_j).
   Rows of Mm at the slave x-dofs, columns at the master x-dofs (held masters have none); in DC the slave's x-dof gets
   D_i, its y-dof sum_j M_ij (= D_i where the master covers the slave), in G sum_j M_ij x_j (3), in N the master
   normals weighted like the master nodes, sum over the master triangles of (int psi_i) n_m (3): the node's normal
   is the master's (as node-to-surface, and as the small-deformation Hertz theory has it), not the curved slave's.
*/
static PetscErrorCode MortarIntegrals(SSStarScene scene, PetscInt ntri, const Triangle tris[], Mat *Mm, Vec *DC, Vec *G, Vec *N)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       gsec, csec;
  PetscSF            sf;
  PetscInt           fStart, fEnd, vStart, vEnd, nleaves, m, xstart, *dnz;
  const PetscInt    *ilocal, *own;
  PetscBool         *leaf;
  Vec                coordinates;
  const PetscScalar *xa;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscCalloc1(fEnd, &leaf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, NULL));
  for (PetscInt l = 0; l < nleaves; l++) {
    const PetscInt p = ilocal ? ilocal[l] : l;

    if (p < fEnd) leaf[p] = PETSC_TRUE;
  }
  PetscCall(DMCreateGlobalVector(dm, DC));
  PetscCall(VecZeroEntries(*DC));
  PetscCall(VecDuplicate(*DC, G));
  PetscCall(VecDuplicate(*DC, N));
  PetscCall(VecZeroEntries(*G));
  PetscCall(VecZeroEntries(*N));
  PetscCall(VecGetLocalSize(*DC, &m));
  PetscCall(VecGetOwnershipRange(*DC, &xstart, NULL));
  /* room at the x-dofs of this rank's contact nodes */
  PetscCall(PetscCalloc1(m + 1, &dnz));
  PetscCall(ISGetIndices(scene->isC, &own));
  for (PetscInt i = 0; i < scene->n; i++)
    if (scene->contact[scene->group[i]].master[0]) dnz[own[3 * i] - xstart] = 64;
  PetscCall(ISRestoreIndices(scene->isC, &own));
  PetscCall(MatCreate(scene->comm, Mm));
  PetscCall(MatSetSizes(*Mm, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(*Mm, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(*Mm, 0, dnz));
  PetscCall(MatMPIAIJSetPreallocation(*Mm, 0, dnz, 0, dnz));
  PetscCall(MatSetOption(*Mm, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscCall(PetscFree(dnz));
  PetscCall(VecGetArrayRead(coordinates, &xa));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    DMLabel label;

    if (!scene->contact[g].master[0]) continue;
    PetscCall(DMGetLabel(dm, scene->contact[g].name, &label));
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt        value, *closure = NULL, nc, nv = 0, vert[3], dof[3];
      const PetscInt *support;
      PetscReal       x[9], n[3], e1[3], e2[3], cc[3] = {0, 0, 0}, len, side = 0, area, S[3][2], T[3][2];

      PetscCall(DMLabelGetValue(label, f, &value));
      if (value < 0 || leaf[f]) continue;
      PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0; k < nc; k++)
        if (closure[2 * k] >= vStart && closure[2 * k] < vEnd && nv < 3) vert[nv++] = closure[2 * k];
      PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0; k < 3; k++) {
        PetscInt off, d, coff;

        PetscCall(PetscSectionGetOffset(csec, vert[k], &coff));
        for (PetscInt c = 0; c < 3; c++) x[3 * k + c] = PetscRealPart(xa[coff + c]);
        PetscCall(PetscSectionGetDof(gsec, vert[k], &d));
        PetscCall(PetscSectionGetOffset(gsec, vert[k], &off));
        if (d < 0) d = -(d + 1);
        if (off < 0) off = -(off + 1);
        dof[k] = d == 3 ? off : -1;
      }
      PetscCall(DMPlexGetSupport(dm, f, &support));
      PetscCall(DMPlexGetTransitiveClosure(dm, support[0], PETSC_TRUE, &nc, &closure));
      for (PetscInt k = 0; k < nc; k++)
        if (closure[2 * k] >= vStart && closure[2 * k] < vEnd) {
          PetscInt coff;

          PetscCall(PetscSectionGetOffset(csec, closure[2 * k], &coff));
          for (PetscInt c = 0; c < 3; c++) cc[c] += PetscRealPart(xa[coff + c]) / 4;
        }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, support[0], PETSC_TRUE, &nc, &closure));
      for (PetscInt c = 0; c < 3; c++) {
        e1[c] = x[3 + c] - x[c];
        e2[c] = x[6 + c] - x[c];
      }
      n[0] = e1[1] * e2[2] - e1[2] * e2[1];
      n[1] = e1[2] * e2[0] - e1[0] * e2[2];
      n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      len  = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      area = len / 2;
      for (PetscInt c = 0; c < 3; c++) side += n[c] * ((x[c] + x[3 + c] + x[6 + c]) / 3 - cc[c]);
      for (PetscInt c = 0; c < 3; c++) n[c] /= side < 0 ? -len : len; /* out of the slave body */
      /* the slave triangle's plane: origin x0, axes e1, e2 = n x e1 */
      len = PetscSqrtReal(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
      for (PetscInt c = 0; c < 3; c++) e1[c] /= len;
      e2[0] = n[1] * e1[2] - n[2] * e1[1];
      e2[1] = n[2] * e1[0] - n[0] * e1[2];
      e2[2] = n[0] * e1[1] - n[1] * e1[0];
      for (PetscInt k = 0; k < 3; k++) {
        S[k][0] = S[k][1] = 0;
        for (PetscInt c = 0; c < 3; c++) {
          S[k][0] += (x[3 * k + c] - x[c]) * e1[c];
          S[k][1] += (x[3 * k + c] - x[c]) * e2[c];
        }
      }
      for (PetscInt k = 0; k < 3; k++) { /* (T: S counterclockwise) */
        const PetscInt kk = ((S[1][0] - S[0][0]) * (S[2][1] - S[0][1]) - (S[1][1] - S[0][1]) * (S[2][0] - S[0][0])) > 0 ? k : 2 - k;

        T[k][0] = S[kk][0], T[k][1] = S[kk][1];
      }
      for (PetscInt k = 0; k < 3; k++) {
        if (dof[k] < 0) continue;
        PetscCall(VecSetValue(*DC, dof[k], area / 3, ADD_VALUES));
      }
      for (PetscInt t = 0; t < ntri; t++) {
        const Triangle *tm = &tris[t];
        PetscReal       Mp[3][2], P[12][2], mij[3][3], dot = 0;
        PetscInt        np;

        if (tm->pair != g) continue;
        for (PetscInt c = 0; c < 3; c++) dot += tm->n[c] * n[c];
        if (dot > -0.3) continue; /* not facing the slave face */
        for (PetscInt k = 0; k < 3; k++) {
          Mp[k][0] = Mp[k][1] = 0;
          for (PetscInt c = 0; c < 3; c++) {
            Mp[k][0] += (tm->x[3 * k + c] - x[c]) * e1[c];
            Mp[k][1] += (tm->x[3 * k + c] - x[c]) * e2[c];
          }
        }
        {
          PetscReal lo[2], hi[2], slo[2], shi[2];

          for (PetscInt c = 0; c < 2; c++) {
            lo[c] = PetscMin(Mp[0][c], PetscMin(Mp[1][c], Mp[2][c]));
            hi[c] = PetscMax(Mp[0][c], PetscMax(Mp[1][c], Mp[2][c]));
            slo[c] = PetscMin(S[0][c], PetscMin(S[1][c], S[2][c]));
            shi[c] = PetscMax(S[0][c], PetscMax(S[1][c], S[2][c]));
          }
          if (lo[0] > shi[0] || hi[0] < slo[0] || lo[1] > shi[1] || hi[1] < slo[1]) continue;
        }
        for (PetscInt k = 0; k < 3; k++) P[k][0] = Mp[k][0], P[k][1] = Mp[k][1];
        np = ClipByTriangle(3, P, T);
        if (np < 3) continue;
        for (PetscInt i = 0; i < 3; i++)
          for (PetscInt j = 0; j < 3; j++) mij[i][j] = 0;
        for (PetscInt k = 1; k + 1 < np; k++) {
          const PetscReal *a = P[0], *b = P[k], *c = P[k + 1];
          const PetscReal  sub = PetscAbsReal((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;

          for (PetscInt q = 0; q < 3; q++) { /* the edge midpoints, weight sub/3 each */
            const PetscReal *p0 = q == 0 ? a : q == 1 ? b : c, *p1 = q == 0 ? b : q == 1 ? c : a;
            PetscReal        pq[2] = {(p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2}, ls[3], lm[3];

            Barycentric2(S[0], S[1], S[2], pq, ls);
            Barycentric2(Mp[0], Mp[1], Mp[2], pq, lm);
            for (PetscInt i = 0; i < 3; i++)
              for (PetscInt j = 0; j < 3; j++) mij[i][j] += sub / 3 * (4 * ls[i] - 1) * lm[j];
          }
        }
        for (PetscInt i = 0; i < 3; i++) {
          PetscReal sum = 0, gx[3] = {0, 0, 0};

          if (dof[i] < 0) continue;
          for (PetscInt j = 0; j < 3; j++) {
            sum += mij[i][j];
            for (PetscInt c = 0; c < 3; c++) gx[c] += mij[i][j] * tm->x[3 * j + c];
            if (tm->dof[j] >= 0 && mij[i][j] != 0) PetscCall(MatSetValue(*Mm, dof[i], tm->dof[j], mij[i][j], ADD_VALUES));
          }
          PetscCall(VecSetValue(*DC, dof[i] + 1, sum, ADD_VALUES));
          for (PetscInt c = 0; c < 3; c++) {
            PetscCall(VecSetValue(*G, dof[i] + c, gx[c], ADD_VALUES));
            PetscCall(VecSetValue(*N, dof[i] + c, sum * tm->n[c], ADD_VALUES));
          }
        }
      }
    }
  }
  PetscCall(VecRestoreArrayRead(coordinates, &xa));
  PetscCall(PetscFree(leaf));
  PetscCall(MatAssemblyBegin(*Mm, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*Mm, MAT_FINAL_ASSEMBLY));
  for (Vec *v = DC; v; v = v == DC ? G : v == G ? N : NULL) {
    PetscCall(VecAssemblyBegin(*v));
    PetscCall(VecAssemblyEnd(*v));
  }
  PetscFunctionReturn(0);
}

/*
   The pairs' contact points: each owned slave node's closest master triangle gives its normal (the triangle's,
   outward from the master body; where the node lies beyond the master's rim, the direction from the closest point),
   its gap and its master weights; B has 3 rows per contact node (every contact node: the rigid obstacles' rows are
   R E_s). Refuses a pair whose two groups are on one body.
*/
PetscErrorCode SSStarPairsSetUp(SSStarScene scene)
{
  DM                 dm = scene->dm;
  PetscInt           ntri = 0, m, rstart, nbad[2] = {-1, -1}, vStart, vEnd, *vtag, *vidx, *slaveBody;
  Triangle          *tris;
  const PetscScalar *ta;
  PetscBool         *mortar = NULL;
  Mat                Mm     = NULL;
  Vec                DC = NULL, G = NULL, N = NULL;
  PetscReal          gmin[3], gmax[3], tol;
  const PetscInt    *own;
  Vec                x;

  PetscFunctionBegin;
  if (!scene->nPairs) PetscFunctionReturn(0);
  PetscCall(DMGetBoundingBox(dm, gmin, gmax));
  tol = 0;
  for (PetscInt k = 0; k < 3; k++) tol += PetscSqr(gmax[k] - gmin[k]);
  tol = 1e-10 * PetscSqrtReal(tol);
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(GatherMasters(scene, &ntri, &tris));
  /* the body of each contact node, through its file index */
  PetscCall(PetscMalloc1(vEnd - vStart + 1, &vtag));
  PetscCall(PetscMalloc1(vEnd - vStart + 1, &vidx));
  PetscCall(PetscMalloc1(scene->n + 1, &slaveBody));
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
    slaveBody[i] = scene->body[vidx[k]];
  }
  PetscCall(PetscFree(vtag));
  PetscCall(PetscFree(vidx));
  for (PetscInt g = 0; g < scene->nContact; g++) {
    PetscInt count = 0;

    if (!scene->contact[g].master[0]) continue;
    for (PetscInt t = 0; t < ntri; t++) count += tris[t].pair == g;
    PetscCheck(count > 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the master group has no triangles", scene->contact[g].name, scene->contact[g].master);
  }
  PetscCall(PetscFree(scene->frame));
  PetscCall(PetscFree(scene->weight));
  PetscCall(PetscMalloc2(9 * scene->n + 1, &scene->frame, 6 * scene->n + 1, &scene->weight));
  PetscCall(ISGetIndices(scene->isC, &own));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscInt  g = scene->group[i];
    const PetscReal *p = &scene->coords[3 * i];
    PetscReal       *R = &scene->frame[9 * i], *wt = &scene->weight[6 * i], best = PETSC_MAX_REAL, n[3], w[3];
    PetscInt         b = -1;

    for (PetscInt k = 0; k < 6; k++) wt[k] = 0;
    if (!scene->contact[g].master[0]) {
      SSStarNodeFrame(&scene->normal[3 * i], R);
      for (PetscInt k = 0; k < 3; k++) wt[k] = -1;
      continue;
    }
    for (PetscInt t = 0; t < ntri; t++) {
      PetscReal d = 0;

      if (tris[t].pair != g) continue;
      if (tris[t].body == slaveBody[i]) {
        if (nbad[0] < 0) nbad[0] = g, nbad[1] = scene->tag[i];
        continue;
      }
      ClosestPoint(tris[t].x, p, w);
      for (PetscInt k = 0; k < 3; k++) d += PetscSqr(p[k] - (w[0] * tris[t].x[k] + w[1] * tris[t].x[3 + k] + w[2] * tris[t].x[6 + k]));
      d = PetscSqrtReal(d);
      if (d < best - tol || (d <= best + tol && b >= 0 && TriangleBefore(&tris[t], &tris[b]))) {
        best = PetscMin(best, d);
        b    = t;
      }
    }
    if (b < 0) { /* every master triangle on the slave's body: refused below */
      SSStarNodeFrame(&scene->normal[3 * i], R);
      for (PetscInt k = 0; k < 3; k++) wt[k] = -1;
      continue;
    }
    {
      const Triangle *t = &tris[b];
      PetscReal       c[3], dc[3], len = 0, gap = 0;

      ClosestPoint(t->x, p, w);
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
      for (PetscInt k = 0; k < 3; k++) {
        scene->normal[3 * i + k] = n[k];
        wt[k]                    = t->dof[k] >= 0 ? (PetscReal)t->dof[k] : -1;
        wt[3 + k]                = w[k];
      }
      SSStarNodeFrame(n, R);
    }
  }
  PetscCall(PetscFree(slaveBody));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbad[0], 1, MPIU_INT, MPI_MAX, scene->comm));
  PetscCheck(nbad[0] < 0, scene->comm, PETSC_ERR_ARG_WRONG, "Option -contact_pair_%s %s: the groups \"%s\" and \"%s\" are on the same body (a contact pair is between two bodies: meshes that do not share nodes)", scene->contact[nbad[0]].name, scene->contact[nbad[0]].master, scene->contact[nbad[0]].name, scene->contact[nbad[0]].master);

  /* dual mortar: the rows of the slave nodes the master covers (the others keep node-to-surface) */
  scene->pairFallback = 0;
  if (scene->pairMethod == SSSTAR_PAIR_DUAL_MORTAR) {
    const PetscScalar *dca, *ga, *na;
    PetscInt           xstart;

    PetscCall(MortarIntegrals(scene, ntri, tris, &Mm, &DC, &G, &N));
    PetscCall(PetscCalloc1(scene->n + 1, &mortar));
    PetscCall(VecGetOwnershipRange(DC, &xstart, NULL));
    PetscCall(VecGetArrayRead(DC, &dca));
    PetscCall(VecGetArrayRead(G, &ga));
    PetscCall(VecGetArrayRead(N, &na));
    for (PetscInt i = 0; i < scene->n; i++) {
      const PetscInt   xd = own[3 * i] - xstart;
      const PetscReal  D = PetscRealPart(dca[xd]), C = PetscRealPart(dca[xd + 1]);
      PetscReal        n[3], len = 0, gap = 0;

      if (!scene->contact[scene->group[i]].master[0]) continue;
      if (D <= 0 || PetscAbsReal(C / D - 1) > 1e-6) {
        scene->pairFallback++;
        continue;
      }
      for (PetscInt k = 0; k < 3; k++) {
        n[k] = PetscRealPart(na[xd + k]);
        len += n[k] * n[k];
      }
      len = PetscSqrtReal(len);
      for (PetscInt k = 0; k < 3; k++) {
        n[k] /= len;
        gap += n[k] * (scene->coords[3 * i + k] - PetscRealPart(ga[xd + k]) / D);
      }
      if (PetscAbsReal(gap) <= tol) gap = 0;
      scene->gap[i] = gap;
      for (PetscInt k = 0; k < 3; k++) scene->normal[3 * i + k] = n[k];
      SSStarNodeFrame(n, &scene->frame[9 * i]);
      scene->weight[6 * i + 3] = D; /* the mortar row: Mm's row / D */
      mortar[i] = PETSC_TRUE;
    }
    PetscCall(VecRestoreArrayRead(N, &na));
    PetscCall(VecRestoreArrayRead(G, &ga));
    PetscCall(VecRestoreArrayRead(DC, &dca));
    PetscCall(VecDestroy(&DC));
    PetscCall(VecDestroy(&G));
    PetscCall(VecDestroy(&N));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &scene->pairFallback, 1, MPIU_INT, MPI_SUM, scene->comm));
  }
  PetscCall(PetscFree(tris));

  /* the gap range of each pair */
  for (PetscInt g = 0; g < scene->nContact; g++) {
    SSStarContactGroup *cg       = &scene->contact[g];
    PetscReal           range[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL};

    if (!cg->master[0]) continue;
    for (PetscInt i = 0; i < scene->n; i++)
      if (scene->group[i] == g) {
        range[0] = PetscMin(range[0], scene->gap[i]);
        range[1] = PetscMin(range[1], -scene->gap[i]);
      }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 2, MPIU_REAL, MPIU_MIN, scene->comm));
    cg->gapMin = range[0];
    cg->gapMax = -range[1];
  }

  /* B: 3 rows per contact node, R at its own dofs, -w_j R at the dofs of the master vertices */
  PetscCall(DMCreateGlobalVector(dm, &x));
  PetscCall(VecGetLocalSize(x, &m));
  PetscCall(VecDestroy(&x));
  PetscCall(MatDestroy(&scene->B));
  PetscCall(MatCreate(scene->comm, &scene->B));
  PetscCall(MatSetSizes(scene->B, 3 * scene->n, m, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(scene->B, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(scene->B, mortar ? 3 + 3 * 24 : 12, NULL));
  PetscCall(MatMPIAIJSetPreallocation(scene->B, mortar ? 3 + 3 * 24 : 12, NULL, mortar ? 3 * 24 : 9, NULL));
  PetscCall(MatSetOption(scene->B, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscCall(MatGetOwnershipRange(scene->B, &rstart, NULL));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscReal *R = &scene->frame[9 * i], *wt = &scene->weight[6 * i];

    for (PetscInt c = 0; c < 3; c++) {
      const PetscInt row = rstart + 3 * i + c;

      for (PetscInt k = 0; k < 3; k++) PetscCall(MatSetValue(scene->B, row, own[3 * i + k], R[3 * c + k], ADD_VALUES));
      if (mortar && mortar[i]) {
        PetscInt           nc;
        const PetscInt    *mc;
        const PetscScalar *mv;

        PetscCall(MatGetRow(Mm, own[3 * i], &nc, &mc, &mv));
        for (PetscInt e = 0; e < nc; e++)
          for (PetscInt k = 0; k < 3; k++)
            if (R[3 * c + k] != 0) PetscCall(MatSetValue(scene->B, row, mc[e] + k, -PetscRealPart(mv[e]) / wt[3] * R[3 * c + k], ADD_VALUES));
        PetscCall(MatRestoreRow(Mm, own[3 * i], &nc, &mc, &mv));
        continue;
      }
      for (PetscInt j = 0; j < 3; j++) {
        if (wt[j] < 0 || wt[3 + j] == 0) continue;
        for (PetscInt k = 0; k < 3; k++)
          if (R[3 * c + k] != 0) PetscCall(MatSetValue(scene->B, row, (PetscInt)wt[j] + k, -wt[3 + j] * R[3 * c + k], ADD_VALUES));
      }
    }
  }
  PetscCall(ISRestoreIndices(scene->isC, &own));
  PetscCall(MatAssemblyBegin(scene->B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(scene->B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatDestroy(&Mm));
  PetscCall(PetscFree(mortar));
  PetscFunctionReturn(0);
}

/*
   The contact kinematics and tractions of every contact node at the solution u (r = K u - b), for /contact: gap (the
   normal gap w_n at the solution), pressure (r.n / area), traction (the tangential traction, global axes, 3 per node)
   and slip (the tangential relative displacement w_t: the slave node against the master surface, or against the
   rigid obstacle; global axes, 3 per node), in the order of the contact nodes.
*/
PetscErrorCode SSStarSceneContactKinematics(SSStarScene scene, Vec u, Vec r, PetscReal gap[], PetscReal pressure[], PetscReal traction[], PetscReal slip[])
{
  const PetscInt     n = scene->n;
  const PetscScalar *wa, *ra;
  Vec                w = NULL, uC = NULL, rC;

  PetscFunctionBegin;
  if (scene->B) {
    PetscCall(MatCreateVecs(scene->B, NULL, &w));
    PetscCall(MatMult(scene->B, u, w));
    PetscCall(VecGetArrayRead(w, &wa));
  } else {
    PetscCall(VecGetSubVector(u, scene->isC, &uC));
    PetscCall(VecGetArrayRead(uC, &wa));
  }
  PetscCall(VecGetSubVector(r, scene->isC, &rC));
  PetscCall(VecGetArrayRead(rC, &ra));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal *nn = &scene->normal[3 * i];
    PetscReal        rn = 0, d[3], dn = 0;

    if (scene->B) { /* w in the frame: back to global axes, R^T w */
      const PetscReal *R = &scene->frame[9 * i];

      for (PetscInt k = 0; k < 3; k++) d[k] = R[k] * PetscRealPart(wa[3 * i]) + R[3 + k] * PetscRealPart(wa[3 * i + 1]) + R[6 + k] * PetscRealPart(wa[3 * i + 2]);
    } else
      for (PetscInt k = 0; k < 3; k++) d[k] = PetscRealPart(wa[3 * i + k]);
    for (PetscInt k = 0; k < 3; k++) {
      rn += PetscRealPart(ra[3 * i + k]) * nn[k];
      dn += d[k] * nn[k];
    }
    gap[i]      = dn + scene->gap[i];
    pressure[i] = scene->area[i] > 0 ? rn / scene->area[i] : 0;
    for (PetscInt k = 0; k < 3; k++) {
      traction[3 * i + k] = scene->area[i] > 0 ? (PetscRealPart(ra[3 * i + k]) - rn * nn[k]) / scene->area[i] : 0;
      slip[3 * i + k]     = d[k] - dn * nn[k];
    }
  }
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreSubVector(r, scene->isC, &rC));
  if (w) {
    PetscCall(VecRestoreArrayRead(w, &wa));
    PetscCall(VecDestroy(&w));
  } else {
    PetscCall(VecRestoreArrayRead(uC, &wa));
    PetscCall(VecRestoreSubVector(u, scene->isC, &uC));
  }
  PetscFunctionReturn(0);
}
