/*
   P1 elasticity on tetrahedra: stiffness K (materials per volume group, springs) and load b (tractions, gravity, the
   lifting of prescribed displacements); for a hyperelastic scene the residual F(u) and its tangent at u
   (docs/derivation.md section 18); the cells' kernels in cells.c and hyperelastic.c, the held dofs in prescribed.c.
*/
#include "../sceneimpl.h"
#include <petscsf.h>

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

/*
   The block preallocation of K: every vertex couples to the vertices of its cells. A vertex on a partition boundary has
   cells on other ranks: each rank counts the neighbours it sees (in the owner's diagonal and off-diagonal column
   ranges) and the counts go to the owner through the point SF, an upper bound of the union. Then K's pattern: each
   vertex's sorted neighbour blocks inserted as zeros (its owner's rows filled in order) and assembled, so that the
   cells add into it in place (blockadd.c).
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
    fill[v] = n;
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
  { /* the pattern: every vertex's sorted neighbours, zeros (a row is filled in order, nothing shifts), assembled */
    PetscScalar *zeros;
    PetscInt     nmax = 0;

    for (PetscInt v = 0; v < nv; v++) nmax = PetscMax(nmax, fill[v]);
    PetscCall(PetscCalloc1(9 * nmax + 1, &zeros));
    for (PetscInt v = 0; v < nv; v++)
      if (blocks[v] >= 0) PetscCall(MatSetValuesBlocked(K, 1, &blocks[v], fill[v], adj + start[v], zeros, ADD_VALUES));
    PetscCall(PetscFree(zeros));
    PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscFree(count));
  PetscCall(PetscFree(adj));
  PetscCall(PetscFree2(start, fill));
  PetscCall(PetscFree(owner));
  PetscCall(PetscFree(ranges));
  PetscFunctionReturn(0);
}

/*
   Adds to K every cell's 12x12 matrix -- Hooke's, or with ua (the local displacement's values) the tangent of the cell's
   material model there (docs/derivation.md (18.3)) -- and the k area/3 of every face of a spring group to the diagonal of
   its vertices (a lumped elastic support); held (Dirichlet) vertices have no block and drop out; a prescribed component
   (-displacement_<G>) gets an identity row (prescribed.c). K holds its pattern already (PreallocateStiffness(), or K's
   matrix for the tangent). *ok: no cell's model refused its deformation (det F <= 0)
*/
static PetscErrorCode AddCellsAndSprings(SSStarScene scene, const SSStarCells *cells, const PetscInt blocks[], PetscSection sec, const PetscScalar ua[], Mat K, PetscBool *ok)
{
  DM             dm = scene->dm;
  SSStarBlockAdd add;

  PetscFunctionBegin;
  *ok = PETSC_TRUE;
  PetscCall(SSStarBlockAddBegin(K, cells->vEnd - cells->vStart, blocks, &add));
  for (PetscInt c = 0; c < cells->cEnd - cells->cStart; c++) {
    const PetscInt *v = &cells->vertices[4 * c];
    PetscInt        b[4];
    PetscReal       x[12], ue[12], fe[12];
    PetscScalar     Ke[144];

    PetscCall(SSStarCellsGet(cells, c, x));
    for (PetscInt a = 0; a < 4; a++) b[a] = blocks[v[a]];
    if (ua) {
      PetscCall(SSStarCellsGetValues(cells, sec, ua, c, ue));
      if (!SSStarTetInternalForce(cells->model[c], cells->lame[c][0], cells->lame[c][1], x, ue, fe, Ke)) *ok = PETSC_FALSE;
    } else SSStarTetStiffness(x, cells->lame[c][0], cells->lame[c][1], Ke);
    SSStarHeldElement(scene, v, Ke);
    PetscCall(SSStarBlockAddCell(&add, v, b, Ke));
  }
  PetscCall(SSStarBlockAddEnd(&add));
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

        if (closure[k] < cells->vStart || closure[k] >= cells->vEnd) continue;
        bk = blocks[closure[k] - cells->vStart];
        PetscCall(MatSetValuesBlocked(K, 1, &bk, 1, &bk, D, ADD_VALUES));
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, f[i], PETSC_TRUE, &ncl, &closure));
    }
    PetscCall(ISRestoreIndices(faces, &f));
    PetscCall(ISDestroy(&faces));
  }
  PetscFunctionReturn(0);
}

/* K in 3x3 blocks, preallocated from the cells' vertices (AddCellsAndSprings() at the reference configuration) */
static PetscErrorCode AssembleStiffness(SSStarScene scene, Mat *K)
{
  DM          dm = scene->dm;
  Vec         global;
  PetscInt    n, N, *blocks;
  PetscBool   ok;
  SSStarCells cells;

  PetscFunctionBegin;
  PetscCall(SSStarCellsBegin(scene, &cells));
  PetscCall(SSStarVertexBlocks(dm, cells.vStart, cells.vEnd, &blocks));
  PetscCall(DMGetGlobalVector(dm, &global));
  PetscCall(VecGetLocalSize(global, &n));
  PetscCall(VecGetSize(global, &N));
  PetscCall(DMRestoreGlobalVector(dm, &global));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)dm), K));
  PetscCall(MatSetSizes(*K, n, n, N, N));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, MATAIJ));
  PetscCall(PreallocateStiffness(dm, *K, cells.cStart, cells.cEnd, cells.vStart, cells.vEnd, cells.vertices, blocks));
  PetscCall(AddCellsAndSprings(scene, &cells, blocks, NULL, NULL, *K, &ok));
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(blocks));
  PetscCall(SSStarCellsEnd(&cells));
  PetscFunctionReturn(0);
}

