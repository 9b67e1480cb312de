static const char help[] = "The contact operator B of ssstar (docs/contact-operator.md), on two small elastic chains pressed together:\n\
body A (nodes 0..n-1, held at node 0) and body B (nodes n..2n-1, held at node 2n-1); A's last two nodes are contact\n\
points compared with B's first nodes through interpolation weights, in tilted frames, one point's rows scaled by 2.\n\
  -case <law>      law: the contact law holds at the solution, w = B u + g and K u - b = B^T lambda\n\
                   formula: the reduced operator in the points' variables is (C K^-1 C^T)^-1, symmetric (one rank)\n\
                   singular: a point's own block of B is singular (refused, naming the point)\n\
                   shared: a point's master dof is another point's own dof (refused, naming the point)\n\
  -n <6>           nodes per body\n\
  -update          declare B again at every iterate (SNESSSStarSetContactUpdate): the points' variables are taken again\n\
  -o <file>        write u (PETSc binary), to compare runs\n";

#include <ssstar.h>
#include <petscblaslapack.h>

typedef struct {
  Mat K;
  Vec b;
} Body;

/* The frame of point p: a rotation about (1, 2, 3) by 0.3 p + 0.2 (rows t1, t2, n) */
static void Frame(PetscInt p, PetscReal R[9])
{
  const PetscReal a[3] = {1 / PetscSqrtReal(14.0), 2 / PetscSqrtReal(14.0), 3 / PetscSqrtReal(14.0)}, t = 0.3 * p + 0.2;
  const PetscReal c = PetscCosReal(t), s = PetscSinReal(t);

  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt j = 0; j < 3; j++) R[3 * i + j] = (i == j ? c : 0) + (1 - c) * a[i] * a[j] + s * (i == j ? 0 : ((i + 1) % 3 == j ? -a[3 - i - j] : a[3 - i - j]));
}

