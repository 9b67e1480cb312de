/* P1 linear elasticity on tetrahedra: stiffness K (materials per volume group, springs) and load b (tractions, gravity). */
#include "../sceneimpl.h"
#include <petscsf.h>

/* Gradients of the four barycentric basis functions of the tetrahedron x[12]; returns its volume. */
PetscReal SSStarTetGradients(const PetscReal x[12], PetscReal grad[4][3])
{
  PetscReal J[3][3], inv[3][3], det;

  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt k = 0; k < 3; k++) J[r][k] = x[3 * (k + 1) + r] - x[r]; /* columns: edges from vertex 0 */
  det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  inv[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det;
  inv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
  inv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
  inv[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det;
  inv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
  inv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
  inv[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det;
  inv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
  inv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
  /* grad lambda_{a+1} = row a of J^{-1}; grad lambda_0 = -sum */
  for (PetscInt k = 0; k < 3; k++) {
    grad[0][k] = 0;
    for (PetscInt a = 0; a < 3; a++) {
      grad[a + 1][k] = inv[a][k];
      grad[0][k] -= inv[a][k];
    }
  }
  return PetscAbsReal(det) / 6.0;
}

/* K_{ai,bj} = vol (lambda g_a,i g_b,j + mu g_a,j g_b,i + mu delta_ij g_a.g_b) */
static void TetStiffness(const PetscReal x[12], PetscReal lambda, PetscReal mu, PetscScalar K[144])
{
  PetscReal g[4][3];
  PetscReal vol = SSStarTetGradients(x, g);

  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt b = 0; b < 4; b++) {
      const PetscReal gab = g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2];
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt j = 0; j < 3; j++) K[(3 * a + i) * 12 + 3 * b + j] = vol * (lambda * g[a][i] * g[b][j] + mu * g[a][j] * g[b][i] + (i == j ? mu * gab : 0.0));
    }
}

/* The coordinates of the vertices of point (in closure order); n is the count expected, 3 per vertex. */
static PetscErrorCode GetVertexCoordinates(DM dm, PetscInt point, PetscInt n, PetscReal x[], PetscBool *ok)
{
  DM           cdm;
  Vec          coordinates;
  PetscSection csec;
  PetscScalar *xc = NULL;
  PetscInt     nx;

  PetscFunctionBegin;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
  PetscCall(DMPlexVecGetClosure(cdm, csec, coordinates, point, &nx, &xc));
  *ok = (PetscBool)(nx == n);
  for (PetscInt k = 0; k < PetscMin(n, nx); k++) x[k] = PetscRealPart(xc[k]);
  PetscCall(DMPlexVecRestoreClosure(cdm, csec, coordinates, point, &nx, &xc));
  PetscFunctionReturn(0);
}

