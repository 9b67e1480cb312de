/*
   The material models of a P1 tetrahedron (docs/derivation.md section 18), as pure kernels on 3 x 3 matrices stored
   row by row (F_iJ = F[3 i + J]): the deformation gradient F = I + grad u of a cell, the strain energy density W(F),
   the first Piola-Kirchhoff stress P = dW/dF and its tangent A_iJkL = dP_iJ/dF_kL (A[9 (3 i + J) + 3 k + L]) of

     linear                  W = lambda/2 (tr eps)^2 + mu eps:eps,  eps = sym(F - I)   (small strain: P = sigma)
     saint_venant_kirchhoff  W = lambda/2 (tr E)^2 + mu E:E,        E = (F^T F - I)/2
     neo_hookean             W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,  I1 = tr(F^T F), J = det F

   the Cauchy stress sigma = P F^T / J and the Green-Lagrange strain; and a cell's internal force and tangent
   stiffness f_ai = V sum_J P_iJ g_aJ, K_ai,bk = V sum_JL g_aJ A_iJkL g_bL (V the reference volume, g_a the gradients
   of its barycentric functions). tests/test_hyperelastic.c checks them against hand-computed values and finite
   differences.
*/
#include "../sceneimpl.h"

const char *const SSStarMaterialModels[] = {"linear", "saint_venant_kirchhoff", "neo_hookean", "SSStarMaterialModel", "SSSTAR_MATERIAL_", NULL};

/* The model named name (of SSStarMaterialModels), or an error naming option */
PetscErrorCode SSStarMaterialModelFromName(MPI_Comm comm, const char option[], const char name[], PetscInt *model)
{
  PetscBool found = PETSC_FALSE;

  PetscFunctionBegin;
  for (PetscInt m = 0; m < 3 && !found; m++) {
    PetscCall(PetscStrcasecmp(name, SSStarMaterialModels[m], &found));
    if (found) *model = m;
  }
  PetscCheck(found, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option %s %s: unknown material model; give linear, saint_venant_kirchhoff or neo_hookean", option, name);
  PetscFunctionReturn(0);
}

/* The determinant of a 3 x 3 matrix (rows) and, if inv is not NULL and it is not zero, the inverse */
static PetscReal Inverse3(const PetscReal A[9], PetscReal inv[9])
{
  const PetscReal c00 = A[4] * A[8] - A[5] * A[7], c01 = A[5] * A[6] - A[3] * A[8], c02 = A[3] * A[7] - A[4] * A[6];
  const PetscReal det = A[0] * c00 + A[1] * c01 + A[2] * c02;

  if (inv && det != 0) {
    inv[0] = c00 / det;
    inv[1] = (A[2] * A[7] - A[1] * A[8]) / det;
    inv[2] = (A[1] * A[5] - A[2] * A[4]) / det;
    inv[3] = c01 / det;
    inv[4] = (A[0] * A[8] - A[2] * A[6]) / det;
    inv[5] = (A[2] * A[3] - A[0] * A[5]) / det;
    inv[6] = c02 / det;
    inv[7] = (A[1] * A[6] - A[0] * A[7]) / det;
    inv[8] = (A[0] * A[4] - A[1] * A[3]) / det;
  }
  return det;
}

/* The determinant of a 3 x 3 matrix (J = det F of a deformation gradient) */
PetscReal SSStarDeterminant3(const PetscReal A[9])
{
  return Inverse3(A, NULL);
}

/* The strain of the model: eps = sym(F - I) (linear) or E = (F^T F - I)/2, as a full symmetric 3 x 3 matrix */
static void ModelStrain(SSStarMaterialModel model, const PetscReal F[9], PetscReal e[9])
{
  for (PetscInt m = 0; m < 3; m++)
    for (PetscInt J = 0; J < 3; J++) {
      if (model == SSSTAR_MATERIAL_LINEAR) e[3 * m + J] = 0.5 * (F[3 * m + J] + F[3 * J + m]) - (m == J ? 1.0 : 0.0);
      else {
        PetscReal c = 0;

        for (PetscInt k = 0; k < 3; k++) c += F[3 * k + m] * F[3 * k + J];
        e[3 * m + J] = 0.5 * (c - (m == J ? 1.0 : 0.0));
      }
    }
}

/*@C
   SSStarTetDeformationGradient - the deformation gradient of a P1 tetrahedron (constant in it): F = I + grad u,
   F_iJ = delta_iJ + sum_a u_a,i dlambda_a/dX_J

   Not Collective

   Input Parameters:
+  x - the reference coordinates of its four vertices, 3 per vertex
-  u - their displacements, 3 per vertex

   Output Parameter:
.  F - the deformation gradient, row by row (F[3 i + J])

   Returns:
   the reference volume of the tetrahedron

   Level: advanced

.seealso: `SSStarMaterialStress()`, `SSStarTetStrain()`
@*/
PetscReal SSStarTetDeformationGradient(const PetscReal x[12], const PetscReal u[12], PetscReal F[9])
{
  PetscReal g[4][3];
  PetscReal vol = SSStarTetGradients(x, g);

  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt J = 0; J < 3; J++) {
      F[3 * i + J] = i == J ? 1.0 : 0.0;
      for (PetscInt a = 0; a < 4; a++) F[3 * i + J] += u[3 * a + i] * g[a][J];
    }
  return vol;
}

