static const char help[] = "One ssstar Newton step (3p system) against the 6p system D [du; eta] = [z; z] of DERIVATION.md section 4.\n";

/* Requirement: on random SPD P, f and random starting points (nodes on the plane, off it, sliding and
   sticking), the step du = u1 - u0 taken by SNESSolve with -snes_max_it 1 equals the solution of the 6p
   system with D = [[gamma P, -H], [I, G]] built from the per-node G, H blocks, to 1e-10 relative. */
#include <ssstar.h>
#include <petscblaslapack.h>

typedef struct {
  Mat P;
  Vec f;
} Problem;

/* du of the 6p system, by LAPACK */
static PetscErrorCode SixPStep(PetscInt p, PetscReal gamma, PetscReal phi, const PetscScalar *P, const PetscReal *u, const PetscReal *c, PetscReal *du, PetscInt counts[])
{
  const PetscInt n = 3 * p, m = 6 * p;
  PetscScalar   *D, *rhs;
  PetscBLASInt   bm, one = 1, info, *piv;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc3(m * m, &D, m, &rhs, m, &piv));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt j = 0; j < n; j++) D[j * m + i] = gamma * P[j * n + i]; /* column-major */
  for (PetscInt i = 0; i < p; i++) {
    const SSStarFriction fr = {SSSTAR_FRICTION_COULOMB, phi, 0.0};
    PetscReal            z[3], d[3], b[3], gc[3] = {gamma * c[3 * i], gamma * c[3 * i + 1], gamma * c[3 * i + 2]}, G[9], H[9];
    SSStarState          st;

    SSStarApproximationStep(&fr, &u[3 * i], gc, z, d, b);
    st = SSStarClassify(&fr, d, b, 0.0, 0.0);
    counts[st]++;
    SSStarTangentBlocks(st, &fr, d, b, G, H);
    for (PetscInt r = 0; r < 3; r++) {
      rhs[3 * i + r]     = z[r];
      rhs[n + 3 * i + r] = z[r];
      D[(3 * i + r) * m + n + 3 * i + r] = 1.0; /* I block, row n+3i+r, column 3i+r */
      for (PetscInt k = 0; k < 3; k++) {
        D[(n + 3 * i + k) * m + 3 * i + r]     = -H[3 * r + k];
        D[(n + 3 * i + k) * m + n + 3 * i + r] = G[3 * r + k];
      }
    }
  }
  PetscCall(PetscBLASIntCast(m, &bm));
  PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&bm, &one, D, &bm, piv, rhs, &bm, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "6p system singular (info %d)", (int)info);
  for (PetscInt i = 0; i < n; i++) du[i] = PetscRealPart(rhs[i]);
  PetscCall(PetscFree3(D, rhs, piv));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const PetscInt  p = 12, n = 3 * p, trials = 40;
  const PetscReal gamma = 0.37;
  PetscInt        counts[SSSTAR_NUM_STATES] = {0}, failures = 0;
  PetscReal       worst = 0;
  PetscRandom     rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  for (PetscInt t = 0; t < trials; t++) {
    Problem      pb;
    Mat          B;
    Vec          u0, u1;
    SNES         snes;
    PetscScalar *Pa;
    PetscReal    u[3 * 12], c[3 * 12], du6[3 * 12], diff = 0, norm = 0, phi = t % 5 == 4 ? 0.0 : 0.1 + 0.02 * t;
    const PetscScalar *ua, *u1a;

    /* P = B^T B + n I, f random */
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &B));
    PetscCall(MatSetRandom(B, rnd));
    PetscCall(MatTransposeMatMult(B, B, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &pb.P));
    PetscCall(MatShift(pb.P, (PetscScalar)n));
    PetscCall(MatCreateVecs(pb.P, &pb.f, &u0));
    PetscCall(VecSetRandom(pb.f, rnd));
    PetscCall(VecScale(pb.f, 10.0));
    PetscCall(VecSetRandom(u0, rnd));
    PetscCall(VecGetArray(u0, (PetscScalar **)&ua));
    for (PetscInt i = 0; i < p; i++) {
      PetscScalar *a = (PetscScalar *)ua;
      if (i % 2 == 0) a[3 * i + 2] = 0.0;                             /* on the plane */
      else a[3 * i + 2] = PetscAbsScalar(a[3 * i + 2]);               /* above it     */
      if (i % 4 == 1) a[3 * i] = a[3 * i + 1] = 0.0;                  /* not slipping */
    }
    PetscCall(VecRestoreArray(u0, (PetscScalar **)&ua));
    PetscCall(VecDuplicate(u0, &u1));
    PetscCall(VecCopy(u0, u1));

    PetscCall(SNESCreate(PETSC_COMM_SELF, &snes));
    PetscCall(SNESSetType(snes, SNESSSSTAR));
    PetscCall(SNESSSStarSetFriction(snes, phi));
    PetscCall(SNESSSStarSetScaling(snes, gamma));
    PetscCall(SNESSSStarSetStateTolerance(snes, 0.0));
    PetscCall(SNESSetTolerances(snes, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1, PETSC_DEFAULT));
    PetscCall(SNESSSStarSetContactProblem(snes, pb.P, pb.f));
    PetscCall(SNESSetFromOptions(snes));
    PetscCall(SNESSolve(snes, NULL, u1));

    /* the same step in 6p form */
    PetscCall(VecGetArrayRead(u0, &ua));
    for (PetscInt i = 0; i < n; i++) u[i] = PetscRealPart(ua[i]);
    PetscCall(VecRestoreArrayRead(u0, &ua));
    {
      Vec cv;
      const PetscScalar *ca;
      PetscCall(VecDuplicate(u0, &cv));
      PetscCall(MatMult(pb.P, u0, cv));
      PetscCall(VecAXPY(cv, -1.0, pb.f));
      PetscCall(VecGetArrayRead(cv, &ca));
      for (PetscInt i = 0; i < n; i++) c[i] = PetscRealPart(ca[i]);
      PetscCall(VecRestoreArrayRead(cv, &ca));
      PetscCall(VecDestroy(&cv));
    }
    PetscCall(MatDenseGetArray(pb.P, &Pa));
    PetscCall(SixPStep(p, gamma, phi, Pa, u, c, du6, counts));
    PetscCall(MatDenseRestoreArray(pb.P, &Pa));
    PetscCall(VecGetArrayRead(u1, &u1a));
    for (PetscInt i = 0; i < n; i++) {
      PetscReal du3 = PetscRealPart(u1a[i]) - u[i];
      diff += (du3 - du6[i]) * (du3 - du6[i]);
      norm += du6[i] * du6[i];
    }
    PetscCall(VecRestoreArrayRead(u1, &u1a));
    diff = PetscSqrtReal(diff / norm);
    worst = PetscMax(worst, diff);
    if (!(diff <= 1e-10)) {
      failures++;
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "FAIL trial %" PetscInt_FMT " (phi %g): |du3p - du6p|/|du6p| = %g\n", t, (double)phi, (double)diff));
    }
    PetscCall(SNESDestroy(&snes));
    PetscCall(VecDestroy(&u0));
    PetscCall(VecDestroy(&u1));
    PetscCall(VecDestroy(&pb.f));
    PetscCall(MatDestroy(&pb.P));
    PetscCall(MatDestroy(&B));
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "states seen:"));
  for (PetscInt s = 0; s < SSSTAR_NUM_STATES; s++) PetscCall(PetscPrintf(PETSC_COMM_SELF, " %s %" PetscInt_FMT, SSStarStateNames[s], counts[s]));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "\nworst relative difference %.1e\n", (double)worst));
  if (!counts[SSSTAR_STATE_L] || !counts[SSSTAR_STATE_M1] || !counts[SSSTAR_STATE_M3P]) {
    failures++;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "FAIL: the random states do not cover L, M1 and M3+\n"));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s\n", failures ? "FAILED" : "OK"));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
