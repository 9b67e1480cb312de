static const char help[] = "ssstar Newton steps against the 6p system D [dv; eta] = [z; z] of docs/derivation.md section 4, in the nodes' frames.\n\
  -trials <24>   random problems\n\
  -sparse        K as AIJ: the generic path (MatMatMult, LU through the KSP) instead of the eliminated dense one\n";

/*
   Requirement: on random SPD K, loads and starting points, with per-node laws (Coulomb, Coulomb with phi = 0, Tresca,
   none, orthotropic with a random direction in global axes), tilted obstacle normals and gaps, declared through SNESSSStarSetContactNodes (every dof a contact dof, nodes
   in reversed order), the step taken by SNESSolve with -snes_max_it 1 equals the solution of the 6p system built from
   the per-node G, H blocks, to 1e-10 relative; so does the second step of -snes_max_it 2 when it is solved by GMRES on
   the LU of the first (SNESSSStarSetLUReuse(snes, 1)); the condition estimate is within a factor 10 of 1/cond_1 of the
   eliminated matrix. Every rank checks the whole vectors (1 or 2 ranks).
*/
#include <ssstar.h>
#include <petscblaslapack.h>

#define NODES 16
#define N     (3 * NODES)

/* the laws of the test, by their index in the table of laws */
enum {
  NONE,
  TRESCA,
  COULOMB,
  ORTHOTROPIC,
  NUM_LAWS
};
static const char *const LawNames[NUM_LAWS] = {SSSTARLAWNONE, SSSTARLAWTRESCA, SSSTARLAWCOULOMB, SSSTARLAWORTHOTROPIC};
static PetscInt          LawIndex[NUM_LAWS];

typedef struct {
  PetscReal K[N * N], b[N]; /* K column-major, SPD */
  PetscInt  law[NODES];     /* NONE, ... */
  PetscReal phi[NODES], phi2[NODES], direction[3 * NODES], bound[NODES], gap[NODES], R[9 * NODES];
  PetscBool tilted, gaps;
  PetscReal gamma;
} Problem;

/* The kernels' friction of node i: a bound times gamma (the kernels see gamma c), the direction in the node's frame */
static PetscErrorCode NodeFriction(const Problem *pb, PetscInt i, SSStarFriction *fr)
{
  const PetscReal *R = &pb->R[9 * i], *a = &pb->direction[3 * i];
  PetscReal        v[5];

  PetscFunctionBeginUser;
  switch (pb->law[i]) {
  case NONE:
    PetscCall(SSStarFrictionSet(fr, SSSTARLAWNONE, 0, NULL));
    break;
  case TRESCA:
    v[0] = pb->gamma * pb->bound[i];
    PetscCall(SSStarFrictionSet(fr, SSSTARLAWTRESCA, 1, v));
    break;
  case COULOMB:
    PetscCall(SSStarFrictionSet(fr, SSSTARLAWCOULOMB, 1, &pb->phi[i]));
    break;
  default:
    v[0] = pb->phi[i];
    v[1] = pb->phi2[i];
    for (PetscInt r = 0; r < 3; r++) v[2 + r] = R[3 * r] * a[0] + R[3 * r + 1] * a[1] + R[3 * r + 2] * a[2];
    PetscCall(SSStarFrictionSet(fr, SSSTARLAWORTHOTROPIC, 5, v));
  }
  PetscFunctionReturn(0);
}

/* The 6p step at u: du, the states, and 1/cond_1 of the matrix of the unknown dofs (section 5 rows not fixed) */
typedef struct {
  PetscReal   du[N];
  SSStarState state[NODES];
  PetscBool   known[N];
  PetscReal   rcond;
} Step;

static void RotateBlock(const PetscReal Ri[9], const PetscReal Kij[9], const PetscReal Rj[9], PetscReal out[9])
{
  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) {
      out[3 * r + c] = 0;
      for (PetscInt k = 0; k < 3; k++)
        for (PetscInt l = 0; l < 3; l++) out[3 * r + c] += Ri[3 * r + k] * Kij[3 * k + l] * Rj[3 * c + l];
    }
}

