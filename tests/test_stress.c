static const char help[] = "The P1 tetrahedron's strain, Hooke's stress and the von Mises stress against hand-computed cases.\n";

/* Requirement: SSStarTetStrain() gives the symmetric part of A for the linear displacement u = A x + c on the unit
   tetrahedron and on a distorted one (and its volume), zero for a small rotation with a translation; SSStarHookeStress()
   gives E on the axis and 0 across it for the uniaxial strain (1, -nu, -nu) and 2 mu eps for a shear; SSStarVonMises()
   gives |s| for a uniaxial stress, sqrt(3) |tau| for a pure shear, 0 for a hydrostatic one and sqrt(234) for
   (1, 2, 3, 4, 5, 6). Tolerance 1e-14 absolute (displacements and stresses O(1)). */
#include <ssstarscene.h>

static int failures = 0;

static void Expect(PetscBool ok, const char what[])
{
  if (!ok) {
    failures++;
    PetscPrintf(PETSC_COMM_SELF, "FAIL %s\n", what);
  }
}

static PetscBool Close(PetscInt n, const PetscReal a[], const PetscReal b[], PetscReal scale)
{
  for (PetscInt i = 0; i < n; i++)
    if (!(PetscAbsReal(a[i] - b[i]) <= 1e-14 * scale)) return PETSC_FALSE; /* NaN fails */
  return PETSC_TRUE;
}

/* u = A x + c at the four vertices x */
static void Linear(const PetscReal x[12], const PetscReal A[9], const PetscReal c[3], PetscReal u[12])
{
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt i = 0; i < 3; i++) u[3 * a + i] = c[i] + A[3 * i] * x[3 * a] + A[3 * i + 1] * x[3 * a + 1] + A[3 * i + 2] * x[3 * a + 2];
}

int main(int argc, char **argv)
{
  const PetscReal unit[12]   = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const PetscReal skewed[12] = {1, 1, 1, 3, 1.5, 1, 1.2, 4, 0.5, 0.7, 1.3, 5};
  const PetscReal A[9]       = {1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3, 7e-3, 8e-3, 10e-3};
  const PetscReal symA[6]    = {1e-3, 5e-3, 10e-3, 7e-3, 5e-3, 3e-3}; /* xx, yy, zz, yz, xz, xy of (A + A^T)/2 */
  const PetscReal W[9]       = {0, -2e-3, 1e-3, 2e-3, 0, -3e-3, -1e-3, 3e-3, 0}; /* a small rotation: skew */
  const PetscReal c[3]       = {0.5, -0.25, 2}, zero[6] = {0, 0, 0, 0, 0, 0};
  PetscReal       u[12], eps[6], sigma[6], vol;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  Linear(unit, A, c, u);
  vol = SSStarTetStrain(unit, u, eps);
  Expect(Close(6, eps, symA, 1) && PetscAbsReal(vol - 1.0 / 6) < 1e-15, "the strain of u = A x + c on the unit tetrahedron is sym(A), its volume 1/6");
  {
    PetscReal reversed[12], ur[12]; /* the vertices in another order: the same strain and volume */

    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt k = 0; k < 3; k++) {
        reversed[3 * a + k] = unit[3 * (3 - a) + k];
        ur[3 * a + k]       = u[3 * (3 - a) + k];
      }
    vol = SSStarTetStrain(reversed, ur, eps);
    Expect(Close(6, eps, symA, 1) && PetscAbsReal(vol - 1.0 / 6) < 1e-15, "the strain and volume do not depend on the vertices' order");
  }
  Linear(skewed, A, c, u);
  vol = SSStarTetStrain(skewed, u, eps);
  Expect(Close(6, eps, symA, 1), "the strain of u = A x + c on a distorted tetrahedron is sym(A)");
  {
    PetscReal e[3][3], det; /* its volume: |det(x1 - x0, x2 - x0, x3 - x0)| / 6 */

    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt k = 0; k < 3; k++) e[i][k] = skewed[3 * (i + 1) + k] - skewed[k];
    det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    Expect(PetscAbsReal(vol - PetscAbsReal(det) / 6) < 1e-14, "the volume of a distorted tetrahedron");
  }
  Linear(skewed, W, c, u);
  (void)SSStarTetStrain(skewed, u, eps);
  Expect(Close(6, eps, zero, 1), "a small rotation and a translation strain nothing");

  { /* Hooke: E = 2, nu = 0.25: lambda = mu = 0.8 */
    const PetscReal E = 2, nu = 0.25, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    const PetscReal uniaxial[6] = {1, -nu, -nu, 0, 0, 0}, expect[6] = {E, 0, 0, 0, 0, 0};
    const PetscReal shear[6] = {0, 0, 0, 0.1, -0.2, 0.3}, tau[6] = {0, 0, 0, 2 * mu * 0.1, -2 * mu * 0.2, 2 * mu * 0.3};

    SSStarHookeStress(lambda, mu, uniaxial, sigma);
    Expect(Close(6, sigma, expect, 1), "the uniaxial strain (1, -nu, -nu) gives the stress (E, 0, 0)");
    SSStarHookeStress(lambda, mu, shear, sigma);
    Expect(Close(6, sigma, tau, 1), "a shear strain gives 2 mu eps");
  }
  { /* von Mises */
    const PetscReal s1[6] = {-3, 0, 0, 0, 0, 0}, s2[6] = {0, 0, 0, 0, 0, 1.5}, s3[6] = {7, 7, 7, 0, 0, 0}, s4[6] = {1, 2, 3, 4, 5, 6};

    Expect(PetscAbsReal(SSStarVonMises(s1) - 3) < 1e-14, "von Mises of a uniaxial stress is |s|");
    Expect(PetscAbsReal(SSStarVonMises(s2) - PetscSqrtReal(3.0) * 1.5) < 1e-14, "von Mises of a pure shear is sqrt(3) |tau|");
    Expect(PetscAbsReal(SSStarVonMises(s3)) < 1e-14, "von Mises of a hydrostatic stress is 0");
    Expect(PetscAbsReal(SSStarVonMises(s4) - PetscSqrtReal(234.0)) < 1e-13, "von Mises of (1, 2, 3, 4, 5, 6) is sqrt(234)");
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s: %d failures\n", failures ? "FAILED" : "passed", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