/*@C
   SSStarMaterialEnergy - the strain energy density W(F) of a material model (per unit reference volume)

   Not Collective

   Input Parameters:
+  model  - SSSTAR_MATERIAL_LINEAR, SSSTAR_MATERIAL_SAINT_VENANT_KIRCHHOFF or SSSTAR_MATERIAL_NEO_HOOKEAN
.  lambda - the first Lame parameter
.  mu     - the shear modulus
-  F      - the deformation gradient, row by row

   Output Parameter:
.  W - the energy density

   Returns:
   PETSC_FALSE where the model is not defined (neo_hookean with J = det F <= 0: W is infinite), else PETSC_TRUE

   Level: advanced

.seealso: `SSStarMaterialStress()`, `SSStarMaterialTangent()`
@*/
PetscBool SSStarMaterialEnergy(SSStarMaterialModel model, PetscReal lambda, PetscReal mu, const PetscReal F[9], PetscReal *W)
{
  PetscReal e[9], tr, ee = 0;

  if (model == SSSTAR_MATERIAL_NEO_HOOKEAN) {
    const PetscReal J = Inverse3(F, NULL);
    PetscReal       I1 = 0, lnJ;

    *W = PETSC_INFINITY;
    if (!(J > 0)) return PETSC_FALSE;
    lnJ = PetscLogReal(J);
    for (PetscInt k = 0; k < 9; k++) I1 += F[k] * F[k];
    *W = 0.5 * mu * (I1 - 3) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
    return PETSC_TRUE;
  }
  ModelStrain(model, F, e);
  tr = e[0] + e[4] + e[8];
  for (PetscInt k = 0; k < 9; k++) ee += e[k] * e[k];
  *W = 0.5 * lambda * tr * tr + mu * ee;
  return PETSC_TRUE;
}

/*@C
   SSStarMaterialStress - the first Piola-Kirchhoff stress P = dW/dF of a material model: sigma(eps) (linear),
   F S with S = lambda tr(E) I + 2 mu E (saint_venant_kirchhoff), mu (F - F^-T) + lambda ln(J) F^-T (neo_hookean)

   Not Collective

   Input Parameters:
+  model  - the material model
.  lambda - the first Lame parameter
.  mu     - the shear modulus
-  F      - the deformation gradient, row by row

   Output Parameter:
.  P - the first Piola-Kirchhoff stress, row by row (P[3 i + J]: force in direction i per unit reference area of normal J)

   Returns:
   PETSC_FALSE where the model is not defined (neo_hookean with det F <= 0; P is then set to NaN), else PETSC_TRUE

   Level: advanced

.seealso: `SSStarMaterialEnergy()`, `SSStarMaterialTangent()`, `SSStarCauchyStress()`
@*/
PetscBool SSStarMaterialStress(SSStarMaterialModel model, PetscReal lambda, PetscReal mu, const PetscReal F[9], PetscReal P[9])
{
  PetscReal e[9], S[9], tr;

  if (model == SSSTAR_MATERIAL_NEO_HOOKEAN) {
    PetscReal       Fi[9];
    const PetscReal J = Inverse3(F, Fi);

    if (!(J > 0)) {
      for (PetscInt k = 0; k < 9; k++) P[k] = (PetscReal)NAN;
      return PETSC_FALSE;
    }
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt m = 0; m < 3; m++) P[3 * i + m] = mu * (F[3 * i + m] - Fi[3 * m + i]) + lambda * PetscLogReal(J) * Fi[3 * m + i];
    return PETSC_TRUE;
  }
  ModelStrain(model, F, e);
  tr = e[0] + e[4] + e[8];
  for (PetscInt k = 0; k < 9; k++) S[k] = 2 * mu * e[k] + (k % 4 == 0 ? lambda * tr : 0.0);
  if (model == SSSTAR_MATERIAL_LINEAR) {
    for (PetscInt k = 0; k < 9; k++) P[k] = S[k];
    return PETSC_TRUE;
  }
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt J = 0; J < 3; J++) {
      P[3 * i + J] = 0;
      for (PetscInt K = 0; K < 3; K++) P[3 * i + J] += F[3 * i + K] * S[3 * K + J];
    }
  return PETSC_TRUE;
}

