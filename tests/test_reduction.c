static const char help[] = "The Schur reduction on a hand-assembled K: a lattice of springs, n x n x n nodes, held at x = 0,\n\
the face y = 0 the contact dofs (on every rank). Computes P, f and the recovered u by each of -types and prints their differences.\n\
  -n <5>                 nodes per side\n\
  -types <direct,mumps,explicit>  the reductions to run and compare (the first one is the reference)\n\
  -floating <0>          nodes per side of a lattice connected to nothing and held nowhere: K is singular\n\
                         (1: a node without any stiffness)\n\
  -memory_limit <0>      GB per rank the reduction may plan for (0: MemAvailable)\n";

#include <ssstarreduction.h>
#include <ssstar.h>

typedef struct {
  PetscInt n;        /* nodes per side of the lattice; the nodes at x = 0 are held (no dofs) */
  PetscInt floating; /* nodes per side of the floating lattice (0: none)                     */
} Lattice;

/* Free nodes: (i, j, k) with 1 <= i < n, numbered i - 1 + (n - 1)(j + n k); then the floating lattice */
static PetscInt NodeId(const Lattice *lat, PetscInt i, PetscInt j, PetscInt k)
{
  return i - 1 + (lat->n - 1) * (j + lat->n * k);
}

/* 3x3 block of a spring along the lattice offset (di, dj, dk): e e^T + I / 10, e the unit offset */
static void Spring(PetscInt di, PetscInt dj, PetscInt dk, PetscScalar A[9])
{
  const PetscReal e[3] = {(PetscReal)di, (PetscReal)dj, (PetscReal)dk};
  const PetscReal l2   = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];

  for (PetscInt r = 0; r < 3; r++)
    for (PetscInt c = 0; c < 3; c++) A[3 * r + c] = e[r] * e[c] / l2 + (r == c ? 0.1 : 0.0);
}