/* K: springs between neighbours of each chain (stiffer along z), ground springs at the held nodes; block size 3 */
static PetscErrorCode AssembleBodies(PetscInt n, Body *body)
{
  PetscInt N = 6 * n, rstart, rend;

  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, N, N, 9, NULL, 9, NULL, &body->K));
  PetscCall(MatSetBlockSize(body->K, 3));
  PetscCall(MatGetOwnershipRange(body->K, &rstart, &rend));
  for (PetscInt node = 0; node < 2 * n; node++) {
    for (PetscInt k = 0; k < 3; k++) {
      const PetscInt  row = 3 * node + k;
      const PetscReal s   = k == 2 ? 4.0 : 1.0;
      PetscReal       diag = 0.1 * s;

      if (row < rstart || row >= rend) continue;
      if (node % n) {
        PetscCall(MatSetValue(body->K, row, row - 3, -s, INSERT_VALUES));
        diag += s;
      }
      if ((node + 1) % n) {
        PetscCall(MatSetValue(body->K, row, row + 3, -s, INSERT_VALUES));
        diag += s;
      }
      if (node == 0 || node == 2 * n - 1) diag += 10 * s;
      PetscCall(MatSetValue(body->K, row, row, diag, INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(body->K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(body->K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(body->K, MAT_SPD, PETSC_TRUE));
  PetscCall(MatCreateVecs(body->K, NULL, &body->b));
  for (PetscInt k = 3 * (n - 1); k < 3 * n; k++) /* A's free end pushed towards B, and sideways */
    if (k >= rstart && k < rend) PetscCall(VecSetValue(body->b, k, k % 3 == 2 ? -8.0 : 0.3, INSERT_VALUES));
  for (PetscInt k = 3 * n; k < 3 * n + 3; k++)
    if (k >= rstart && k < rend) PetscCall(VecSetValue(body->b, k, k % 3 == 2 ? 1.0 : 0.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(body->b));
  PetscCall(VecAssemblyEnd(body->b));
  PetscFunctionReturn(0);
}

/*
   Points p = 0, 1: the own node n-2+p of A, compared with B's nodes: p = 0 with 0.5 node n + 0.5 node n+1, p = 1 with
   0.25 node n + 0.75 node n+1 (or, case shared, with A's node n-1, the other point's own node); B_p = d_p R_p
   (E_own - M_p), d = 1, 2. Owned by the rank that owns the own dofs.
*/
static PetscErrorCode ContactOperator(PetscInt n, const char *which, Mat K, IS *dofs, Mat *B, Vec *gaps)
{
  PetscInt  rstart, rend, npoints = 0, idx[6], mstart;
  PetscBool singular, shared;

  PetscFunctionBeginUser;
  PetscCall(PetscStrcmp(which, "singular", &singular));
  PetscCall(PetscStrcmp(which, "shared", &shared));
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  for (PetscInt p = 0; p < 2; p++) {
    const PetscInt own = 3 * (n - 2 + p);

    if (own < rstart || own >= rend) continue;
    for (PetscInt k = 0; k < 3; k++) idx[3 * npoints + k] = own + k;
    npoints++;
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, 3 * npoints, idx, PETSC_COPY_VALUES, dofs));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, 3 * npoints, rend - rstart, PETSC_DETERMINE, 6 * n, 9, NULL, 9, NULL, B));
  PetscCall(MatGetOwnershipRange(*B, &mstart, NULL));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, npoints, PETSC_DETERMINE, gaps));
  for (PetscInt q = 0; q < npoints; q++) {
    const PetscInt  p      = idx[3 * q] / 3 - (n - 2);
    const PetscInt  m0     = shared && p == 0 ? n - 1 : n, m1 = n + 1;
    const PetscReal w0     = p == 0 ? 0.5 : 0.25, d = p == 0 ? 1.0 : 2.0;
    PetscReal       R[9];
    PetscInt        rows[3], own[3], mc0[3], mc1[3];
    PetscScalar     vo[9], v0[9], v1[9];

    Frame(p, R);
    for (PetscInt k = 0; k < 3; k++) {
      rows[k] = mstart + 3 * q + k;
      own[k]  = idx[3 * q + k];
      mc0[k]  = 3 * m0 + k;
      mc1[k]  = 3 * m1 + k;
    }
    for (PetscInt k = 0; k < 9; k++) {
      vo[k] = singular && p == 1 && k >= 6 ? 0.0 : d * R[k];
      v0[k] = -d * w0 * R[k];
      v1[k] = -d * (1 - w0) * R[k];
    }
    PetscCall(MatSetValues(*B, 3, rows, 3, own, vo, INSERT_VALUES));
    PetscCall(MatSetValues(*B, 3, rows, 3, mc0, v0, INSERT_VALUES));
    PetscCall(MatSetValues(*B, 3, rows, 3, mc1, v1, INSERT_VALUES));
    PetscCall(VecSetValue(*gaps, mstart / 3 + q, d * (0.01 + 0.02 * p), INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*B, MAT_FINAL_ASSEMBLY));
  PetscCall(VecAssemblyBegin(*gaps));
  PetscCall(VecAssemblyEnd(*gaps));
  PetscFunctionReturn(0);
}

/* w = B u + g, and lambda with B^T lambda = K u - b (least squares on the points' own rows), per point, frames (t1, t2, n) */
static PetscErrorCode CheckLaw(PetscInt n, Body *body, Mat B, Vec gaps, Vec u, PetscReal phi)
{
  Vec        w, r, lambda;
  Mat        Bt;
  KSP        ksp;
  PetscReal  worst = 0, scale;
  const PetscScalar *wa, *la;
  PetscInt   np;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(B, NULL, &w));
  PetscCall(MatMult(B, u, w));
  PetscCall(VecGetLocalSize(gaps, &np));
  {
    const PetscScalar *ga;
    PetscScalar       *wa2;

    PetscCall(VecGetArrayRead(gaps, &ga));
    PetscCall(VecGetArray(w, &wa2));
    for (PetscInt q = 0; q < np; q++) wa2[3 * q + 2] += ga[q];
    PetscCall(VecRestoreArray(w, &wa2));
    PetscCall(VecRestoreArrayRead(gaps, &ga));
  }
  PetscCall(VecDuplicate(body->b, &r));
  PetscCall(MatMult(body->K, u, r));
  PetscCall(VecAXPY(r, -1.0, body->b));
  /* lambda: B^T lambda = r; B^T has full column rank: normal equations by LSQR */
  PetscCall(MatCreateVecs(B, NULL, &lambda));
  PetscCall(MatTranspose(B, MAT_INITIAL_MATRIX, &Bt));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, Bt, Bt));
  PetscCall(KSPSetType(ksp, KSPLSQR));
  PetscCall(KSPSetTolerances(ksp, 1e-14, 1e-30, PETSC_DEFAULT, 1000));
  {
    PC pc;

    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCNONE));
  }
  PetscCall(KSPSolve(ksp, r, lambda));
  {
    Vec       res;
    PetscReal rn, bn;

    PetscCall(VecDuplicate(r, &res));
    PetscCall(MatMult(Bt, lambda, res));
    PetscCall(VecAXPY(res, -1.0, r));
    PetscCall(VecNorm(res, NORM_INFINITY, &rn));
    PetscCall(VecNorm(body->b, NORM_INFINITY, &bn));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "force balance K u - b = B^T lambda: residual %.1e relative\n", (double)(rn / bn)));
    PetscCheck(rn <= 1e-8 * bn, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "K u - b is not B^T lambda: %g", (double)(rn / bn));
    PetscCall(VecDestroy(&res));
  }
  PetscCall(VecNorm(lambda, NORM_INFINITY, &scale));
  PetscCall(VecGetArrayRead(w, &wa));
  PetscCall(VecGetArrayRead(lambda, &la));
  for (PetscInt q = 0; q < np; q++) {
    /* lambda is the force on the body along (t1, t2, n) per unit of w: r = lambda (c = P u - f = r in the kernels) */
    const PetscReal wn = PetscRealPart(wa[3 * q + 2]), ln = PetscRealPart(la[3 * q + 2]);
    const PetscReal lt = PetscSqrtReal(PetscRealPart(la[3 * q] * la[3 * q] + la[3 * q + 1] * la[3 * q + 1]));
    const PetscReal wt = PetscSqrtReal(PetscRealPart(wa[3 * q] * wa[3 * q] + wa[3 * q + 1] * wa[3 * q + 1]));

    worst = PetscMax(worst, PetscMax(0, -wn) / 1e-3);
    worst = PetscMax(worst, PetscMax(0, -ln) / scale);
    worst = PetscMax(worst, PetscAbsReal(wn * ln) / (1e-3 * scale));
    worst = PetscMax(worst, PetscMax(0, lt - phi * ln) / scale);
    if (wt > 1e-9) worst = PetscMax(worst, PetscAbsReal(lt - phi * ln) / scale); /* sliding: on the cone */
    PetscCall(PetscSynchronizedPrintf(PETSC_COMM_WORLD, "point: w = (%.3e, %.3e, %.3e), lambda = (%.3e, %.3e, %.3e)\n", (double)PetscRealPart(wa[3 * q]), (double)PetscRealPart(wa[3 * q + 1]), (double)wn, (double)PetscRealPart(la[3 * q]), (double)PetscRealPart(la[3 * q + 1]), (double)ln));
  }
  PetscCall(PetscSynchronizedFlush(PETSC_COMM_WORLD, PETSC_STDOUT));
  PetscCall(VecRestoreArrayRead(lambda, &la));
  PetscCall(VecRestoreArrayRead(w, &wa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &worst, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "contact law on w: worst violation %.1e relative\n", (double)worst));
  PetscCheck(worst <= 1e-8, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the contact law is violated by %g", (double)worst);
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&Bt));
  PetscCall(VecDestroy(&lambda));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* (C K^-1 C^T)^-1 with C = R^T B / d per point (the points' variables, global frame), against the solver's P */
static PetscErrorCode CheckFormula(PetscInt n, Body *body, Mat B, SNES snes)
{
  Mat          Kd, Bd, P, Pd;
  PetscScalar *k, *bb, *p;
  PetscInt     N = 6 * n, m = 6;
  PetscBLASInt bn, bm, info, *piv;
  PetscScalar *X, *S;
  PetscReal    err = 0, asym = 0, pmax = 0;

  PetscFunctionBeginUser;
  PetscCall(SNESSSStarGetReducedProblem(snes, &P, NULL));
  PetscCall(MatConvert(body->K, MATSEQDENSE, MAT_INITIAL_MATRIX, &Kd));
  PetscCall(MatConvert(B, MATSEQDENSE, MAT_INITIAL_MATRIX, &Bd));
  PetscCall(MatConvert(P, MATSEQDENSE, MAT_INITIAL_MATRIX, &Pd));
  PetscCall(MatDenseGetArray(Kd, &k));
  PetscCall(MatDenseGetArray(Bd, &bb));
  PetscCall(MatDenseGetArray(Pd, &p));
  PetscCall(PetscMalloc3(N * m, &X, m * m, &S, N, &piv));
  /* C = R^T B / d, X = C^T (N x m, column-major) */
  for (PetscInt q = 0; q < 2; q++) {
    PetscReal R[9];
    const PetscReal d = q == 0 ? 1.0 : 2.0;

    Frame(q, R);
    for (PetscInt j = 0; j < N; j++)
      for (PetscInt k2 = 0; k2 < 3; k2++) {
        PetscScalar v = 0;

        for (PetscInt c = 0; c < 3; c++) v += R[3 * c + k2] * bb[j * m + 3 * q + c] / d;
        X[(3 * q + k2) * N + j] = v;
      }
  }
  PetscCall(PetscBLASIntCast(N, &bn));
  PetscCall(PetscBLASIntCast(m, &bm));
  { /* S = C K^-1 C^T */
    PetscScalar *Y;

    PetscCall(PetscMalloc1(N * m, &Y));
    PetscCall(PetscArraycpy(Y, X, N * m));
    PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&bn, &bm, k, &bn, piv, Y, &bn, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK gesv: %d", (int)info);
    for (PetscInt a = 0; a < m; a++)
      for (PetscInt c = 0; c < m; c++) {
        PetscScalar v = 0;

        for (PetscInt j = 0; j < N; j++) v += X[a * N + j] * Y[c * N + j];
        S[c * m + a] = v;
      }
    PetscCall(PetscFree(Y));
  }
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bm, &bm, S, &bm, piv, &info));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "C K^-1 C^T is singular");
  {
    PetscScalar work[64];
    PetscBLASInt lwork = 64;

    PetscCallBLAS("LAPACKgetri", LAPACKgetri_(&bm, S, &bm, piv, work, &lwork, &info));
  }
  for (PetscInt a = 0; a < m; a++)
    for (PetscInt c = 0; c < m; c++) {
      err  = PetscMax(err, PetscAbsScalar(p[c * m + a] - S[c * m + a]));
      asym = PetscMax(asym, PetscAbsScalar(p[c * m + a] - p[a * m + c]));
      pmax = PetscMax(pmax, PetscAbsScalar(p[c * m + a]));
    }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "reduced operator: |P - (C K^-1 C^T)^-1| %.1e, |P - P^T| %.1e (relative to max |P|)\n", (double)(err / pmax), (double)(asym / pmax)));
  PetscCheck(err <= 1e-12 * pmax && asym <= 1e-12 * pmax, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the reduced operator is wrong");
  PetscCall(PetscFree3(X, S, piv));
  PetscCall(MatDenseRestoreArray(Pd, &p));
  PetscCall(MatDenseRestoreArray(Bd, &bb));
  PetscCall(MatDenseRestoreArray(Kd, &k));
  PetscCall(MatDestroy(&Kd));
  PetscCall(MatDestroy(&Bd));
  PetscCall(MatDestroy(&Pd));
  PetscFunctionReturn(0);
}