/*@C
   SSStarMaterialTangent - the tangent A_iJkL = dP_iJ/dF_kL of a material model (docs/derivation.md (18.4))

   Not Collective

   Input Parameters:
+  model  - the material model
.  lambda - the first Lame parameter
.  mu     - the shear modulus
-  F      - the deformation gradient, row by row

   Output Parameter:
.  A - the tangent, A[9 (3 i + J) + 3 k + L]; it has the major symmetry A_iJkL = A_kLiJ (W is a potential)

   Returns:
   PETSC_FALSE where the model is not defined (neo_hookean with det F <= 0), else PETSC_TRUE

   Notes:
   linear: lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk) (Hooke's, whatever F); saint_venant_kirchhoff:
   d_ik S_JL + lambda F_iJ F_kL + mu (F F^T)_ik d_JL + mu F_iL F_kJ; neo_hookean: mu d_ik d_JL
   + (mu - lambda ln J) G_Jk G_Li + lambda G_Ji G_Lk with G = F^-1. At F = I all three are Hooke's.

   Level: advanced

.seealso: `SSStarMaterialStress()`
@*/
PetscBool SSStarMaterialTangent(SSStarMaterialModel model, PetscReal lambda, PetscReal mu, const PetscReal F[9], PetscReal A[81])
{
  PetscReal G[9], S[9], FFt[9], e[9], tr, J = 1;

  if (model == SSSTAR_MATERIAL_NEO_HOOKEAN) {
    J = Inverse3(F, G);
    if (!(J > 0)) {
      for (PetscInt k = 0; k < 81; k++) A[k] = (PetscReal)NAN;
      return PETSC_FALSE;
    }
  } else if (model == SSSTAR_MATERIAL_SAINT_VENANT_KIRCHHOFF) {
    ModelStrain(model, F, e);
    tr = e[0] + e[4] + e[8];
    for (PetscInt k = 0; k < 9; k++) S[k] = 2 * mu * e[k] + (k % 4 == 0 ? lambda * tr : 0.0);
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt k = 0; k < 3; k++) FFt[3 * i + k] = F[3 * i] * F[3 * k] + F[3 * i + 1] * F[3 * k + 1] + F[3 * i + 2] * F[3 * k + 2];
  }
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt m = 0; m < 3; m++)
      for (PetscInt k = 0; k < 3; k++)
        for (PetscInt L = 0; L < 3; L++) {
          const PetscReal dik = i == k ? 1.0 : 0.0, dmL = m == L ? 1.0 : 0.0, dim = i == m ? 1.0 : 0.0, dkL = k == L ? 1.0 : 0.0, diL = i == L ? 1.0 : 0.0, dmk = m == k ? 1.0 : 0.0;
          PetscReal       a;

          switch (model) {
          case SSSTAR_MATERIAL_SAINT_VENANT_KIRCHHOFF:
            a = dik * S[3 * m + L] + lambda * F[3 * i + m] * F[3 * k + L] + mu * FFt[3 * i + k] * dmL + mu * F[3 * i + L] * F[3 * k + m];
            break;
          case SSSTAR_MATERIAL_NEO_HOOKEAN:
            a = mu * dik * dmL + (mu - lambda * PetscLogReal(J)) * G[3 * m + k] * G[3 * L + i] + lambda * G[3 * m + i] * G[3 * L + k];
            break;
          default:
            a = lambda * dim * dkL + mu * (dik * dmL + diL * dmk);
          }
          A[9 * (3 * i + m) + 3 * k + L] = a;
        }
  return PETSC_TRUE;
}