/* K_ij as a row-major 3x3 block */
static void KBlock(const Problem *pb, PetscInt i, PetscInt j, PetscReal B[9])
{
  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) B[3 * r + c] = pb->K[(3 * j + c) * N + 3 * i + r];
}

static PetscReal Norm1(PetscInt n, const PetscReal *A)
{
  PetscReal nrm = 0;

  for (PetscInt c = 0; c < n; c++) {
    PetscReal s = 0;

    for (PetscInt r = 0; r < n; r++) s += PetscAbsReal(A[c * n + r]);
    nrm = PetscMax(nrm, s);
  }
  return nrm;
}

static PetscErrorCode SixPStep(const Problem *pb, const PetscReal u[], Step *st)
{
  const PetscInt m = 2 * N;
  PetscReal      c[N], G[NODES][9], H[NODES][9], S[NODES][9], T[NODES][9], z[N];
  PetscScalar   *D, *rhs, *A;
  PetscBLASInt   bm, one = 1, info, *piv, nR = 0, lwork = N * N;
  PetscInt       unknown[N];

  PetscFunctionBeginUser;
  for (PetscInt r = 0; r < N; r++) {
    c[r] = -pb->b[r];
    for (PetscInt k = 0; k < N; k++) c[r] += pb->K[k * N + r] * u[k];
  }
  for (PetscInt i = 0; i < NODES; i++) {
    const PetscReal *R = &pb->R[9 * i];
    SSStarFriction   fr;
    PetscReal        v[3], cc[3], d[3], bb[3];

    PetscCall(NodeFriction(pb, i, &fr));
    for (PetscInt r = 0; r < 3; r++) {
      v[r]  = R[3 * r] * u[3 * i] + R[3 * r + 1] * u[3 * i + 1] + R[3 * r + 2] * u[3 * i + 2] + (r == 2 ? pb->gap[i] : 0.0);
      cc[r] = pb->gamma * (R[3 * r] * c[3 * i] + R[3 * r + 1] * c[3 * i + 1] + R[3 * r + 2] * c[3 * i + 2]);
    }
    SSStarApproximationStep(&fr, v, cc, &z[3 * i], d, bb);
    st->state[i] = SSStarClassify(&fr, d, bb, 0.0, 0.0);
    SSStarTangentBlocks(st->state[i], &fr, d, bb, G[i], H[i]);
    SSStarReducedBlocks(st->state[i], &fr, d, bb, S[i], T[i]);
    for (PetscInt r = 0; r < 3; r++) {
      st->known[3 * i + r] = PETSC_TRUE;
      for (PetscInt k = 0; k < 3; k++)
        if (S[i][3 * r + k] != 0.0 || T[i][3 * r + k] != (PetscReal)(k == r)) st->known[3 * i + r] = PETSC_FALSE;
      if (!st->known[3 * i + r]) unknown[nR++] = 3 * i + r;
    }
  }

  /* D = [[gamma R K R^T, -H], [I, G]] (column-major), rhs [z; z] */
  PetscCall(PetscCalloc4(m * m, &D, m, &rhs, m, &piv, N * N, &A));
  for (PetscInt i = 0; i < NODES; i++)
    for (PetscInt j = 0; j < NODES; j++) {
      PetscReal Kij[9], B[9];

      KBlock(pb, i, j, Kij);
      RotateBlock(&pb->R[9 * i], Kij, &pb->R[9 * j], B);
      for (PetscInt r = 0; r < 3; r++)
        for (PetscInt k = 0; k < 3; k++) D[(3 * j + k) * m + 3 * i + r] = pb->gamma * B[3 * r + k];
    }
  for (PetscInt i = 0; i < NODES; i++)
    for (PetscInt r = 0; r < 3; r++) {
      rhs[3 * i + r]     = z[3 * i + r];
      rhs[N + 3 * i + r] = z[3 * i + r];
      D[(3 * i + r) * m + N + 3 * i + r] = 1.0;
      for (PetscInt k = 0; k < 3; k++) {
        D[(N + 3 * i + k) * m + 3 * i + r]     = -H[i][3 * r + k];
        D[(N + 3 * i + k) * m + N + 3 * i + r] = G[i][3 * r + k];
      }
    }
  /* the eliminated matrix A_RR of A = gamma S R K R^T + T, rows and columns of the unknown dofs */
  for (PetscInt a = 0; a < nR; a++)
    for (PetscInt bcol = 0; bcol < nR; bcol++) {
      const PetscInt ga = unknown[a], gb = unknown[bcol], i = ga / 3, r = ga % 3;
      PetscReal      v = ga / 3 == gb / 3 ? T[i][3 * r + gb % 3] : 0.0;

      for (PetscInt k = 0; k < 3; k++) v += S[i][3 * r + k] * D[gb * m + 3 * i + k];
      A[bcol * nR + a] = v;
    }
  PetscCall(PetscBLASIntCast(m, &bm));
  PetscCallBLAS("LAPACKgesv", LAPACKgesv_(&bm, &one, D, &bm, piv, rhs, &bm, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "6p system singular (info %d)", (int)info);
  for (PetscInt i = 0; i < NODES; i++) {
    const PetscReal *R = &pb->R[9 * i];

    for (PetscInt k = 0; k < 3; k++) st->du[3 * i + k] = R[k] * rhs[3 * i] + R[3 + k] * rhs[3 * i + 1] + R[6 + k] * rhs[3 * i + 2];
  }
  st->rcond = 1;
  if (nR) {
    PetscReal    anorm = Norm1(nR, A);
    PetscScalar *work;

    PetscCall(PetscMalloc1(lwork, &work));
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&nR, &nR, A, &nR, piv, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "A_RR singular (info %d)", (int)info);
    PetscCallBLAS("LAPACKgetri", LAPACKgetri_(&nR, A, &nR, piv, work, &lwork, &info));
    st->rcond = 1.0 / (anorm * Norm1(nR, A));
    PetscCall(PetscFree(work));
  }
  PetscCall(PetscFree4(D, rhs, piv, A));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscInt  lu, reused, krylov;
  PetscReal rcond;
} Counts;