/* -update: the same B declared again at every iterate (the iterate taken into the points' variables of a new T) */
typedef struct {
  IS  dofs;
  Mat B;
  Vec gaps;
} Declaration;

static PetscErrorCode DeclareAgain(SNES snes, Vec x, void *ctx)
{
  Declaration *d = (Declaration *)ctx;

  PetscFunctionBeginUser;
  PetscCall(SNESSSStarSetContactOperator(snes, d->dofs, d->B, d->gaps));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Body      body;
  SNES      snes;
  IS        dofs;
  Mat       B;
  Vec       gaps, u;
  PetscInt  n = 6;
  char      which[32] = "law", out[PETSC_MAX_PATH_LEN] = "";
  PetscBool formula, hasOut, update = PETSC_FALSE;
  Declaration declaration;
  PetscReal phi;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", which, sizeof(which), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-o", out, sizeof(out), &hasOut));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-update", &update, NULL));
  PetscCall(PetscStrcmp(which, "formula", &formula));
  PetscCall(AssembleBodies(n, &body));
  PetscCall(ContactOperator(n, which, body.K, &dofs, &B, &gaps));

  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, body.K, body.b));
  PetscCall(SNESSSStarSetContactOperator(snes, dofs, B, gaps));
  if (formula) PetscCall(SNESSSStarSetReductionType(snes, SSSTARREDUCTIONDIRECT));
  declaration = (Declaration){dofs, B, gaps};
  if (update) PetscCall(SNESSSStarSetContactUpdate(snes, DeclareAgain, &declaration));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(MatCreateVecs(body.K, &u, NULL));
  PetscCall(VecZeroEntries(u));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESSSStarGetFriction(snes, &phi));
  if (update) {
    PetscInt updates, its;

    PetscCall(SNESSSStarGetNonlinearCounts(snes, NULL, &updates));
    PetscCall(SNESGetIterationNumber(snes, &its));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "contact updates: %" PetscInt_FMT " in %" PetscInt_FMT " iterations\n", updates, its));
  }
  if (formula) PetscCall(CheckFormula(n, &body, B, snes));
  else PetscCall(CheckLaw(n, &body, B, gaps, u, phi));
  if (hasOut) {
    PetscViewer viewer;

    PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, out, FILE_MODE_WRITE, &viewer));
    PetscCall(VecView(u, viewer));
    PetscCall(PetscViewerDestroy(&viewer));
  }
  PetscCall(VecDestroy(&u));
  PetscCall(SNESDestroy(&snes));
  PetscCall(ISDestroy(&dofs));
  PetscCall(MatDestroy(&B));
  PetscCall(VecDestroy(&gaps));
  PetscCall(MatDestroy(&body.K));
  PetscCall(VecDestroy(&body.b));
  PetscCall(PetscFinalize());
  return 0;
}
