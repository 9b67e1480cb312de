/*
   Dual mortar for the contact pairs (-pair_discretization dual_mortar; Wohlmuth 2000, Popp et al. 2010): a slave node's
   contact point is its dual-basis weighted average over the slave surface, compared with the master surface over the
   overlap of the slave faces with the master triangles (pairs.c), so that the contact pressure passes the patch test.
   The master triangles a slave face may overlap are those whose projections onto its plane meet its box there: the
   search over the ranks finds them (SSStarSearchFindInRegions(), the prism of the face's box along its normal).
   Where the master does not cover a slave node, the node keeps node-to-surface.
*/
#include "master.h"

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
   The plane of a slave triangle x with normal n: axes e1 (along its first edge) and e2 = n x e1 from its first vertex;
   its vertices there (S), counterclockwise (T); the region of the master triangles that may overlap it: the prism of
   its box in the plane, along n
*/
static void SlavePlane(const PetscReal x[9], const PetscReal n[3], PetscReal e1[3], PetscReal e2[3], PetscReal S[3][2], PetscReal T[3][2], SSStarRegion *region)
{
  PetscReal len;

  for (PetscInt c = 0; c < 3; c++) e1[c] = x[3 + c] - x[c];
  len = PetscSqrtReal(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (PetscInt c = 0; c < 3; c++) e1[c] /= len;
  SSStarCross3(n, e1, e2);
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
  for (PetscInt c = 0; c < 3; c++) {
    region->origin[c]   = x[c];
    region->axes[c]     = e1[c];
    region->axes[3 + c] = e2[c];
    region->axes[6 + c] = n[c];
  }
  for (PetscInt c = 0; c < 2; c++) {
    region->lo[c] = PetscMin(S[0][c], PetscMin(S[1][c], S[2][c]));
    region->hi[c] = PetscMax(S[0][c], PetscMax(S[1][c], S[2][c]));
  }
  region->lo[2] = PETSC_NINFINITY;
  region->hi[2] = PETSC_INFINITY;
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
   The master triangles of a slave face: those whose projections meet its box in its plane, in the order of their keys.
*/
static PetscErrorCode MortarIntegrals(SSStarScene scene, PetscInt g, SSStarSearch search, Mat *Mm, Vec *DC, Vec *G, Vec *N)
{
  SSStarFaces      faces;
  DMLabel          label;
  PetscInt         m, xstart, *dnz, *face, nf = 0, *offset;
  const PetscInt  *own;
  SSStarRegion    *region;
  SSStarSearchHit *hit;
  PetscReal       *data;

  PetscFunctionBegin;
  PetscCall(DMCreateGlobalVector(scene->dm, DC));
  PetscCall(VecZeroEntries(*DC));
  PetscCall(VecDuplicate(*DC, G));
  PetscCall(VecDuplicate(*DC, N));
  PetscCall(VecZeroEntries(*G));
  PetscCall(VecZeroEntries(*N));
  PetscCall(VecGetLocalSize(*DC, &m));
  PetscCall(VecGetOwnershipRange(*DC, &xstart, NULL));
  /* room at the x-dofs of this rank's slave nodes */
  PetscCall(PetscCalloc1(m + 1, &dnz));
  PetscCall(ISGetIndices(scene->isC, &own));
  for (PetscInt i = 0; i < scene->n; i++)
    if (scene->group[i] == g) dnz[own[3 * i] - xstart] = 64;
  PetscCall(ISRestoreIndices(scene->isC, &own));
  PetscCall(MatCreate(scene->comm, Mm));
  PetscCall(MatSetSizes(*Mm, m, m, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(*Mm, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(*Mm, 0, dnz));
  PetscCall(MatMPIAIJSetPreallocation(*Mm, 0, dnz, 0, dnz));
  PetscCall(MatSetOption(*Mm, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  PetscCall(PetscFree(dnz));
  PetscCall(SSStarFacesBegin(scene, &faces));
  PetscCall(DMGetLabel(scene->dm, scene->contact[g].name, &label));
  PetscCall(PetscMalloc2(faces.fEnd - faces.fStart + 1, &face, faces.fEnd - faces.fStart + 1, &region));
  for (PetscInt f = faces.fStart; f < faces.fEnd; f++) { /* the slave faces owned here and their regions */
    PetscInt  value, dof[3], tag[3], vertex;
    PetscReal x[9], n[3], e1[3], e2[3], area, S[3][2], T[3][2];

    PetscCall(DMLabelGetValue(label, f, &value));
    if (value < 0 || faces.leaf[f]) continue;
    PetscCall(SSStarFaceTriangle(&faces, f, x, dof, tag, &vertex, n, &area)); /* n: out of the slave body */
    SlavePlane(x, n, e1, e2, S, T, &region[nf]);
    face[nf++] = f;
  }
  PetscCall(SSStarSearchFindInRegions(search, nf, region, &offset, &hit, &data));
  for (PetscInt s = 0; s < nf; s++) {
    PetscInt  dof[3], tag[3], vertex;
    PetscReal x[9], n[3], e1[3], e2[3], area, S[3][2], T[3][2];

    PetscCall(SSStarFaceTriangle(&faces, face[s], x, dof, tag, &vertex, n, &area));
    SlavePlane(x, n, e1, e2, S, T, &region[s]);
    for (PetscInt k = 0; k < 3; k++) {
      if (dof[k] < 0) continue;
      PetscCall(VecSetValue(*DC, dof[k], area / 3, ADD_VALUES));
    }
    for (PetscInt e = offset[s]; e < offset[s + 1]; e++) {
      SSStarMasterTriangle tm;
      PetscReal            Mp[3][2], P[12][2], mij[3][3], dot = 0;
      PetscInt             np;

      SSStarMasterTriangleFromHit(&hit[e], &data[SSSTAR_MASTER_DATA * e], &tm);
      for (PetscInt c = 0; c < 3; c++) dot += tm.n[c] * n[c];
      if (dot > -0.3) continue; /* not facing the slave face */
      for (PetscInt k = 0; k < 3; k++) {
        Mp[k][0] = Mp[k][1] = 0;
        for (PetscInt c = 0; c < 3; c++) {
          Mp[k][0] += (tm.x[3 * k + c] - x[c]) * e1[c];
          Mp[k][1] += (tm.x[3 * k + c] - x[c]) * e2[c];
        }
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
          for (PetscInt c = 0; c < 3; c++) gx[c] += mij[i][j] * tm.x[3 * j + c];
          if (tm.dof[j] >= 0 && mij[i][j] != 0) PetscCall(MatSetValue(*Mm, dof[i], tm.dof[j], mij[i][j], ADD_VALUES));
        }
        PetscCall(VecSetValue(*DC, dof[i] + 1, sum, ADD_VALUES));
        for (PetscInt c = 0; c < 3; c++) {
          PetscCall(VecSetValue(*G, dof[i] + c, gx[c], ADD_VALUES));
          PetscCall(VecSetValue(*N, dof[i] + c, sum * tm.n[c], ADD_VALUES));
        }
      }
    }
  }
  PetscCall(PetscFree(offset));
  PetscCall(PetscFree(hit));
  PetscCall(PetscFree(data));
  PetscCall(PetscFree2(face, region));
  PetscCall(SSStarFacesEnd(&faces));
  PetscCall(MatAssemblyBegin(*Mm, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*Mm, MAT_FINAL_ASSEMBLY));
  for (Vec *v = DC; v; v = v == DC ? G : v == G ? N : NULL) {
    PetscCall(VecAssemblyBegin(*v));
    PetscCall(VecAssemblyEnd(*v));
  }
  PetscFunctionReturn(0);
}

/*
   SSStarMortarRows - the rows of the slave nodes of pair g the master covers (sum_j M_ij = D_i): the normal (the master
   normals weighted like the master nodes), the gap of the node against its weighted master point, and the masters
   M_ij / D_i; mortar[i] marks them. The others keep node-to-surface (scene->pairFallback counts them).
*/
PetscErrorCode SSStarMortarRows(SSStarScene scene, PetscInt g, SSStarSearch search, PetscReal tol, PetscBool mortar[], SSStarMasters *masters)
{
  Mat                Mm;
  Vec                DC, G, N;
  const PetscScalar *dca, *ga, *na;
  const PetscInt    *own;
  PetscInt           xstart, fallback = 0;

  PetscFunctionBegin;
  PetscCall(MortarIntegrals(scene, g, search, &Mm, &DC, &G, &N));
  PetscCall(VecGetOwnershipRange(DC, &xstart, NULL));
  PetscCall(VecGetArrayRead(DC, &dca));
  PetscCall(VecGetArrayRead(G, &ga));
  PetscCall(VecGetArrayRead(N, &na));
  PetscCall(ISGetIndices(scene->isC, &own));
  for (PetscInt i = 0; i < scene->n; i++) {
    const PetscInt     xd = own[3 * i] - xstart;
    const PetscReal    D = PetscRealPart(dca[xd]), C = PetscRealPart(dca[xd + 1]);
    PetscReal          n[3], len = 0, gap = 0;
    PetscInt           nc;
    const PetscInt    *mc;
    const PetscScalar *mv;

    if (scene->group[i] != g) continue;
    if (D <= 0 || PetscAbsReal(C / D - 1) > 1e-6) {
      fallback++;
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
    PetscCall(MatGetRow(Mm, own[3 * i], &nc, &mc, &mv));
    for (PetscInt e = 0; e < nc; e++) PetscCall(SSStarMastersAdd(masters, i, mc[e], PetscRealPart(mv[e]) / D));
    PetscCall(MatRestoreRow(Mm, own[3 * i], &nc, &mc, &mv));
    mortar[i] = PETSC_TRUE;
  }
  PetscCall(ISRestoreIndices(scene->isC, &own));
  PetscCall(VecRestoreArrayRead(N, &na));
  PetscCall(VecRestoreArrayRead(G, &ga));
  PetscCall(VecRestoreArrayRead(DC, &dca));
  PetscCall(VecDestroy(&DC));
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&N));
  PetscCall(MatDestroy(&Mm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fallback, 1, MPIU_INT, MPI_SUM, scene->comm));
  scene->pairFallback += fallback;
  PetscFunctionReturn(0);
}