/*
   SNESSolve from u0 with max_it steps, every dof a contact dof; the owned nodes are declared in reversed order (the
   solver sorts them). u: the whole result on every rank.
*/
static PetscErrorCode Solve(const Problem *pb, PetscBool sparse, PetscInt maxit, PetscReal reuse, const PetscReal u0[], PetscReal u[], Counts *counts)
{
  MPI_Comm           comm = PETSC_COMM_WORLD;
  PetscInt           nodes = PETSC_DECIDE, Nnodes = NODES, start, dofs[N];
  PetscInt           lawsUser[NODES];
  Mat                K;
  Vec                x, b, normals, gaps, phi, phi2, direction, bounds, all;
  IS                 is;
  SNES               snes;
  VecScatter         toAll;
  const PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(PetscSplitOwnership(comm, &nodes, &Nnodes));
  PetscCallMPI(MPI_Scan(&nodes, &start, 1, MPIU_INT, MPI_SUM, comm));
  start -= nodes;
  if (sparse) PetscCall(MatCreateAIJ(comm, 3 * nodes, 3 * nodes, N, N, 3 * nodes, NULL, N - 3 * nodes, NULL, &K));
  else PetscCall(MatCreateDense(comm, 3 * nodes, 3 * nodes, N, N, NULL, &K));
  for (PetscInt r = 3 * start; r < 3 * (start + nodes); r++)
    for (PetscInt c = 0; c < N; c++) PetscCall(MatSetValue(K, r, c, pb->K[c * N + r], INSERT_VALUES));
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(K, &x, &b));
  PetscCall(VecCreateMPI(comm, 3 * nodes, N, &normals));
  PetscCall(VecDuplicate(normals, &direction));
  PetscCall(VecCreateMPI(comm, nodes, NODES, &gaps));
  PetscCall(VecDuplicate(gaps, &phi));
  PetscCall(VecDuplicate(gaps, &phi2));
  PetscCall(VecDuplicate(gaps, &bounds));
  for (PetscInt k = 0; k < nodes; k++) { /* user's node k is node j */
    const PetscInt j = start + nodes - 1 - k;

    for (PetscInt r = 0; r < 3; r++) {
      dofs[3 * k + r] = 3 * j + r;
      PetscCall(VecSetValue(normals, 3 * (start + k) + r, pb->R[9 * j + 6 + r], INSERT_VALUES));
      PetscCall(VecSetValue(direction, 3 * (start + k) + r, pb->direction[3 * j + r], INSERT_VALUES));
      PetscCall(VecSetValue(x, 3 * j + r, u0[3 * j + r], INSERT_VALUES));
      PetscCall(VecSetValue(b, 3 * j + r, pb->b[3 * j + r], INSERT_VALUES));
    }
    PetscCall(VecSetValue(gaps, start + k, pb->gap[j], INSERT_VALUES));
    PetscCall(VecSetValue(phi, start + k, pb->phi[j], INSERT_VALUES));
    PetscCall(VecSetValue(phi2, start + k, pb->phi2[j], INSERT_VALUES));
    PetscCall(VecSetValue(bounds, start + k, pb->bound[j], INSERT_VALUES));
    lawsUser[k] = LawIndex[pb->law[j]];
  }
  for (Vec *v = (Vec[]){x, b, normals, direction, gaps, phi, phi2, bounds}, *e = v + 8; v < e; v++) {
    PetscCall(VecAssemblyBegin(*v));
    PetscCall(VecAssemblyEnd(*v));
  }
  PetscCall(ISCreateGeneral(comm, 3 * nodes, dofs, PETSC_COPY_VALUES, &is));

  PetscCall(SNESCreate(comm, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSSStarSetLinearProblem(snes, K, b));
  PetscCall(SNESSSStarSetContactNodes(snes, is, pb->tilted ? normals : NULL, pb->gaps ? gaps : NULL));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction", phi));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "slip_bound", bounds));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction_1", phi));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction_2", phi2));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction_direction", direction));
  PetscCall(SNESSSStarSetNodeFrictionLaws(snes, nodes, lawsUser));
  PetscCall(SNESSSStarSetScaling(snes, pb->gamma));
  PetscCall(SNESSSStarSetStateTolerance(snes, 0.0));
  PetscCall(SNESSSStarSetLUReuse(snes, reuse));
  PetscCall(SNESSSStarSetGlobalization(snes, PETSC_FALSE, PETSC_DEFAULT, PETSC_DEFAULT)); /* full steps: the ones compared */
  PetscCall(SNESSetTolerances(snes, PETSC_DEFAULT, 1e-300, PETSC_DEFAULT, maxit, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(SNESSolve(snes, NULL, x));
  PetscCall(SNESSSStarGetNewtonStepCounts(snes, &counts->lu, &counts->reused, &counts->krylov));
  PetscCall(SNESSSStarGetConditionEstimate(snes, &counts->rcond));

  PetscCall(VecScatterCreateToAll(x, &toAll, &all));
  PetscCall(VecScatterBegin(toAll, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(toAll, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all, &xa));
  for (PetscInt k = 0; k < N; k++) u[k] = PetscRealPart(xa[k]);
  PetscCall(VecRestoreArrayRead(all, &xa));
  PetscCall(VecScatterDestroy(&toAll));
  PetscCall(VecDestroy(&all));
  PetscCall(SNESDestroy(&snes));
  PetscCall(ISDestroy(&is));
  for (Vec *v = (Vec[]){x, b, normals, direction, gaps, phi, phi2, bounds}, *e = v + 8; v < e; v++) PetscCall(VecDestroy(v));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(0);
}

static PetscErrorCode RandomProblem(PetscRandom rnd, PetscInt t, Problem *pb, PetscReal u0[])
{
  PetscReal B[N * N];

  PetscFunctionBeginUser;
  /* K = B^T B + N I */
  for (PetscInt k = 0; k < N * N; k++) PetscCall(PetscRandomGetValueReal(rnd, &B[k]));
  for (PetscInt i = 0; i < N; i++)
    for (PetscInt j = 0; j < N; j++) {
      pb->K[j * N + i] = i == j ? N : 0.0;
      for (PetscInt k = 0; k < N; k++) pb->K[j * N + i] += B[i * N + k] * B[j * N + k];
    }
  for (PetscInt k = 0; k < N; k++) {
    PetscCall(PetscRandomGetValueReal(rnd, &pb->b[k]));
    pb->b[k] *= 10;
  }
  pb->gamma  = 0.37;
  pb->tilted = (PetscBool)(t % 2);
  pb->gaps   = (PetscBool)(t % 3 != 0);
  for (PetscInt i = 0; i < NODES; i++) {
    PetscReal n[3] = {0, 0, 1}, v[3], x;
    const PetscReal *R = &pb->R[9 * i];

    switch ((i + t) % 6) {
    case 0:
      pb->law[i] = NONE;
      break;
    case 1:
      pb->law[i] = TRESCA;
      break;
    case 5:
      pb->law[i] = ORTHOTROPIC;
      break;
    default:
      pb->law[i] = COULOMB;
    }
    PetscCall(PetscRandomGetValueReal(rnd, &x));
    pb->phi[i]   = (i + t) % 6 == 2 ? 0.0 : 0.3 + 0.2 * x; /* Coulomb with phi = 0 too */
    pb->phi2[i]  = 0.1 + 0.3 * PetscAbsReal(x);
    pb->bound[i] = 20.0 + 20.0 * x;
    for (PetscInt k = 0; k < 3; k++) PetscCall(PetscRandomGetValueReal(rnd, &pb->direction[3 * i + k]));
    pb->direction[3 * i + 2] *= 0.2; /* far from the normals, which are within 27 degrees of (0, 0, 1) */
    PetscCall(PetscRandomGetValueReal(rnd, &x));
    pb->gap[i] = pb->gaps ? 0.05 * x : 0.0;
    if (pb->tilted) {
      PetscCall(PetscRandomGetValueReal(rnd, &n[0]));
      PetscCall(PetscRandomGetValueReal(rnd, &n[1]));
      n[0] *= 0.5;
      n[1] *= 0.5;
      x = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + 1);
      for (PetscInt k = 0; k < 3; k++) n[k] /= x;
    }
    SSStarNodeFrame(n, &pb->R[9 * i]);
    /* the start in the node's frame: on the plane (even nodes) or above it, slipping or not */
    for (PetscInt k = 0; k < 3; k++) PetscCall(PetscRandomGetValueReal(rnd, &v[k]));
    v[2] = i % 2 == 0 ? 0.0 : PetscAbsReal(v[2]);
    if (i % 4 == 1) v[0] = v[1] = 0.0;
    v[2] -= pb->gap[i];
    for (PetscInt k = 0; k < 3; k++) u0[3 * i + k] = R[k] * v[0] + R[3 + k] * v[1] + R[6 + k] * v[2];
  }
  PetscFunctionReturn(0);
}

static PetscReal RelativeDifference(const PetscReal a[], const PetscReal b[], const PetscReal ref[])
{
  PetscReal diff = 0, norm = 0;

  for (PetscInt k = 0; k < N; k++) {
    diff += (a[k] - b[k] - ref[k]) * (a[k] - b[k] - ref[k]);
    norm += ref[k] * ref[k];
  }
  return PetscSqrtReal(diff / norm);
}

int main(int argc, char **argv)
{
  PetscInt    trials = 24, failures = 0, seen[NUM_LAWS][SSSTAR_NUM_STATES] = {{0}}, moved = 0;
  PetscReal   worst[3] = {0, 0, 0}, rcondRatio[2] = {PETSC_MAX_REAL, 0};
  PetscBool   sparse = PETSC_FALSE;
  PetscRandom rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  for (PetscInt l = 0; l < NUM_LAWS; l++) PetscCall(SSStarLawGetIndex(LawNames[l], &LawIndex[l]));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-trials", &trials, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-sparse", &sparse, NULL));
  /* the second step on the first step's LU is solved to the round-off */
  PetscCall(PetscOptionsSetValue(NULL, "-snes_ssstar_newton_ksp_rtol", "1e-14"));
  PetscCall(PetscOptionsSetValue(NULL, "-snes_ssstar_newton_ksp_max_it", "500"));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd)); /* the same numbers on every rank */
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  for (PetscInt t = 0; t < trials; t++) {
    Problem  *pb;
    PetscReal u0[N], u1[N], u2[N], d;
    Step      s0, s1;
    Counts    c1, c2;

    PetscCall(PetscNew(&pb));
    PetscCall(RandomProblem(rnd, t, pb, u0));
    PetscCall(SixPStep(pb, u0, &s0));
    for (PetscInt i = 0; i < NODES; i++) seen[pb->law[i]][s0.state[i]]++;

    /* one step: a fresh LU */
    PetscCall(Solve(pb, sparse, 1, -1, u0, u1, &c1));
    d = RelativeDifference(u1, u0, s0.du);
    worst[0] = PetscMax(worst[0], d);
    if (!(d <= 1e-10) || c1.lu != 1) {
      failures++;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAIL trial %" PetscInt_FMT ": first step |du - du6p|/|du6p| = %g, %" PetscInt_FMT " LU\n", t, (double)d, c1.lu));
    }
    if (sparse) {
      if (c1.rcond != -1) {
        failures++;
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAIL trial %" PetscInt_FMT ": sparse path gives a condition estimate %g, not -1\n", t, (double)c1.rcond));
      }
    } else {
      rcondRatio[0] = PetscMin(rcondRatio[0], c1.rcond / s0.rcond);
      rcondRatio[1] = PetscMax(rcondRatio[1], c1.rcond / s0.rcond);
    }

    /* two steps, the second on the first's LU */
    if (!sparse) {
      PetscCall(SixPStep(pb, u1, &s1));
      for (PetscInt k = 0; k < N; k++)
        if (s0.known[k] != s1.known[k]) {
          moved++;
          break;
        }
      PetscCall(Solve(pb, sparse, 2, 1.0, u0, u2, &c2));
      d = RelativeDifference(u2, u1, s1.du);
      worst[1] = PetscMax(worst[1], d);
      if (!(d <= 1e-10) || c2.lu != 1 || c2.reused != 1) {
        failures++;
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAIL trial %" PetscInt_FMT ": second step on the old LU |du - du6p|/|du6p| = %g (%" PetscInt_FMT " LU, %" PetscInt_FMT " reused)\n", t, (double)d, c2.lu, c2.reused));
      }
    }
    PetscCall(PetscFree(pb));
  }
  PetscCall(PetscRandomDestroy(&rnd));

  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "states seen (law: L M1 M2 M3+ M3- M4 LS):"));
  for (PetscInt l = 0; l < NUM_LAWS; l++) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, " %s:", LawNames[l]));
    for (PetscInt s = 0; s < SSSTAR_NUM_STATES; s++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, " %" PetscInt_FMT, seen[l][s]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "\nworst relative difference: first step %.1e, step on an old LU %.1e (%" PetscInt_FMT " trials with dofs changing status)\n", (double)worst[0], (double)worst[1], moved));
  if (!sparse) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "condition estimate / 1/cond_1(A_RR) in [%.2f, %.2f]\n", (double)rcondRatio[0], (double)rcondRatio[1]));
    if (!(rcondRatio[0] >= 0.1 && rcondRatio[1] <= 10)) {
      failures++;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAIL: the condition estimate is off by more than a factor 10\n"));
    }
    if (!moved) {
      failures++;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAIL: no trial moved a dof between known and unknown on the old LU\n"));
    }
  }
  if (!seen[COULOMB][SSSTAR_STATE_L] || !seen[COULOMB][SSSTAR_STATE_M1] || !seen[COULOMB][SSSTAR_STATE_M3P] || !seen[TRESCA][SSSTAR_STATE_LS] || !seen[TRESCA][SSSTAR_STATE_M1] ||
      !(seen[NONE][SSSTAR_STATE_M1] + seen[NONE][SSSTAR_STATE_M3P] + seen[NONE][SSSTAR_STATE_M3M]) || !seen[ORTHOTROPIC][SSSTAR_STATE_M1] || !seen[ORTHOTROPIC][SSSTAR_STATE_M3P]) {
    failures++;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FAIL: the random states do not cover Coulomb L, M1, M3+, Tresca LS, M1, frictionless contact and orthotropic M1, M3+\n"));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", failures ? "FAILED" : "OK"));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