/* Adds the spring between node a (or held, a < 0) and node b to K */
static PetscErrorCode AddSpring(Mat K, PetscInt a, PetscInt b, const PetscScalar A[9])
{
  PetscScalar minusA[9];

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 9; k++) minusA[k] = -A[k];
  if (a >= 0) PetscCall(MatSetValuesBlocked(K, 1, &a, 1, &a, A, ADD_VALUES));
  PetscCall(MatSetValuesBlocked(K, 1, &b, 1, &b, A, ADD_VALUES));
  if (a >= 0) {
    PetscCall(MatSetValuesBlocked(K, 1, &a, 1, &b, minusA, ADD_VALUES));
    PetscCall(MatSetValuesBlocked(K, 1, &b, 1, &a, minusA, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

/* Springs of an m x m x m lattice to all 26 neighbours; node (i, j, k) is id(i, j, k), negative when held */
static PetscErrorCode AddLattice(Mat K, const Lattice *lat, PetscInt m, PetscInt offset, PetscBool held, PetscInt first, PetscInt last)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < m; k++)
    for (PetscInt j = 0; j < m; j++)
      for (PetscInt i = 0; i < m; i++)
        for (PetscInt dk = -1; dk <= 1; dk++)
          for (PetscInt dj = -1; dj <= 1; dj++)
            for (PetscInt di = -1; di <= 1; di++) {
              const PetscInt i2 = i + di, j2 = j + dj, k2 = k + dk;
              PetscInt       a, b;
              PetscScalar    A[9];

              if (dk * 9 + dj * 3 + di <= 0) continue; /* each pair once */
              if (i2 < 0 || i2 >= m || j2 < 0 || j2 >= m || k2 < 0 || k2 >= m) continue;
              a = held ? (i == 0 ? -1 : NodeId(lat, i, j, k)) : offset + i + m * (j + m * k);
              b = held ? (i2 == 0 ? -1 : NodeId(lat, i2, j2, k2)) : offset + i2 + m * (j2 + m * k2);
              if (a < 0 && b < 0) continue;
              if (b < 0) { /* the held node first */
                b = a;
                a = -1;
              }
              if (b < first || b >= last) continue; /* the rank owning b adds the spring */
              Spring(di, dj, dk, A);
              PetscCall(AddSpring(K, a, b, A));
            }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Lattice             lat = {5, 0};
  PetscReal           limit    = 0;
  char               *names[3];
  PetscBool           set;
  PetscInt            ntypes = 3, nfree, first, last, nC = 0, nI = 0, *idxC, *idxI;
  Mat                 K, P[3];
  Vec                 F, f[3], u[3], uC, rC, res;
  IS                  isC, isI;
  PetscLayout         layout;
  PetscMPIInt         rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &lat.n, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-floating", &lat.floating, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-memory_limit", &limit, NULL));
  PetscCall(PetscOptionsGetStringArray(NULL, NULL, "-types", names, &ntypes, &set));
  if (!set) {
    const char *const schur[] = {SSSTARREDUCTIONDIRECT, SSSTARREDUCTIONMUMPS, SSSTARREDUCTIONEXPLICIT};

    ntypes = 3;
    for (PetscInt t = 0; t < 3; t++) PetscCall(PetscStrallocpy(schur[t], &names[t]));
  }
  nfree        = (lat.n - 1) * lat.n * lat.n + lat.floating * lat.floating * lat.floating;

  /* K: 3 dofs per free node, nodes split over the ranks */
  PetscCall(PetscLayoutCreate(PETSC_COMM_WORLD, &layout));
  PetscCall(PetscLayoutSetSize(layout, nfree));
  PetscCall(PetscLayoutSetUp(layout));
  PetscCall(PetscLayoutGetRange(layout, &first, &last));
  PetscCall(PetscLayoutDestroy(&layout));
  PetscCall(MatCreate(PETSC_COMM_WORLD, &K));
  PetscCall(MatSetSizes(K, 3 * (last - first), 3 * (last - first), PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(K, 3));
  PetscCall(MatSetType(K, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(K, 81, NULL));
  PetscCall(MatMPIAIJSetPreallocation(K, 81, NULL, 81, NULL));
  PetscCall(AddLattice(K, &lat, lat.n, 0, PETSC_TRUE, first, last));
  if (lat.floating) PetscCall(AddLattice(K, &lat, lat.floating, (lat.n - 1) * lat.n * lat.n, PETSC_FALSE, first, last));
  if (lat.floating == 1 && last == nfree) { /* the lone node: zero entries on its diagonal block */
    const PetscInt    node    = nfree - 1;
    const PetscScalar zero[9] = {0};

    PetscCall(MatSetValuesBlocked(K, 1, &node, 1, &node, zero, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));

  /* contact dofs: the nodes at y = 0, in decreasing node order (any order is allowed) */
  PetscCall(PetscMalloc2(3 * (last - first), &idxC, 3 * (last - first), &idxI));
  for (PetscInt v = last - 1; v >= first; v--) {
    const PetscBool contact = (PetscBool)(v < (lat.n - 1) * lat.n * lat.n && (v / (lat.n - 1)) % lat.n == 0);

    for (PetscInt c = 0; c < 3; c++) {
      if (contact) idxC[nC++] = 3 * v + c;
      else idxI[nI++] = 3 * v + c;
    }
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, nC, idxC, PETSC_COPY_VALUES, &isC));
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, nI, idxI, PETSC_COPY_VALUES, &isI));
  PetscCall(ISSort(isI));
  PetscCall(PetscFree2(idxC, idxI));

  PetscCall(MatCreateVecs(K, &F, &res));
  {
    PetscInt     lo, hi;
    PetscScalar *fa;

    PetscCall(VecGetOwnershipRange(F, &lo, &hi));
    PetscCall(VecGetArray(F, &fa));
    for (PetscInt i = lo; i < hi; i++) fa[i - lo] = PetscSinReal(0.37 * i) + 0.1;
    PetscCall(VecRestoreArray(F, &fa));
  }

  for (PetscInt t = 0; t < ntypes; t++) {
    SSStarReduction red;
    Mat             Pt;

    PetscCall(SSStarReductionCreate(PETSC_COMM_WORLD, &red));
    PetscCall(SSStarReductionSetType(red, names[t]));
    PetscCall(SSStarReductionSetMemoryLimit(red, limit));
    PetscCall(SSStarReductionSetUp(red, K, isC, isI));
    PetscCall(SSStarReductionGetSchurComplement(red, &Pt));
    PetscCall(MatConvert(Pt, MATDENSE, MAT_INITIAL_MATRIX, &P[t]));
    PetscCall(MatCreateVecs(P[t], &f[t], NULL));
    PetscCall(SSStarReductionReduceLoad(red, F, f[t]));
    /* recovery of the contact displacement uC = f / 10 (any uC will do), with its contact force rC = P uC - f */
    PetscCall(VecDuplicate(f[t], &uC));
    PetscCall(VecDuplicate(f[t], &rC));
    PetscCall(VecCopy(f[t], uC));
    PetscCall(VecScale(uC, 0.1));
    PetscCall(MatMult(P[t], uC, rC));
    PetscCall(VecAXPY(rC, -1.0, f[t]));
    PetscCall(VecDuplicate(F, &u[t]));
    PetscCall(SSStarReductionRecover(red, F, uC, rC, u[t]));
    { /* u solves the interior equations: (K u - F)_I = 0 */
      Vec       resI;
      PetscReal rnorm, fnorm;

      PetscCall(MatMult(K, u[t], res));
      PetscCall(VecAXPY(res, -1.0, F));
      PetscCall(VecGetSubVector(res, isI, &resI));
      PetscCall(VecNorm(resI, NORM_INFINITY, &rnorm));
      PetscCall(VecRestoreSubVector(res, isI, &resI));
      PetscCall(VecNorm(F, NORM_INFINITY, &fnorm));
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: interior residual %.1e\n", names[t], (double)(rnorm / fnorm)));
    }
    PetscCall(VecDestroy(&uC));
    PetscCall(VecDestroy(&rC));
    PetscCall(SSStarReductionDestroy(&red));
  }
  for (PetscInt t = 1; t < ntypes; t++) { /* max differences, relative to the largest entry */
    PetscReal dP, nP, df, nf, du, nu;

    PetscCall(MatNorm(P[0], NORM_MAX, &nP));
    PetscCall(MatAXPY(P[t], -1.0, P[0], SAME_NONZERO_PATTERN));
    PetscCall(MatNorm(P[t], NORM_MAX, &dP));
    PetscCall(VecNorm(f[0], NORM_INFINITY, &nf));
    PetscCall(VecAXPY(f[t], -1.0, f[0]));
    PetscCall(VecNorm(f[t], NORM_INFINITY, &df));
    PetscCall(VecNorm(u[0], NORM_INFINITY, &nu));
    PetscCall(VecAXPY(u[t], -1.0, u[0]));
    PetscCall(VecNorm(u[t], NORM_INFINITY, &du));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s vs %s: P %.1e f %.1e u %.1e\n", names[t], names[0], (double)(dP / nP), (double)(df / nf), (double)(du / nu)));
  }
  for (PetscInt t = 0; t < ntypes; t++) {
    PetscCall(MatDestroy(&P[t]));
    PetscCall(VecDestroy(&f[t]));
    PetscCall(VecDestroy(&u[t]));
    PetscCall(PetscFree(names[t]));
  }
  PetscCall(ISDestroy(&isC));
  PetscCall(ISDestroy(&isI));
  PetscCall(VecDestroy(&F));
  PetscCall(VecDestroy(&res));
  PetscCall(MatDestroy(&K));
  PetscCall(PetscFinalize());
  return 0;
}
