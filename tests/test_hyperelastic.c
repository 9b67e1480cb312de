static const char help[] = "The material models' kernels (src/scene/elasticity/hyperelastic.c) against hand-computed cases and finite differences.\n";

/* Requirement: for the linear, Saint Venant-Kirchhoff and neo-Hookean models, SSStarMaterialStress() is the derivative
   of SSStarMaterialEnergy() and SSStarMaterialTangent() that of the stress (central differences, relative 1e-7), the
   tangent has the major symmetry and is Hooke's at F = I; a rigid rotation of 90 degrees stresses neither hyperelastic
   model (to 1e-14) and gives the linear one its hand-computed spurious stress; a uniaxial stretch gives the
   hand-computed P, Cauchy stress and energy of each model; neo-Hookean refuses det F <= 0; a cell's internal force is
   the gradient of V W(F), its tangent the derivative of the force, and the linear model's force is
   K u with its energy eps:sigma/2 of SSStarTetStrain() and SSStarHookeStress(); the Green-Lagrange strain of a rotation is zero. */
#include <ssstarscene.h>

static int failures = 0;

static void Expect(PetscBool ok, const char what[])
{
  if (!ok) {
    failures++;
    PetscPrintf(PETSC_COMM_SELF, "FAIL %s\n", what);
  }
}

/* max |a - b| <= tol * max(scale, max |b|); NaN fails */
static PetscBool Close(PetscInt n, const PetscReal a[], const PetscReal b[], PetscReal tol, PetscReal scale)
{
  PetscReal m = scale;

  for (PetscInt i = 0; i < n; i++) m = PetscMax(m, PetscAbsReal(b[i]));
  for (PetscInt i = 0; i < n; i++)
    if (!(PetscAbsReal(a[i] - b[i]) <= tol * m)) return PETSC_FALSE;
  return PETSC_TRUE;
}

static const char *const Names[3] = {"linear", "saint_venant_kirchhoff", "neo_hookean"};

/* P against central differences of W, A against central differences of P, A's major symmetry */
static void CheckDerivatives(SSStarMaterialModel m, PetscReal lambda, PetscReal mu, const PetscReal F[9])
{
  const PetscReal h = 1e-6;
  PetscReal       P[9], A[81], Pfd[9], Afd[81], At[81];
  char            what[256];

  (void)SSStarMaterialStress(m, lambda, mu, F, P);
  (void)SSStarMaterialTangent(m, lambda, mu, F, A);
  for (PetscInt k = 0; k < 9; k++) {
    PetscReal Fp[9], Fm[9], Wp, Wm, Pp[9], Pm[9];

    for (PetscInt j = 0; j < 9; j++) Fp[j] = Fm[j] = F[j];
    Fp[k] += h;
    Fm[k] -= h;
    (void)SSStarMaterialEnergy(m, lambda, mu, Fp, &Wp);
    (void)SSStarMaterialEnergy(m, lambda, mu, Fm, &Wm);
    Pfd[k] = (Wp - Wm) / (2 * h);
    (void)SSStarMaterialStress(m, lambda, mu, Fp, Pp);
    (void)SSStarMaterialStress(m, lambda, mu, Fm, Pm);
    for (PetscInt j = 0; j < 9; j++) Afd[9 * j + k] = (Pp[j] - Pm[j]) / (2 * h);
  }
  for (PetscInt r = 0; r < 9; r++)
    for (PetscInt c = 0; c < 9; c++) At[9 * r + c] = A[9 * c + r];
  PetscSNPrintf(what, sizeof(what), "%s: P = dW/dF (central differences)", Names[m]);
  Expect(Close(9, P, Pfd, 1e-7, mu), what);
  PetscSNPrintf(what, sizeof(what), "%s: A = dP/dF (central differences)", Names[m]);
  Expect(Close(81, A, Afd, 1e-7, mu), what);
  PetscSNPrintf(what, sizeof(what), "%s: A_iJkL = A_kLiJ", Names[m]);
  Expect(Close(81, A, At, 1e-14, mu), what);
}