/* The Lame parameters of E, nu, with the checks naming the option they came from */
static PetscErrorCode LameParameters(MPI_Comm comm, PetscReal E, PetscReal nu, const char option[], PetscReal *lambda, PetscReal *mu)
{
  PetscFunctionBegin;
  PetscCheck(E > 0 && !PetscIsInfOrNanReal(E), comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: Young's modulus E = %g must be a positive number", option, (double)E);
  PetscCheck(nu > -1 && nu < 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE, "%s: Poisson's ratio nu = %g must be in (-1, 0.5)", option, (double)nu);
  *lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  *mu     = E / (2 * (1 + nu));
  PetscFunctionReturn(0);
}

/*
   The Lame parameters of every local cell (lame, or NULL): those of its -material_<G> group, else of -E, -nu; and its
   density (rho, or NULL): its group's (-material_<G> E,nu,rho), else -density's (-1 where neither is given). A cell in
   two material groups, or in none without -E and -nu, is an error naming the options.
*/
PetscErrorCode SSStarCellMaterials(SSStarScene scene, PetscInt cStart, PetscInt cEnd, PetscReal (*lame)[2], PetscReal rho[])
{
  PetscReal(*groupLame)[2];
  DMLabel    *labels;
  PetscInt    conflict[2] = {-1, -1}; /* two groups of one cell (found * nMaterials + m); a cell without material */
  PetscBool   hasGlobal   = (PetscBool)(scene->hasE && scene->hasNu);
  PetscReal   global[2]   = {0, 0}, none[2];
  char        option[SSSTAR_GROUP_NAME_LEN + 16];

  PetscFunctionBegin;
  if (hasGlobal) PetscCall(LameParameters(scene->comm, scene->E, scene->nu, "-E, -nu", &global[0], &global[1]));
  PetscCall(PetscMalloc2(scene->nMaterials, &labels, scene->nMaterials, &groupLame));
  for (PetscInt m = 0; m < scene->nMaterials; m++) {
    PetscCall(DMGetLabel(scene->dm, scene->materials[m].name, &labels[m]));
    PetscCall(PetscSNPrintf(option, sizeof(option), "-material_%s", scene->materials[m].name));
    PetscCall(LameParameters(scene->comm, scene->materials[m].value[0], scene->materials[m].value[1], option, &groupLame[m][0], &groupLame[m][1]));
  }
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscReal *cell = lame ? lame[c - cStart] : none;
    PetscInt   found = -1;

    cell[0] = global[0];
    cell[1] = global[1];
    if (rho) rho[c - cStart] = scene->hasDensity ? scene->density : -1;
    for (PetscInt m = 0; m < scene->nMaterials; m++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(labels[m], c, &value));
      if (value < 0) continue;
      if (found >= 0) conflict[0] = found * scene->nMaterials + m;
      found   = m;
      cell[0] = groupLame[m][0];
      cell[1] = groupLame[m][1];
      if (rho && scene->materials[m].count > 2) rho[c - cStart] = scene->materials[m].value[2];
    }
    if (found < 0 && !hasGlobal) conflict[1] = c;
  }
  PetscCall(PetscFree2(labels, groupLame));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, conflict, 2, MPIU_INT, MPI_MAX, scene->comm));
  PetscCheck(conflict[0] < 0, scene->comm, PETSC_ERR_ARG_WRONG, "Options -material_%s and -material_%s contradict each other: some cells are in both volume groups", scene->materials[conflict[0] / PetscMax(scene->nMaterials, 1)].name, scene->materials[conflict[0] % PetscMax(scene->nMaterials, 1)].name);
  PetscCheck(conflict[1] < 0, scene->comm, PETSC_ERR_ARG_WRONG, "Incomplete material: some cells are in no -material_<G> volume group, and -E and -nu are not both given");
  PetscFunctionReturn(0);
}

/* The area of a boundary face of group (a triangle) and its vertex coordinates */
static PetscErrorCode BoundaryTriangle(DM dm, PetscInt f, const char group[], PetscReal x[9], PetscReal *area)
{
  PetscReal n[3];
  PetscInt  support;
  PetscBool triangle;

  PetscFunctionBegin;
  PetscCall(GetVertexCoordinates(dm, f, 9, x, &triangle));
  PetscCheck(triangle, PETSC_COMM_SELF, PETSC_ERR_SUP, "Face %" PetscInt_FMT " of physical group \"%s\" is not a triangle", f, group);
  PetscCall(DMPlexGetSupportSize(dm, f, &support));
  PetscCheck(support == 1, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "The triangle (%g, %g, %g), (%g, %g, %g), (%g, %g, %g) of physical group \"%s\" is not on the boundary of the body", (double)x[0], (double)x[1], (double)x[2], (double)x[3], (double)x[4], (double)x[5], (double)x[6], (double)x[7], (double)x[8], group);
  *area = SSStarTriangleNormal(&x[0], &x[3], &x[6], n);
  PetscFunctionReturn(0);
}

