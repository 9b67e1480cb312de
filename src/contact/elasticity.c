/* P1 linear elasticity on tetrahedra: stiffness K (materials per volume group, springs) and load b (tractions, gravity). */
#include "sceneimpl.h"

/* Gradients of the four barycentric basis functions of the tetrahedron x[12]; returns its volume. */
static PetscReal TetGradients(const PetscReal x[12], PetscReal grad[4][3])
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
  PetscReal vol = TetGradients(x, g);

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
   The Lame parameters of every local cell: those of its -material_<G> group, else of -E, -nu. A cell in two material
   groups, or in none without -E and -nu, is an error naming the options.
*/
static PetscErrorCode CellMaterials(SSStarScene scene, PetscInt cStart, PetscInt cEnd, PetscReal (*lame)[2])
{
  PetscReal(*groupLame)[2];
  DMLabel    *labels;
  PetscInt    conflict[2] = {-1, -1}; /* two groups of one cell (found * nMaterials + m); a cell without material */
  PetscBool   hasGlobal   = (PetscBool)(scene->hasE && scene->hasNu);
  PetscReal   global[2]   = {0, 0};
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
    PetscInt found = -1;

    lame[c - cStart][0] = global[0];
    lame[c - cStart][1] = global[1];
    for (PetscInt m = 0; m < scene->nMaterials; m++) {
      PetscInt value;

      PetscCall(DMLabelGetValue(labels[m], c, &value));
      if (value < 0) continue;
      if (found >= 0) conflict[0] = found * scene->nMaterials + m;
      found               = m;
      lame[c - cStart][0] = groupLame[m][0];
      lame[c - cStart][1] = groupLame[m][1];
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
  PetscReal e1[3], e2[3], n[3];
  PetscInt  support;
  PetscBool triangle;

  PetscFunctionBegin;
  PetscCall(GetVertexCoordinates(dm, f, 9, x, &triangle));
  PetscCheck(triangle, PETSC_COMM_SELF, PETSC_ERR_SUP, "Face %" PetscInt_FMT " of physical group \"%s\" is not a triangle", f, group);
  PetscCall(DMPlexGetSupportSize(dm, f, &support));
  PetscCheck(support == 1, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "The triangle (%g, %g, %g), (%g, %g, %g), (%g, %g, %g) of physical group \"%s\" is not on the boundary of the body", (double)x[0], (double)x[1], (double)x[2], (double)x[3], (double)x[4], (double)x[5], (double)x[6], (double)x[7], (double)x[8], group);
  for (PetscInt k = 0; k < 3; k++) {
    e1[k] = x[3 + k] - x[k];
    e2[k] = x[6 + k] - x[k];
  }
  n[0]  = e1[1] * e2[2] - e1[2] * e2[1];
  n[1]  = e1[2] * e2[0] - e1[0] * e2[2];
  n[2]  = e1[0] * e2[1] - e1[1] * e2[0];
  *area = 0.5 * PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
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

/*
   K by COO assembly: every cell adds its 12x12 block, every face of a spring group k area/3 to the diagonal of its
   vertices' dofs (a lumped elastic support); constrained (Dirichlet) dofs have negative indices and drop out.
*/
static PetscErrorCode AssembleStiffness(SSStarScene scene, Mat *K)
{
  DM           dm = scene->dm;
  PetscSection sec, gsec;
  PetscInt     cStart, cEnd, n, N, *ci, *cj, ncoo, nspring = 0, k;
  PetscScalar *values;
  PetscReal(*lame)[2];
  IS          *springFaces;
  PetscInt    *nSpringFaces;
  Vec          global;

  PetscFunctionBegin;
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc1(cEnd - cStart, &lame));
  PetscCall(CellMaterials(scene, cStart, cEnd, lame));
  PetscCall(PetscMalloc2(scene->nSprings, &springFaces, scene->nSprings, &nSpringFaces));
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    PetscCall(GroupFaces(dm, scene->springs[s].name, &springFaces[s], &nSpringFaces[s]));
    nspring += nSpringFaces[s];
  }
  ncoo = 144 * (cEnd - cStart) + 9 * nspring;
  PetscCall(PetscMalloc3(ncoo, &ci, ncoo, &cj, ncoo, &values));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt *idx = NULL, nidx;
    PetscReal x[12];
    PetscBool tet;

    k = 144 * (c - cStart);
    PetscCall(GetVertexCoordinates(dm, c, 12, x, &tet));
    PetscCheck(tet, PETSC_COMM_SELF, PETSC_ERR_SUP, "Cell %" PetscInt_FMT " is not a linear tetrahedron", c);
    TetStiffness(x, lame[c - cStart][0], lame[c - cStart][1], &values[k]);
    PetscCall(DMPlexGetClosureIndices(dm, sec, gsec, c, PETSC_TRUE, &nidx, &idx, NULL, NULL));
    PetscCheck(nidx == 12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Cell %" PetscInt_FMT " has %" PetscInt_FMT " dofs, not 12", c, nidx);
    for (PetscInt a = 0; a < 12; a++)
      for (PetscInt b = 0; b < 12; b++) {
        ci[k + 12 * a + b] = idx[a];
        cj[k + 12 * a + b] = idx[b];
      }
    PetscCall(DMPlexRestoreClosureIndices(dm, sec, gsec, c, PETSC_TRUE, &nidx, &idx, NULL, NULL));
  }
  k = 144 * (cEnd - cStart);
  for (PetscInt s = 0; s < scene->nSprings; s++) {
    const PetscInt *faces;

    PetscCall(ISGetIndices(springFaces[s], &faces));
    for (PetscInt i = 0; i < nSpringFaces[s]; i++, k += 9) {
      PetscInt *idx = NULL, nidx;
      PetscReal x[9], area;

      PetscCall(BoundaryTriangle(dm, faces[i], scene->springs[s].name, x, &area));
      PetscCall(DMPlexGetClosureIndices(dm, sec, gsec, faces[i], PETSC_TRUE, &nidx, &idx, NULL, NULL));
      for (PetscInt a = 0; a < 9; a++) {
        ci[k + a]     = idx[a];
        cj[k + a]     = idx[a];
        values[k + a] = scene->springs[s].value[0] * area / 3.0;
      }
      PetscCall(DMPlexRestoreClosureIndices(dm, sec, gsec, faces[i], PETSC_TRUE, &nidx, &idx, NULL, NULL));
    }
    PetscCall(ISRestoreIndices(springFaces[s], &faces));
    PetscCall(ISDestroy(&springFaces[s]));
  }
  PetscCall(PetscFree2(springFaces, nSpringFaces));
  PetscCall(PetscFree(lame));
  PetscCall(DMGetGlobalVector(dm, &global));
  PetscCall(VecGetLocalSize(global, &n));
  PetscCall(VecGetSize(global, &N));
  PetscCall(DMRestoreGlobalVector(dm, &global));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)dm), K));
  PetscCall(MatSetSizes(*K, n, n, N, N));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, MATAIJ));
  PetscCall(MatSetPreallocationCOO(*K, ncoo, ci, cj));
  PetscCall(MatSetValuesCOO(*K, values, ADD_VALUES));
  PetscCall(PetscFree3(ci, cj, values));
  PetscFunctionReturn(0);
}