/* A cell's force against the gradient of V W(F(u)), its tangent against differences of the force */
static void CheckCell(SSStarMaterialModel m, PetscReal lambda, PetscReal mu, const PetscReal x[12], const PetscReal u[12])
{
  const PetscReal h = 1e-6;
  PetscReal       f[12], ffd[12], Kfd[144], Kr[144], F[9], vol;
  PetscScalar     K[144];
  char            what[256];

  (void)SSStarTetInternalForce(m, lambda, mu, x, u, f, K);
  for (PetscInt k = 0; k < 12; k++) {
    PetscReal up[12], um[12], Wp, Wm, fp[12], fm[12];

    for (PetscInt j = 0; j < 12; j++) up[j] = um[j] = u[j];
    up[k] += h;
    um[k] -= h;
    vol = SSStarTetDeformationGradient(x, up, F);
    (void)SSStarMaterialEnergy(m, lambda, mu, F, &Wp);
    (void)SSStarTetDeformationGradient(x, um, F);
    (void)SSStarMaterialEnergy(m, lambda, mu, F, &Wm);
    ffd[k] = vol * (Wp - Wm) / (2 * h);
    (void)SSStarTetInternalForce(m, lambda, mu, x, up, fp, NULL);
    (void)SSStarTetInternalForce(m, lambda, mu, x, um, fm, NULL);
    for (PetscInt j = 0; j < 12; j++) Kfd[12 * j + k] = (fp[j] - fm[j]) / (2 * h);
  }
  for (PetscInt k = 0; k < 144; k++) Kr[k] = PetscRealPart(K[k]);
  PetscSNPrintf(what, sizeof(what), "%s: a cell's force is the gradient of V W(F(u))", Names[m]);
  Expect(Close(12, f, ffd, 1e-7, mu), what);
  PetscSNPrintf(what, sizeof(what), "%s: a cell's tangent is the derivative of its force", Names[m]);
  Expect(Close(144, Kr, Kfd, 1e-7, mu), what);
}