/* The faces of a surface group on this rank (NULL and 0 when it has none here) */
static PetscErrorCode GroupFaces(DM dm, const char group[], IS *faces, PetscInt *n)
{
  DMLabel  label;
  PetscInt fStart, fEnd, count = 0, *f;

  PetscFunctionBegin;
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(PetscMalloc1(fEnd - fStart, &f));
  for (PetscInt p = fStart; p < fEnd; p++) {
    PetscInt value;

    PetscCall(DMLabelGetValue(label, p, &value));
    if (value >= 0) f[count++] = p;
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, count, f, PETSC_OWN_POINTER, faces));
  *n = count;
  PetscFunctionReturn(0);
}

/* The global block (node) index of every local vertex, its first global dof / 3; -1 when it is held (no dofs) */
PetscErrorCode SSStarVertexBlocks(DM dm, PetscInt vStart, PetscInt vEnd, PetscInt **blocks)
{
  PetscSection gsec;

  PetscFunctionBegin;
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(PetscMalloc1(vEnd - vStart, blocks));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt dof, cdof, off;

    PetscCall(PetscSectionGetDof(gsec, v, &dof));
    PetscCall(PetscSectionGetConstraintDof(gsec, v, &cdof));
    PetscCall(PetscSectionGetOffset(gsec, v, &off));
    if (dof < 0) { /* a ghost: -(dof + 1), -(offset + 1) of its owner */
      dof = -(dof + 1);
      off = -(off + 1);
    }
    (*blocks)[v - vStart] = dof - cdof == 3 ? off / 3 : -1;
  }
  PetscFunctionReturn(0);
}

/* The four vertices of every local cell, numbered from vStart */
static PetscErrorCode CellVertices(DM dm, PetscInt cStart, PetscInt cEnd, PetscInt vStart, PetscInt **cv)
{
  PetscFunctionBegin;
  PetscCall(PetscMalloc1(4 * (cEnd - cStart), cv));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt *v = &(*cv)[4 * (c - cStart)];

    PetscCall(SSStarMeshCellVertices(dm, c, v));
    for (PetscInt k = 0; k < 4; k++) v[k] -= vStart;
  }
  PetscFunctionReturn(0);
}