/* Adds the consistent load of a constant traction t on the triangles of group: area/3 t per vertex. */
PetscErrorCode SSStarAddTraction(DM dm, const char group[], const PetscReal t[3], Vec Floc)
{
  IS              faces;
  const PetscInt *f;
  PetscInt        nf;

  PetscFunctionBegin;
  PetscCall(GroupFaces(dm, group, &faces, &nf));
  PetscCall(ISGetIndices(faces, &f));
  for (PetscInt i = 0; i < nf; i++) {
    PetscScalar load[9];
    PetscReal   x[9], area;

    PetscCall(BoundaryTriangle(dm, f[i], group, x, &area));
    for (PetscInt v = 0; v < 3; v++)
      for (PetscInt k = 0; k < 3; k++) load[3 * v + k] = area / 3.0 * t[k];
    PetscCall(DMPlexVecSetClosure(dm, NULL, Floc, f[i], load, ADD_VALUES));
  }
  PetscCall(ISRestoreIndices(faces, &f));
  PetscCall(ISDestroy(&faces));
  PetscFunctionReturn(0);
}

/* Adds the consistent load of the body force rho g: vol/4 rho g per vertex of every cell. */
static PetscErrorCode AddGravity(DM dm, PetscReal rho, const PetscReal g[3], Vec Floc)
{
  PetscInt cStart, cEnd;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscScalar load[12];
    PetscReal   x[12], grad[4][3], vol;
    PetscBool   tet;

    PetscCall(GetVertexCoordinates(dm, c, 12, x, &tet));
    vol = TetGradients(x, grad);
    for (PetscInt v = 0; v < 4; v++)
      for (PetscInt k = 0; k < 3; k++) load[3 * v + k] = vol / 4.0 * rho * g[k];
    PetscCall(DMPlexVecSetClosure(dm, NULL, Floc, c, load, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

/*
   The stiffness K and load b of P1 linear elasticity with the scene's materials, springs, tractions and gravity
   (u = 0 on the Dirichlet groups is built into the dofs)
*/
/*
   The rigid-body modes of the body in the layout of K (the coordinates of its free dofs, block size 3), as K's
   near-null space: algebraic multigrid (PCGAMG) builds its coarse spaces from them, which halves its iterations on
   elasticity (the whole-body Newton step of ssstar uses it)
*/
static PetscErrorCode SetRigidBodyModes(DM dm, Mat K)
{
  DM                 cdm;
  PetscSection       sec, csec;
  Vec                cloc, xloc, x;
  PetscInt           vStart, vEnd;
  const PetscScalar *ca;
  PetscScalar       *xa;
  MatNullSpace       modes;

  PetscFunctionBegin;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetCoordinatesLocal(dm, &cloc));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetLocalVector(dm, &xloc));
  PetscCall(VecGetArrayRead(cloc, &ca));
  PetscCall(VecGetArrayWrite(xloc, &xa));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off, coff, dof;

    PetscCall(PetscSectionGetDof(sec, v, &dof));
    if (dof != 3) continue;
    PetscCall(PetscSectionGetOffset(sec, v, &off));
    PetscCall(PetscSectionGetOffset(csec, v, &coff));
    for (PetscInt k = 0; k < 3; k++) xa[off + k] = ca[coff + k];
  }
  PetscCall(VecRestoreArrayWrite(xloc, &xa));
  PetscCall(VecRestoreArrayRead(cloc, &ca));
  PetscCall(DMCreateGlobalVector(dm, &x)); /* the held dofs are not in it */
  PetscCall(DMLocalToGlobal(dm, xloc, INSERT_VALUES, x));
  PetscCall(DMRestoreLocalVector(dm, &xloc));
  PetscCall(VecSetBlockSize(x, 3));
  PetscCall(MatNullSpaceCreateRigidBody(x, &modes));
  PetscCall(MatSetNearNullSpace(K, modes));
  PetscCall(MatNullSpaceDestroy(&modes));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarAssembleElasticity(SSStarScene scene, Mat *K, Vec *b)
{
  DM  dm = scene->dm;
  Vec Floc;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscCall(AssembleStiffness(scene, K));
  PetscCall(MatSetOption(*K, MAT_SPD, PETSC_TRUE));
  PetscCall(SetRigidBodyModes(dm, *K));

  PetscCall(DMCreateGlobalVector(dm, b));
  PetscCall(PetscObjectSetName((PetscObject)*b, "load"));
  PetscCall(DMGetLocalVector(dm, &Floc));
  PetscCall(VecZeroEntries(Floc));
  for (PetscInt t = 0; t < scene->nTractions; t++) PetscCall(SSStarAddTraction(dm, scene->tractions[t].name, scene->tractions[t].value, Floc));
  if (scene->hasGravity) PetscCall(AddGravity(dm, scene->density, scene->gravity, Floc));
  PetscCall(VecZeroEntries(*b));
  PetscCall(DMLocalToGlobal(dm, Floc, ADD_VALUES, *b));
  PetscCall(DMRestoreLocalVector(dm, &Floc));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscFunctionReturn(0);
}