/*@C
   SSStarCauchyStress - the Cauchy (true) stress of a first Piola-Kirchhoff stress: sigma = P F^T / det F, in the
   current configuration

   Not Collective

   Input Parameters:
+  F - the deformation gradient, row by row
-  P - the first Piola-Kirchhoff stress, row by row

   Output Parameter:
.  sigma - xx, yy, zz, yz, xz, xy (for a hyperelastic P, P F^T is symmetric; its symmetric part is taken)

   Level: advanced

.seealso: `SSStarMaterialStress()`, `SSStarVonMises()`
@*/
void SSStarCauchyStress(const PetscReal F[9], const PetscReal P[9], PetscReal sigma[6])
{
  const PetscInt  ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  const PetscReal J        = Inverse3(F, NULL);

  for (PetscInt c = 0; c < 6; c++) {
    const PetscInt i = ij[c][0], j = ij[c][1];
    PetscReal      s = 0;

    for (PetscInt K = 0; K < 3; K++) s += 0.5 * (P[3 * i + K] * F[3 * j + K] + P[3 * j + K] * F[3 * i + K]);
    sigma[c] = s / J;
  }
}

/*@C
   SSStarGreenLagrangeStrain - the Green-Lagrange strain E = (F^T F - I)/2 of a deformation gradient (the reference
   configuration's; eps = sym(F - I) to first order)

   Not Collective

   Input Parameter:
.  F - the deformation gradient, row by row

   Output Parameter:
.  E - xx, yy, zz, yz, xz, xy (tensor components)

   Level: advanced

.seealso: `SSStarTetDeformationGradient()`, `SSStarTetStrain()`
@*/
void SSStarGreenLagrangeStrain(const PetscReal F[9], PetscReal E[6])
{
  const PetscInt ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  PetscReal      e[9];

  ModelStrain(SSSTAR_MATERIAL_SAINT_VENANT_KIRCHHOFF, F, e);
  for (PetscInt c = 0; c < 6; c++) E[c] = e[3 * ij[c][0] + ij[c][1]];
}

/*@C
   SSStarTetInternalForce - the internal force of a P1 tetrahedron of a material model and, optionally, its tangent
   stiffness: f_ai = V sum_J P_iJ dlambda_a/dX_J and K_ai,bk = V sum_JL dlambda_a/dX_J A_iJkL dlambda_b/dX_L
   (docs/derivation.md (18.2), (18.3))

   Not Collective

   Input Parameters:
+  model  - the material model
.  lambda - the first Lame parameter
.  mu     - the shear modulus
.  x      - the reference coordinates of its four vertices, 3 per vertex
-  u      - their displacements, 3 per vertex

   Output Parameters:
+  f - the internal force at its vertices, 3 per vertex (dPi/du for the energy V W(F))
-  K - the 12 x 12 tangent stiffness df/du, row by row, or NULL

   Returns:
   PETSC_FALSE where the model is not defined (neo_hookean with det F <= 0), else PETSC_TRUE

   Notes:
   For the linear model f = K u and K is SSStarTetStiffness()'s matrix.

   Level: advanced

.seealso: `SSStarMaterialStress()`, `SSStarMaterialTangent()`
@*/
PetscBool SSStarTetInternalForce(SSStarMaterialModel model, PetscReal lambda, PetscReal mu, const PetscReal x[12], const PetscReal u[12], PetscReal f[12], PetscScalar K[144])
{
  PetscReal g[4][3], F[9], P[9], A[81], vol;
  PetscBool ok;

  vol = SSStarTetGradients(x, g);
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt J = 0; J < 3; J++) {
      F[3 * i + J] = i == J ? 1.0 : 0.0;
      for (PetscInt a = 0; a < 4; a++) F[3 * i + J] += u[3 * a + i] * g[a][J];
    }
  ok = SSStarMaterialStress(model, lambda, mu, F, P);
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt i = 0; i < 3; i++) f[3 * a + i] = vol * (P[3 * i] * g[a][0] + P[3 * i + 1] * g[a][1] + P[3 * i + 2] * g[a][2]);
  if (!K) return ok;
  ok = (PetscBool)(SSStarMaterialTangent(model, lambda, mu, F, A) && ok);
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt k = 0; k < 3; k++) {
      PetscReal Ag[3][4]; /* sum_L A_iJkL g_bL, per J and b */

      for (PetscInt J = 0; J < 3; J++)
        for (PetscInt b = 0; b < 4; b++) Ag[J][b] = A[9 * (3 * i + J) + 3 * k] * g[b][0] + A[9 * (3 * i + J) + 3 * k + 1] * g[b][1] + A[9 * (3 * i + J) + 3 * k + 2] * g[b][2];
      for (PetscInt a = 0; a < 4; a++)
        for (PetscInt b = 0; b < 4; b++) K[(3 * a + i) * 12 + 3 * b + k] = vol * (g[a][0] * Ag[0][b] + g[a][1] * Ag[1][b] + g[a][2] * Ag[2][b]);
    }
  return ok;
}