/*
   The block preallocation of K: every vertex couples to the vertices of its cells. A vertex on a partition boundary has
   cells on other ranks: each rank counts the neighbours it sees (in the owner's diagonal and off-diagonal column
   ranges) and the counts go to the owner through the point SF, an upper bound of the union.
*/
static PetscErrorCode PreallocateStiffness(DM dm, Mat K, PetscInt cStart, PetscInt cEnd, PetscInt vStart, PetscInt vEnd, const PetscInt cv[], const PetscInt blocks[])
{
  MPI_Comm        comm = PetscObjectComm((PetscObject)dm);
  const PetscInt  nv = vEnd - vStart, nc = cEnd - cStart;
  const PetscInt *ilocal;
  const PetscSFNode *iremote;
  PetscInt       *start, *adj, *fill, *owner, *count, *dnz, *onz, *ranges, pStart, pEnd, nleaves, rstart, rend, m, Ncol;
  PetscSF         sf;
  PetscMPIInt     rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetLocalSize(K, &m, NULL)); /* the rows of each rank (K's layout is not set up before preallocation) */
  PetscCall(MatGetSize(K, NULL, &Ncol));
  PetscCall(PetscMalloc1(size + 1, &ranges));
  ranges[0] = 0;
  PetscCallMPI(MPI_Allgather(&m, 1, MPIU_INT, ranges + 1, 1, MPIU_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) ranges[r + 1] += ranges[r];
  rstart = ranges[rank];
  rend   = ranges[rank + 1];
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, &iremote));
  /* the owner rank of every local vertex */
  PetscCall(PetscMalloc1(nv, &owner));
  for (PetscInt v = 0; v < nv; v++) owner[v] = rank;
  for (PetscInt l = 0; l < nleaves; l++) {
    const PetscInt p = ilocal ? ilocal[l] : l;

    if (p >= vStart && p < vEnd) owner[p - vStart] = iremote[l].rank;
  }
  /* the neighbours of every vertex through its local cells (CSR, 4 per cell and vertex), sorted and unique */
  PetscCall(PetscCalloc2(nv + 1, &start, nv, &fill));
  for (PetscInt k = 0; k < 4 * nc; k++) start[cv[k] + 1] += 4;
  for (PetscInt v = 0; v < nv; v++) start[v + 1] += start[v];
  PetscCall(PetscMalloc1(start[nv], &adj));
  for (PetscInt c = 0; c < nc; c++)
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt v = cv[4 * c + a];

      for (PetscInt b = 0; b < 4; b++) adj[start[v] + fill[v]++] = blocks[cv[4 * c + b]];
    }
  /* count[2 p], count[2 p + 1]: the diagonal and off-diagonal neighbours of point p, in its owner's ranges */
  PetscCall(PetscCalloc1(2 * (pEnd - pStart), &count));
  for (PetscInt v = 0; v < nv; v++) {
    PetscInt  n = fill[v], *row = adj + start[v];
    const PetscInt lo = ranges[owner[v]] / 3, hi = ranges[owner[v] + 1] / 3;

    if (blocks[v] < 0) continue;
    PetscCall(PetscSortRemoveDupsInt(&n, row));
    for (PetscInt k = 0; k < n; k++) {
      if (row[k] < 0) continue;
      count[2 * (vStart + v - pStart) + (row[k] >= lo && row[k] < hi ? 0 : 1)]++;
    }
  }
  {
    MPI_Datatype pair;

    PetscCallMPI(MPI_Type_contiguous(2, MPIU_INT, &pair));
    PetscCallMPI(MPI_Type_commit(&pair));
    PetscCall(PetscSFReduceBegin(sf, pair, count, count, MPI_SUM));
    PetscCall(PetscSFReduceEnd(sf, pair, count, count, MPI_SUM));
    PetscCallMPI(MPI_Type_free(&pair));
  }
  m = (rend - rstart) / 3;
  PetscCall(PetscCalloc2(m, &dnz, m, &onz));
  for (PetscInt v = 0; v < nv; v++) {
    const PetscInt b = blocks[v] - rstart / 3, Nb = ranges[rank + 1] / 3 - ranges[rank] / 3, No = Ncol / 3 - Nb;

    if (owner[v] != rank || blocks[v] < 0) continue;
    dnz[b] = PetscMin(count[2 * (vStart + v - pStart)], Nb);
    onz[b] = PetscMin(count[2 * (vStart + v - pStart) + 1], No);
  }
  PetscCall(MatXAIJSetPreallocation(K, 3, dnz, onz, NULL, NULL));
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(PetscFree(count));
  PetscCall(PetscFree(adj));
  PetscCall(PetscFree2(start, fill));
  PetscCall(PetscFree(owner));
  PetscCall(PetscFree(ranges));
  PetscFunctionReturn(0);
}