int main(int argc, char **argv)
{
  const PetscReal E = 3, nu = 0.3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const PetscReal I9[9]   = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const PetscReal R90[9]  = {0, -1, 0, 1, 0, 0, 0, 0, 1}; /* 90 degrees about z */
  const PetscReal Fgen[9] = {1.2, 0.3, -0.1, -0.2, 0.8, 0.25, 0.15, -0.05, 1.1};
  const PetscReal skewed[12] = {1, 1, 1, 3, 1.5, 1, 1.2, 4, 0.5, 0.7, 1.3, 5};
  const PetscReal ucell[12]  = {0.1, -0.2, 0.05, 0.3, 0.1, -0.4, -0.15, 0.2, 0.3, 0.05, -0.1, 0.2};
  PetscReal       P[9], A[81], Hooke[81], W, zero[81] = {0};

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  (void)SSStarMaterialTangent(SSSTAR_MATERIAL_LINEAR, lambda, mu, I9, Hooke);
  for (PetscInt m = 0; m < 3; m++) {
    char what[256];

    CheckDerivatives((SSStarMaterialModel)m, lambda, mu, Fgen);
    CheckCell((SSStarMaterialModel)m, lambda, mu, skewed, ucell);
    (void)SSStarMaterialStress((SSStarMaterialModel)m, lambda, mu, I9, P);
    (void)SSStarMaterialTangent((SSStarMaterialModel)m, lambda, mu, I9, A);
    PetscSNPrintf(what, sizeof(what), "%s: no stress at F = I, and Hooke's tangent", Names[m]);
    Expect(Close(9, P, zero, 1e-15, mu) && Close(81, A, Hooke, 1e-15, mu), what);
  }
  { /* Hooke's tangent by hand: A_xxxx = lambda + 2 mu, A_xxyy = lambda, A_xyxy = A_xyyx = mu */
    const PetscReal hand[4] = {lambda + 2 * mu, lambda, mu, mu}, got[4] = {Hooke[0], Hooke[4], Hooke[9 * 1 + 1], Hooke[9 * 1 + 3]};

    Expect(Close(4, got, hand, 1e-15, mu), "Hooke's tangent: lambda + 2 mu, lambda, mu, mu");
  }
  { /* a rigid rotation of 90 degrees about z */
    const PetscReal spurious[9] = {-2 * lambda - 2 * mu, 0, 0, 0, -2 * lambda - 2 * mu, 0, 0, 0, -2 * lambda}; /* eps = diag(-1, -1, 0) */
    PetscReal       El[6];

    for (PetscInt m = 1; m < 3; m++) {
      (void)SSStarMaterialStress((SSStarMaterialModel)m, lambda, mu, R90, P);
      (void)SSStarMaterialEnergy((SSStarMaterialModel)m, lambda, mu, R90, &W);
      Expect(Close(9, P, zero, 1e-14, mu) && PetscAbsReal(W) < 1e-14 * mu, m == 1 ? "saint_venant_kirchhoff: a rotation of 90 degrees stresses nothing" : "neo_hookean: a rotation of 90 degrees stresses nothing");
    }
    (void)SSStarMaterialStress(SSSTAR_MATERIAL_LINEAR, lambda, mu, R90, P);
    Expect(Close(9, P, spurious, 1e-15, mu), "linear: a rotation of 90 degrees gives the spurious stress of eps = diag(-1, -1, 0)");
    SSStarGreenLagrangeStrain(R90, El);
    Expect(Close(6, El, zero, 1e-15, 1), "the Green-Lagrange strain of a rotation is zero");
  }
  { /* a uniaxial stretch F = diag(a, b, b), by hand */
    const PetscReal a = 0.7, b = 1.1, J = a * b * b, F[9] = {a, 0, 0, 0, b, 0, 0, 0, b};
    const PetscReal E11 = (a * a - 1) / 2, E22 = (b * b - 1) / 2;
    const PetscReal svk[3] = {a * (lambda * (E11 + 2 * E22) + 2 * mu * E11), b * (lambda * (E11 + 2 * E22) + 2 * mu * E22), 0.5 * lambda * PetscSqr(E11 + 2 * E22) + mu * (E11 * E11 + 2 * E22 * E22)};
    const PetscReal nh[3]  = {mu * (a - 1 / a) + lambda * PetscLogReal(J) / a, mu * (b - 1 / b) + lambda * PetscLogReal(J) / b, 0.5 * mu * (a * a + 2 * b * b - 3) - mu * PetscLogReal(J) + 0.5 * lambda * PetscSqr(PetscLogReal(J))};
    const PetscReal *hand[2] = {svk, nh};

    for (PetscInt m = 1; m < 3; m++) {
      PetscReal got[3], sigma[6], s_hand[6];

      (void)SSStarMaterialStress((SSStarMaterialModel)m, lambda, mu, F, P);
      (void)SSStarMaterialEnergy((SSStarMaterialModel)m, lambda, mu, F, &W);
      got[0] = P[0];
      got[1] = P[4];
      got[2] = W;
      Expect(Close(3, got, hand[m - 1], 1e-14, mu) && P[8] == P[4] && P[1] == 0 && P[5] == 0, m == 1 ? "saint_venant_kirchhoff: the hand-computed uniaxial stretch" : "neo_hookean: the hand-computed uniaxial stretch");
      SSStarCauchyStress(F, P, sigma);
      s_hand[0] = P[0] * a / J;
      s_hand[1] = s_hand[2] = P[4] * b / J;
      s_hand[3] = s_hand[4] = s_hand[5] = 0;
      Expect(Close(6, sigma, s_hand, 1e-14, mu), "the Cauchy stress of a stretch: sigma_ii = P_ii F_ii / J");
    }
  }
  { /* the Cauchy stress is objective: F -> R F rotates it, sigma -> R sigma R^T */
    PetscReal RF[9], P1[9], P2[9], s1[6], s2[6], S1[9], rot[9], s2full[9];

    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) RF[3 * i + j] = R90[3 * i] * Fgen[j] + R90[3 * i + 1] * Fgen[3 + j] + R90[3 * i + 2] * Fgen[6 + j];
    (void)SSStarMaterialStress(SSSTAR_MATERIAL_NEO_HOOKEAN, lambda, mu, Fgen, P1);
    (void)SSStarMaterialStress(SSSTAR_MATERIAL_NEO_HOOKEAN, lambda, mu, RF, P2);
    SSStarCauchyStress(Fgen, P1, s1);
    SSStarCauchyStress(RF, P2, s2);
    {
      const PetscInt ij[9] = {0, 5, 4, 5, 1, 3, 4, 3, 2}; /* the full matrix of xx, yy, zz, yz, xz, xy */

      for (PetscInt k = 0; k < 9; k++) {
        S1[k]     = s1[ij[k]];
        s2full[k] = s2[ij[k]];
      }
    }
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) {
        rot[3 * i + j] = 0;
        for (PetscInt k = 0; k < 3; k++)
          for (PetscInt l = 0; l < 3; l++) rot[3 * i + j] += R90[3 * i + k] * S1[3 * k + l] * R90[3 * j + l];
      }
    Expect(Close(9, s2full, rot, 1e-14, mu), "neo_hookean: the Cauchy stress of R F is R sigma R^T");
  }
  { /* neo-Hookean is not defined for det F <= 0 */
    const PetscReal inverted[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};

    Expect((PetscBool)(!SSStarMaterialStress(SSSTAR_MATERIAL_NEO_HOOKEAN, lambda, mu, inverted, P) && !SSStarMaterialEnergy(SSSTAR_MATERIAL_NEO_HOOKEAN, lambda, mu, inverted, &W) && !SSStarMaterialTangent(SSSTAR_MATERIAL_NEO_HOOKEAN, lambda, mu, inverted, A)), "neo_hookean refuses det F <= 0");
    Expect(SSStarMaterialStress(SSSTAR_MATERIAL_SAINT_VENANT_KIRCHHOFF, lambda, mu, inverted, P), "saint_venant_kirchhoff is defined for any F");
  }
  { /* the linear model: its cell force is K u with its tangent K, its energy eps:sigma/2 of SSStarTetStrain(), SSStarHookeStress() */
    PetscScalar K[144];
    PetscReal   f[12], Ku[12], F[9], eps[6], sigma[6], half = 0, vol;

    (void)SSStarTetInternalForce(SSSTAR_MATERIAL_LINEAR, lambda, mu, skewed, ucell, f, K);
    for (PetscInt i = 0; i < 12; i++) {
      Ku[i] = 0;
      for (PetscInt j = 0; j < 12; j++) Ku[i] += PetscRealPart(K[12 * i + j]) * ucell[j];
    }
    Expect(Close(12, f, Ku, 1e-14, mu), "linear: a cell's force is K u, K its tangent");
    vol = SSStarTetDeformationGradient(skewed, ucell, F);
    (void)SSStarMaterialEnergy(SSSTAR_MATERIAL_LINEAR, lambda, mu, F, &W);
    Expect(PetscAbsReal(vol - SSStarTetStrain(skewed, ucell, eps)) < 1e-15, "the deformation gradient's volume is the strain's");
    SSStarHookeStress(lambda, mu, eps, sigma);
    for (PetscInt k = 0; k < 6; k++) half += 0.5 * (k < 3 ? 1 : 2) * eps[k] * sigma[k];
    Expect(PetscAbsReal(W - half) <= 1e-14 * PetscAbsReal(half), "linear: W = eps:sigma/2 of SSStarTetStrain() and SSStarHookeStress()");
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_hyperelastic passed: %d failures\n", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
