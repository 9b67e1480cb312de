/* P1 linear elasticity on tetrahedra: stiffness K and load F from constant tractions. */
#include <ssstarcontact.h>

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

/* K by COO assembly: every cell adds its 12x12 block; constrained (Dirichlet) dofs have negative indices and drop out. */
static PetscErrorCode AssembleStiffness(DM dm, PetscReal lambda, PetscReal mu, Mat *K)
{
  PetscSection sec, gsec;
  PetscInt     cStart, cEnd, n, N, *ci, *cj;
  PetscScalar *values;
  Vec          global;

  PetscFunctionBegin;
  PetscCall(DMGetLocalSection(dm, &sec));
  PetscCall(DMGetGlobalSection(dm, &gsec));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(PetscMalloc3(144 * (cEnd - cStart), &ci, 144 * (cEnd - cStart), &cj, 144 * (cEnd - cStart), &values));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscInt *idx = NULL, nidx, k = 144 * (c - cStart);
    PetscReal x[12];
    PetscBool tet;

    PetscCall(GetVertexCoordinates(dm, c, 12, x, &tet));
    PetscCheck(tet, PETSC_COMM_SELF, PETSC_ERR_SUP, "Cell %" PetscInt_FMT " is not a linear tetrahedron", c);
    TetStiffness(x, lambda, mu, &values[k]);
    PetscCall(DMPlexGetClosureIndices(dm, sec, gsec, c, PETSC_TRUE, &nidx, &idx, NULL, NULL));
    PetscCheck(nidx == 12, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Cell %" PetscInt_FMT " has %" PetscInt_FMT " dofs, not 12", c, nidx);
    for (PetscInt a = 0; a < 12; a++)
      for (PetscInt b = 0; b < 12; b++) {
        ci[k + 12 * a + b] = idx[a];
        cj[k + 12 * a + b] = idx[b];
      }
    PetscCall(DMPlexRestoreClosureIndices(dm, sec, gsec, c, PETSC_TRUE, &nidx, &idx, NULL, NULL));
  }
  PetscCall(DMGetGlobalVector(dm, &global));
  PetscCall(VecGetLocalSize(global, &n));
  PetscCall(VecGetSize(global, &N));
  PetscCall(DMRestoreGlobalVector(dm, &global));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)dm), K));
  PetscCall(MatSetSizes(*K, n, n, N, N));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, MATAIJ));
  PetscCall(MatSetPreallocationCOO(*K, 144 * (cEnd - cStart), ci, cj));
  PetscCall(MatSetValuesCOO(*K, values, ADD_VALUES));
  PetscCall(PetscFree3(ci, cj, values));
  PetscFunctionReturn(0);
}

/* Adds the consistent load of a constant traction t on the triangles of group: area/3 t per vertex. */
static PetscErrorCode AddTraction(DM dm, const char group[], const PetscReal t[3], Vec Floc)
{
  DMLabel  label;
  PetscInt fStart, fEnd;

  PetscFunctionBegin;
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscScalar load[9];
    PetscReal   x[9], e1[3], e2[3], n[3], area;
    PetscInt    value, support;
    PetscBool   triangle;

    PetscCall(DMLabelGetValue(label, f, &value));
    if (value < 0) continue;
    PetscCall(DMPlexGetSupportSize(dm, f, &support));
    PetscCheck(support == 1, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Face %" PetscInt_FMT " of physical group \"%s\" is not on the boundary", f, group);
    PetscCall(GetVertexCoordinates(dm, f, 9, x, &triangle));
    PetscCheck(triangle, PETSC_COMM_SELF, PETSC_ERR_SUP, "Face %" PetscInt_FMT " of physical group \"%s\" is not a triangle", f, group);
    for (PetscInt k = 0; k < 3; k++) {
      e1[k] = x[3 + k] - x[k];
      e2[k] = x[6 + k] - x[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    area = 0.5 * PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (PetscInt v = 0; v < 3; v++)
      for (PetscInt k = 0; k < 3; k++) load[3 * v + k] = area / 3.0 * t[k];
    PetscCall(DMPlexVecSetClosure(dm, NULL, Floc, f, load, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

/*@C
   SSStarAssembleElasticity - the stiffness K and load F of P1 linear elasticity (E, nu) with the tractions of the scene
   on "top" and "right" (u = 0 on "dirichlet" is built into the dofs)
@*/
PetscErrorCode SSStarAssembleElasticity(DM dm, const SSStarScene *scene, Mat *K, Vec *F)
{
  const PetscReal lambda = scene->E * scene->nu / ((1 + scene->nu) * (1 - 2 * scene->nu));
  const PetscReal mu     = scene->E / (2 * (1 + scene->nu));
  Vec             Floc;

  PetscFunctionBegin;
  PetscCheck(scene->E > 0, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_OUTOFRANGE, "-E %g: Young's modulus must be positive", (double)scene->E);
  PetscCheck(scene->nu > -1 && scene->nu < 0.5, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_OUTOFRANGE, "-nu %g: Poisson's ratio must be in (-1, 0.5)", (double)scene->nu);
  PetscCall(PetscLogEventBegin(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscCall(AssembleStiffness(dm, lambda, mu, K));
  PetscCall(MatSetOption(*K, MAT_SPD, PETSC_TRUE));

  PetscCall(DMCreateGlobalVector(dm, F));
  PetscCall(PetscObjectSetName((PetscObject)*F, "load"));
  PetscCall(DMGetLocalVector(dm, &Floc));
  PetscCall(VecZeroEntries(Floc));
  PetscCall(AddTraction(dm, SSSTAR_GROUP_TOP, scene->traction_top, Floc));
  PetscCall(AddTraction(dm, SSSTAR_GROUP_RIGHT, scene->traction_right, Floc));
  PetscCall(VecZeroEntries(*F));
  PetscCall(DMLocalToGlobal(dm, Floc, ADD_VALUES, *F));
  PetscCall(DMRestoreLocalVector(dm, &Floc));
  PetscCall(PetscLogEventEnd(SSSTAR_Assembly, dm, 0, 0, 0));
  PetscFunctionReturn(0);
}