/*
   K in 3x3 blocks: every cell adds its 12x12 matrix, every face of a spring group k area/3 to the diagonal of its
   vertices (a lumped elastic support); held (Dirichlet) vertices have no block and drop out.
*/
static PetscErrorCode AssembleStiffness(SSStarScene scene, Mat *K)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       csec;
  Vec                cloc, global;
  const PetscScalar *ca;
  PetscInt           cStart, cEnd, vStart, vEnd, n, N, *cv, *blocks;
  PetscReal(*lame)[2];

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(cEnd - cStart, &lame));
  PetscCall(SSStarCellMaterials(scene, cStart, cEnd, lame, NULL));
  PetscCall(CellVertices(dm, cStart, cEnd, vStart, &cv));
  PetscCall(SSStarVertexBlocks(dm, vStart, vEnd, &blocks));
  PetscCall(DMGetGlobalVector(dm, &global));
  PetscCall(VecGetLocalSize(global, &n));
  PetscCall(VecGetSize(global, &N));
  PetscCall(DMRestoreGlobalVector(dm, &global));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)dm), K));
  PetscCall(MatSetSizes(*K, n, n, N, N));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, MATAIJ));
  PetscCall(PreallocateStiffness(dm, *K, cStart, cEnd, vStart, vEnd, cv, blocks));

  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetCoordinatesLocal(dm, &cloc));
  PetscCall(VecGetArrayRead(cloc, &ca));
  for (PetscInt c = cStart; c < cEnd; c++) {
    const PetscInt *v = &cv[4 * (c - cStart)];
    PetscInt        b[4];
    PetscReal       x[12];
    PetscScalar     Ke[144];

    for (PetscInt a = 0; a < 4; a++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(csec, vStart + v[a], &off));
      for (PetscInt k = 0; k < 3; k++) x[3 * a + k] = PetscRealPart(ca[off + k]);
      b[a] = blocks[v[a]];
    }
    TetStiffness(x, lame[c - cStart][0], lame[c - cStart][1], Ke);
    PetscCall(MatSetValuesBlocked(*K, 4, b, 4, b, Ke, ADD_VALUES));
  }
  PetscCall(VecRestoreArrayRead(cloc, &ca));
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    IS              faces;
    const PetscInt *f;
    PetscInt        nf;

    PetscCall(GroupFaces(dm, scene->springs[s].name, &faces, &nf));
    PetscCall(ISGetIndices(faces, &f));
    for (PetscInt i = 0; i < nf; i++) {
      PetscInt   *closure = NULL, ncl;
      PetscReal   x[9], area;
      PetscScalar D[9] = {0};

      PetscCall(BoundaryTriangle(dm, f[i], scene->springs[s].name, x, &area));
      D[0] = D[4] = D[8] = scene->springs[s].value[0] * area / 3.0;
      PetscCall(DMPlexGetTransitiveClosure(dm, f[i], PETSC_TRUE, &ncl, &closure));
      for (PetscInt k = 0; k < 2 * ncl; k += 2) {
        PetscInt bk;

        if (closure[k] < vStart || closure[k] >= vEnd) continue;
        bk = blocks[closure[k] - vStart];
        PetscCall(MatSetValuesBlocked(*K, 1, &bk, 1, &bk, D, ADD_VALUES));
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, f[i], PETSC_TRUE, &ncl, &closure));
    }
    PetscCall(ISRestoreIndices(faces, &f));
    PetscCall(ISDestroy(&faces));
  }
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(blocks));
  PetscCall(PetscFree(cv));
  PetscCall(PetscFree(lame));
  PetscFunctionReturn(0);
}

/* Adds the consistent load of a constant traction t on the triangles of group, area/3 t per vertex, to Floc (if not
   NULL); area (if not NULL): the group's area on this rank */
static PetscErrorCode TractionLoad(DM dm, const char group[], const PetscReal t[3], Vec Floc, PetscReal *area)
{
  IS              faces;
  const PetscInt *f;
  PetscInt        nf;

  PetscFunctionBegin;
  if (area) *area = 0;
  PetscCall(GroupFaces(dm, group, &faces, &nf));
  PetscCall(ISGetIndices(faces, &f));
  for (PetscInt i = 0; i < nf; i++) {
    PetscScalar load[9];
    PetscReal   x[9], a;

    PetscCall(BoundaryTriangle(dm, f[i], group, x, &a));
    if (area) *area += a;
    if (!Floc) continue;
    for (PetscInt v = 0; v < 3; v++)
      for (PetscInt k = 0; k < 3; k++) load[3 * v + k] = a / 3.0 * t[k];
    PetscCall(DMPlexVecSetClosure(dm, NULL, Floc, f[i], load, ADD_VALUES));
  }
  PetscCall(ISRestoreIndices(faces, &f));
  PetscCall(ISDestroy(&faces));
  PetscFunctionReturn(0);
}

