/*
   The P1 tetrahedron of linear elasticity, cell by cell: its basis gradients, stiffness, strain, Hooke's stress and the
   von Mises stress (pure kernels, tests/test_kernels.c checks them on hand-computed cases), and the Lame parameters of
   every cell of a scene (its -material_<G>, else -E, -nu). Used by the assembly (elasticity.c), the prescribed
   displacements (prescribed.c), the reactions (reactions.c) and the stresses of the output (output/stress.c).
*/
#include "../sceneimpl.h"

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
void SSStarTetStiffness(const PetscReal x[12], PetscReal lambda, PetscReal mu, PetscScalar K[144])
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

/*@C
   SSStarTetStrain - the strain of a P1 tetrahedron (constant in it): eps = B u, the symmetric gradient of the linear
   displacement of its vertices (docs/derivation.md section 15)

   Not Collective

   Input Parameters:
+  x - the coordinates of its four vertices, 3 per vertex
-  u - their displacements, 3 per vertex

   Output Parameter:
.  strain - eps_xx, eps_yy, eps_zz, eps_yz, eps_xz, eps_xy (the tensor's components: eps_yz = (du_y/dz + du_z/dy)/2,
            half the engineering shear strain)

   Returns:
   the volume of the tetrahedron

   Level: advanced

.seealso: `SSStarHookeStress()`, `SSStarVonMises()`
@*/
PetscReal SSStarTetStrain(const PetscReal x[12], const PetscReal u[12], PetscReal strain[6])
{
  PetscReal g[4][3], du[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; /* du[i][j] = d u_i / d x_j */
  PetscReal vol = SSStarTetGradients(x, g);

  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) du[i][j] += u[3 * a + i] * g[a][j];
  strain[0] = du[0][0];
  strain[1] = du[1][1];
  strain[2] = du[2][2];
  strain[3] = 0.5 * (du[1][2] + du[2][1]);
  strain[4] = 0.5 * (du[0][2] + du[2][0]);
  strain[5] = 0.5 * (du[0][1] + du[1][0]);
  return vol;
}

/*@C
   SSStarHookeStress - Hooke's law of an isotropic linear elastic material: sigma = lambda tr(eps) I + 2 mu eps

   Not Collective

   Input Parameters:
+  lambda - the first Lame parameter, E nu / ((1 + nu)(1 - 2 nu))
.  mu     - the shear modulus, E / (2 (1 + nu))
-  strain - eps_xx, eps_yy, eps_zz, eps_yz, eps_xz, eps_xy (tensor components, SSStarTetStrain())

   Output Parameter:
.  stress - sigma_xx, sigma_yy, sigma_zz, sigma_yz, sigma_xz, sigma_xy

   Level: advanced

.seealso: `SSStarTetStrain()`, `SSStarVonMises()`
@*/
void SSStarHookeStress(PetscReal lambda, PetscReal mu, const PetscReal strain[6], PetscReal stress[6])
{
  const PetscReal trace = strain[0] + strain[1] + strain[2];

  for (PetscInt k = 0; k < 6; k++) stress[k] = 2 * mu * strain[k] + (k < 3 ? lambda * trace : 0.0);
}

/*@C
   SSStarVonMises - the von Mises equivalent stress sqrt(3 J2) of a stress: sqrt(((sxx - syy)^2 + (syy - szz)^2 +
   (szz - sxx)^2)/2 + 3 (syz^2 + sxz^2 + sxy^2))

   Not Collective

   Input Parameter:
.  stress - sigma_xx, sigma_yy, sigma_zz, sigma_yz, sigma_xz, sigma_xy

   Returns:
   the von Mises stress (|sigma| for a uniaxial stress, sqrt(3) |tau| for a pure shear)

   Level: advanced

.seealso: `SSStarHookeStress()`
@*/
PetscReal SSStarVonMises(const PetscReal stress[6])
{
  const PetscReal *s = stress, d = PetscSqr(s[0] - s[1]) + PetscSqr(s[1] - s[2]) + PetscSqr(s[2] - s[0]);

  return PetscSqrtReal(0.5 * d + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
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
PetscErrorCode SSStarCellMaterials(SSStarScene scene, PetscInt cStart, PetscInt cEnd, PetscReal (*lame)[2])
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

/*
   A walk over the local cells with what the kernels need: the vertices of each (numbered from vStart), the cell's Lame
   parameters, and (SSStarCellsGet()) the coordinates of its vertices
*/
PetscErrorCode SSStarCellsBegin(SSStarScene scene, SSStarCells *cells)
{
  DM       dm = scene->dm, cdm;
  PetscInt n;

  PetscFunctionBegin;
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cells->cStart, &cells->cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &cells->vStart, &cells->vEnd));
  n = cells->cEnd - cells->cStart;
  PetscCall(PetscMalloc2(4 * n + 1, &cells->vertices, n + 1, &cells->lame));
  PetscCall(SSStarCellMaterials(scene, cells->cStart, cells->cEnd, cells->lame));
  for (PetscInt c = 0; c < n; c++) {
    PetscInt *v = &cells->vertices[4 * c];

    PetscCall(SSStarMeshCellVertices(dm, cells->cStart + c, v));
    for (PetscInt a = 0; a < 4; a++) v[a] -= cells->vStart;
  }
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &cells->csec));
  PetscCall(DMGetCoordinatesLocal(dm, &cells->coordinates));
  PetscCall(VecGetArrayRead(cells->coordinates, &cells->ca));
  PetscFunctionReturn(0);
}

/* The coordinates of the vertices of local cell c (0-based from cStart), 3 per vertex */
PetscErrorCode SSStarCellsGet(const SSStarCells *cells, PetscInt c, PetscReal x[12])
{
  PetscFunctionBeginHot;
  for (PetscInt a = 0; a < 4; a++) {
    PetscInt off;

    PetscCall(PetscSectionGetOffset(cells->csec, cells->vStart + cells->vertices[4 * c + a], &off));
    for (PetscInt k = 0; k < 3; k++) x[3 * a + k] = PetscRealPart(cells->ca[off + k]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarCellsEnd(SSStarCells *cells)
{
  PetscFunctionBegin;
  PetscCall(VecRestoreArrayRead(cells->coordinates, &cells->ca));
  PetscCall(PetscFree2(cells->vertices, cells->lame));
  PetscFunctionReturn(0);
}