/*
   SSStarAssembleTangent - the tangent stiffness J = dF/du of a hyperelastic scene at u, into J (K's matrix, its
   pattern): the cells' tangents of their material models (18.3), the springs, the identity rows of the prescribed
   components as in K. *ok (the same on every rank): no cell refused its deformation (neo-Hookean det F <= 0)
*/
PetscErrorCode SSStarAssembleTangent(SSStarScene scene, Vec u, Mat J, PetscBool *ok)
{
  DM                 dm = scene->dm;
  PetscInt          *blocks;
  PetscSection       sec;
  Vec                uloc;
  const PetscScalar *ua;
  SSStarCells        cells;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(VecZeroEntries(uloc)); /* the -dirichlet dofs: 0 */
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, uloc));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(SSStarCellsBegin(scene, &cells));
  PetscCall(SSStarVertexBlocks(dm, cells.vStart, cells.vEnd, &blocks));
  PetscCall(MatZeroEntries(J));
  PetscCall(AddCellsAndSprings(scene, &cells, blocks, sec, ua, J, ok));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(blocks));
  PetscCall(SSStarCellsEnd(&cells));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ok, 1, MPIU_BOOL, MPI_LAND, scene->comm));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
   SSStarAssembleResidual - the residual F(u) = f(u) + k u - load of a hyperelastic scene (docs/derivation.md (18.2)):
   the cells' internal forces of their material models and the springs' forces on the dofs that are not prescribed,
   diag(K) u at the prescribed components (whose load is diag(K) g: SSStarAssembleLoad()). *ok (the same on every rank):
   no cell refused its deformation (neo-Hookean det F <= 0; F is then NaN there)
*/
PetscErrorCode SSStarAssembleResidual(SSStarScene scene, Vec u, Vec load, Vec r, PetscBool *ok)
{
  DM                 dm = scene->dm;
  PetscSection       sec;
  Vec                uloc, floc, wloc;
  const PetscScalar *ua;
  PetscScalar       *fa;
  SSStarCells        cells;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  *ok = PETSC_TRUE;
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetLocalVector(dm, &uloc));
  PetscCall(DMGetLocalVector(dm, &floc));
  PetscCall(VecZeroEntries(uloc)); /* the -dirichlet dofs: 0 */
  PetscCall(DMGlobalToLocal(dm, u, INSERT_VALUES, uloc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecGetArrayRead(uloc, &ua));
  PetscCall(VecGetArray(floc, &fa));
  PetscCall(SSStarCellsBegin(scene, &cells));
  for (PetscInt c = 0; c < cells.cEnd - cells.cStart; c++) {
    const PetscInt *v = &cells.vertices[4 * c];
    PetscReal       x[12], ue[12], fe[12];

    PetscCall(SSStarCellsGet(&cells, c, x));
    PetscCall(SSStarCellsGetValues(&cells, sec, ua, c, ue));
    if (!SSStarTetInternalForce(cells.model[c], cells.lame[c][0], cells.lame[c][1], x, ue, fe, NULL)) *ok = PETSC_FALSE;
    for (PetscInt a = 0; a < 4; a++) {
      PetscInt off;

      PetscCall(PetscSectionGetOffset(sec, cells.vStart + v[a], &off));
      for (PetscInt k = 0; k < 3; k++) fa[off + k] += fe[3 * a + k];
    }
  }
  PetscCall(SSStarCellsEnd(&cells));
  PetscCall(VecRestoreArray(floc, &fa));
  PetscCall(VecRestoreArrayRead(uloc, &ua));
  PetscCall(DMGetLocalVector(dm, &wloc)); /* the springs: k area/3 u per face vertex */
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    const PetscReal k3[3] = {scene->springs[s].value[0], scene->springs[s].value[0], scene->springs[s].value[0]};

    PetscCall(VecZeroEntries(wloc));
    PetscCall(SSStarAddTraction(dm, scene->springs[s].name, k3, wloc));
    PetscCall(VecPointwiseMult(wloc, wloc, uloc));
    PetscCall(VecAXPY(floc, 1.0, wloc));
  }
  PetscCall(DMRestoreLocalVector(dm, &wloc));
  PetscCall(VecZeroEntries(r));
  PetscCall(DMLocalToGlobal(dm, floc, ADD_VALUES, r));
  PetscCall(DMRestoreLocalVector(dm, &floc));
  PetscCall(DMRestoreLocalVector(dm, &uloc));
  PetscCall(SSStarHeldDiagonal(scene, u, r, PETSC_FALSE)); /* the prescribed rows: diag(K) u, whatever was added there */
  PetscCall(VecAXPY(r, -1.0, load));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ok, 1, MPIU_BOOL, MPI_LAND, scene->comm));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
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
  PetscCall(SSStarCellMaterials(scene, cStart, cEnd, NULL, NULL, rho));
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