/* Adds the consistent load of a constant traction t on the triangles of group: area/3 t per vertex. */
PetscErrorCode SSStarAddTraction(DM dm, const char group[], const PetscReal t[3], Vec Floc)
{
  PetscFunctionBegin;
  PetscCall(TractionLoad(dm, group, t, Floc, NULL));
  PetscFunctionReturn(0);
}

/* Adds the consistent load of the body force rho g: vol/4 rho g per vertex of every cell, rho the cell's density. */
static PetscErrorCode AddGravity(SSStarScene scene, const PetscReal g[3], Vec Floc)
{
  DM         dm = scene->dm;
  PetscInt   cStart, cEnd;
  PetscReal *rho;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc1(cEnd - cStart + 1, &rho));
  PetscCall(SSStarCellMaterials(scene, cStart, cEnd, NULL, rho));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscScalar load[12];
    PetscReal   x[12], grad[4][3], vol;
    PetscBool   tet;

    PetscCall(GetVertexCoordinates(dm, c, 12, x, &tet));
    vol = SSStarTetGradients(x, grad);
    for (PetscInt v = 0; v < 4; v++)
      for (PetscInt k = 0; k < 3; k++) load[3 * v + k] = vol / 4.0 * PetscMax(rho[c - cStart], 0) * g[k];
    PetscCall(DMPlexVecSetClosure(dm, NULL, Floc, c, load, ADD_VALUES));
  }
  PetscCall(PetscFree(rho));
  PetscFunctionReturn(0);
}

/*
   The stiffness K and load b of P1 linear elasticity with the scene's materials, springs, tractions and gravity
   (u = 0 on the Dirichlet groups is built into the dofs)
*/
/*
   The rigid-body modes in the layout of K (the coordinates of its free dofs, block size 3): as K's near-null space, the
   six of the whole mesh, from which algebraic multigrid (PCGAMG) builds its coarse spaces (it halves its iterations on
   elasticity; the whole-body Newton step of ssstar uses it); as K's null space, six for each floating body (held by
   contact alone, bodies.c), orthonormal: K does not resist them, and the solver needs to know it (docs/derivation.md
   section 14)
*/
static PetscErrorCode SetRigidBodyModes(SSStarScene scene, Mat K)
{
  DM                 dm = scene->dm, cdm;
  PetscSection       sec, csec;
  Vec                cloc, xloc, x, *modes;
  PetscInt           vStart, vEnd, nmodes = 6 * scene->nFloating;
  const PetscScalar *ca;
  PetscScalar       *xa;
  MatNullSpace       nsp;

  PetscFunctionBegin;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetCoordinatesLocal(dm, &cloc));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetLocalVector(dm, &xloc));
  PetscCall(VecGetArrayRead(cloc, &ca));
  PetscCall(PetscMalloc1(nmodes + 1, &modes));
  /* mode 6 b + k of floating body b: the translation along axis k (k < 3), the rotation about axis k - 3 */
  for (PetscInt mode = -1; mode < nmodes; mode++) {
    PetscCall(VecGetArrayWrite(xloc, &xa));
    for (PetscInt v = vStart; v < vEnd; v++) {
      PetscInt off, coff, dof;

      PetscCall(PetscSectionGetDof(sec, v, &dof));
      if (dof != 3) continue;
      PetscCall(PetscSectionGetOffset(sec, v, &off));
      PetscCall(PetscSectionGetOffset(csec, v, &coff));
      for (PetscInt k = 0; k < 3; k++) xa[off + k] = mode < 0 ? ca[coff + k] : 0.0;
      if (mode >= 0 && scene->body[v - vStart] == scene->floating[mode / 6]) {
        const PetscInt k = mode % 6;

        if (k < 3) xa[off + k] = 1;
        else { /* e_a x x */
          const PetscInt a = k - 3, b = (a + 1) % 3, c = (a + 2) % 3;

          xa[off + b] = -ca[coff + c];
          xa[off + c] = ca[coff + b];
        }
      }
    }
    PetscCall(VecRestoreArrayWrite(xloc, &xa));
    PetscCall(DMCreateGlobalVector(dm, &x)); /* the held dofs are not in it */
    PetscCall(DMLocalToGlobal(dm, xloc, INSERT_VALUES, x));
    PetscCall(VecSetBlockSize(x, 3));
    if (mode < 0) {
      PetscCall(MatNullSpaceCreateRigidBody(x, &nsp));
      PetscCall(MatSetNearNullSpace(K, nsp));
      PetscCall(MatNullSpaceDestroy(&nsp));
      PetscCall(VecDestroy(&x));
    } else modes[mode] = x;
  }
  PetscCall(VecRestoreArrayRead(cloc, &ca));
  PetscCall(DMRestoreLocalVector(dm, &xloc));
  if (nmodes) {
    for (PetscInt k = 0; k < nmodes; k++) /* Gram-Schmidt, twice: the rotations about the body's centroid */
      for (PetscInt pass = 0; pass < 2; pass++) {
        for (PetscInt j = 6 * (k / 6); j < k; j++) {
          PetscScalar dot;

          PetscCall(VecDot(modes[k], modes[j], &dot));
          PetscCall(VecAXPY(modes[k], -dot, modes[j]));
        }
        PetscCall(VecNormalize(modes[k], NULL));
      }
    PetscCall(MatNullSpaceCreate(scene->comm, PETSC_FALSE, nmodes, modes, &nsp));
    PetscCall(MatSetNullSpace(K, nsp));
    PetscCall(MatNullSpaceDestroy(&nsp));
  }
  for (PetscInt k = 0; k < nmodes; k++) PetscCall(VecDestroy(&modes[k]));
  PetscCall(PetscFree(modes));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarAssembleElasticity(SSStarScene scene, PetscReal t, Mat *K, Vec *b)
{
  DM dm = scene->dm;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscCall(AssembleStiffness(scene, K));
  PetscCall(MatSetOption(*K, scene->nFloating ? MAT_SYMMETRIC : MAT_SPD, PETSC_TRUE)); /* floating: semidefinite */
  PetscCall(SetRigidBodyModes(scene, *K));

  PetscCall(DMCreateGlobalVector(dm, b));
  PetscCall(PetscObjectSetName((PetscObject)*b, "load"));
  PetscCall(SSStarAssembleLoad(scene, t, *b));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The load b at the time t of the histories: the tractions and gravity evaluated at t (a surface and a volume loop) */
PetscErrorCode SSStarAssembleLoad(SSStarScene scene, PetscReal t, Vec b)
{
  DM        dm = scene->dm;
  Vec       Floc;
  PetscReal value[3];

  PetscFunctionBegin;
  PetscCall(DMGetLocalVector(dm, &Floc));
  PetscCall(VecZeroEntries(Floc));
  for (PetscInt k = 0; k < scene->nTractions; k++) {
    PetscCall(SSStarHistoryEvaluate(scene->tractions[k].history, t, value));
    PetscCall(SSStarAddTraction(dm, scene->tractions[k].name, value, Floc));
  }
  if (scene->hasGravity) {
    PetscCall(SSStarHistoryEvaluate(scene->gravityHistory, t, value));
    PetscCall(AddGravity(scene, value, Floc));
  }
  PetscCall(VecZeroEntries(b));
  PetscCall(DMLocalToGlobal(dm, Floc, ADD_VALUES, b));
  PetscCall(DMRestoreLocalVector(dm, &Floc));
  PetscFunctionReturn(0);
}

/* The area of a surface group (all ranks) */
PetscErrorCode SSStarGroupArea(DM dm, const char group[], PetscReal *area)
{
  PetscFunctionBegin;
  PetscCall(TractionLoad(dm, group, NULL, NULL, area));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, area, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)dm)));
  PetscFunctionReturn(0);
}