PetscErrorCode SSStarAssembleElasticity(SSStarScene scene, PetscReal t, Mat *K, Vec *b)
{
  DM dm = scene->dm;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscCall(AssembleStiffness(scene, K));
  PetscCall(SSStarSetRigidBodyModes(scene, NULL, *K));
  if (scene->nDisplacements) { /* the load of a prescribed component: diag(K) g */
    PetscCall(VecDestroy(&scene->diagK));
    PetscCall(MatCreateVecs(*K, &scene->diagK, NULL));
    PetscCall(MatGetDiagonal(*K, scene->diagK));
  }

  PetscCall(DMCreateGlobalVector(dm, b));
  PetscCall(PetscObjectSetName((PetscObject)*b, "load"));
  PetscCall(SSStarAssembleLoad(scene, t, *b));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
   The resultants of the external load Floc (local) on the dofs that are not held and on each held group's, recorded
   for the reactions and the load's resultant (reactions.c): each rank's entries, summed over the ranks (a cell or a
   face is on one rank)
*/
static PetscErrorCode RecordLoad(SSStarScene scene, Vec Floc)
{
  const PetscInt     nheld = scene->nDirichlet + scene->nDisplacements;
  PetscSection       sec;
  PetscInt           vStart, vEnd;
  const PetscScalar *fa;
  PetscReal         *sums;

  PetscFunctionBegin;
  PetscCall(PetscCalloc1(3 * nheld + 3, &sums)); /* the free dofs', then each held group's */
  PetscCall(DMGetLocalSection(scene->dm, &sec));
  PetscCall(DMPlexGetDepthStratum(scene->dm, 0, &vStart, &vEnd));
  PetscCall(VecGetArrayRead(Floc, &fa));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off;

    PetscCall(PetscSectionGetOffset(sec, v, &off));
    for (PetscInt k = 0; k < 3; k++) sums[3 * (scene->heldBy[3 * (v - vStart) + k] + 1) + k] += PetscRealPart(fa[off + k]);
  }
  PetscCall(VecRestoreArrayRead(Floc, &fa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 3 * nheld + 3, MPIU_REAL, MPIU_SUM, scene->comm));
  PetscCall(PetscArraycpy(scene->loadFree, sums, 3));
  PetscCall(PetscFree(scene->loadHeld));
  PetscCall(PetscMalloc1(3 * nheld + 1, &scene->loadHeld));
  PetscCall(PetscArraycpy(scene->loadHeld, sums + 3, 3 * nheld));
  PetscCall(PetscFree(sums));
  PetscFunctionReturn(0);
}

/*
   The load b at the time t of the histories: the tractions and gravity evaluated at t (a surface and a volume loop),
   with the prescribed displacements at t: b - K_{:,D} g on the dofs not held, diag(K) g on the prescribed ones
   (docs/derivation.md section 15); a hyperelastic scene has no lifting, its residual takes u_D as it is (18.2)
*/
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
  PetscCall(RecordLoad(scene, Floc));
  if (scene->nDisplacements) {
    PetscReal  *values;
    SSStarCells cells;
    Vec         gloc, g;

    PetscCall(PetscMalloc1(3 * (scene->nDirichlet + scene->nDisplacements), &values));
    PetscCall(SSStarHeldValues(scene, t, values));
    PetscCall(DMGetLocalVector(dm, &gloc));
    PetscCall(SSStarHeldLocalValues(scene, values, gloc));
    if (scene->affine) { /* a hyperelastic scene's residual takes u_D = g as it is: no lifting (18.2) */
      PetscCall(SSStarCellsBegin(scene, &cells));
      PetscCall(SSStarHeldLift(scene, &cells, gloc, Floc));
      PetscCall(SSStarCellsEnd(&cells));
    }
    PetscCall(VecZeroEntries(b));
    PetscCall(DMLocalToGlobal(dm, Floc, ADD_VALUES, b));
    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(DMLocalToGlobal(dm, gloc, INSERT_VALUES, g));
    PetscCall(SSStarHeldDiagonal(scene, g, b, PETSC_FALSE)); /* diag(K) g at the prescribed components */
    PetscCall(DMRestoreGlobalVector(dm, &g));
    PetscCall(DMRestoreLocalVector(dm, &gloc));
    PetscCall(PetscFree(values));
  } else {
    PetscCall(VecZeroEntries(b));
    PetscCall(DMLocalToGlobal(dm, Floc, ADD_VALUES, b));
  }
  PetscCall(DMRestoreLocalVector(dm, &Floc));
  if (!scene->lastLoad) PetscCall(VecDuplicate(b, &scene->lastLoad));
  PetscCall(VecCopy(b, scene->lastLoad));
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
