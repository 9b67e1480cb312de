static const char help[] = "Dense LU of an n x n matrix on the ranks of the run: ScaLAPACK (pdgetrf on a 1 x size grid) against LAPACK\n\
(dgetrf) on rank 0 with 1 and with `size` OpenBLAS threads while the other ranks wait without spinning.\n\
  -n <list>          matrix sizes (default 1000,2000,3300,5000)\n\
  -repeat <3>        factorizations per size and method (the median is printed)\n\
  -nb <list>         ScaLAPACK block sizes (default 64)\n\
Run with mpiexec --bind-to none so that rank 0's threads can use the other cores.\n";

#include <petscmat.h>
#include <petscblaslapack.h>
#include <petsc/private/petscscalapack.h>
#include <dlfcn.h>
#include <unistd.h>

/* OpenBLAS's thread count, if the BLAS is OpenBLAS */
static void SetBLASThreads(int n)
{
  void (*set)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  if (set) set(n);
}

/* the other ranks sleep (instead of spinning in MPI) until rank 0 is done */
static PetscErrorCode WaitForRoot(MPI_Comm comm)
{
  MPI_Request req;
  int         done = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Ibarrier(comm, &req));
  while (!done) {
    PetscCallMPI(MPI_Test(&req, &done, MPI_STATUS_IGNORE));
    if (!done) usleep(200);
  }
  PetscFunctionReturn(0);
}

static int CompareReal(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static PetscErrorCode Lapack(MPI_Comm comm, PetscInt n, int threads, PetscRandom rnd, double *t)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Barrier(comm));
  if (rank == 0) {
    PetscScalar  *a;
    PetscBLASInt *piv, bn, info;
    double        t0;

    PetscCall(PetscMalloc2(n * n, &a, n, &piv));
    for (PetscInt k = 0; k < n * n; k++) PetscCall(PetscRandomGetValue(rnd, &a[k]));
    PetscCall(PetscBLASIntCast(n, &bn));
    SetBLASThreads(threads);
    t0 = MPI_Wtime();
    PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, a, &bn, piv, &info));
    *t = MPI_Wtime() - t0;
    SetBLASThreads(1);
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "getrf info %d", (int)info);
    PetscCall(PetscFree2(a, piv));
  }
  PetscCall(WaitForRoot(comm));
  PetscCallMPI(MPI_Bcast(t, 1, MPI_DOUBLE, 0, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode ScaLapack(MPI_Comm comm, PetscInt n, PetscInt nb, PetscRandom rnd, double *t)
{
  Mat            A;
  Mat_ScaLAPACK *a;
  double         t0;

  PetscFunctionBeginUser;
  PetscCall(MatCreateScaLAPACK(comm, nb, nb, n, n, 0, 0, &A));
  a = (Mat_ScaLAPACK *)A->data;
  for (PetscInt k = 0; k < (PetscInt)a->lld * a->locc; k++) PetscCall(PetscRandomGetValue(rnd, &a->loc[k]));
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCallMPI(MPI_Barrier(comm));
  t0 = MPI_Wtime();
  PetscCall(MatLUFactor(A, NULL, NULL, NULL));
  PetscCallMPI(MPI_Barrier(comm));
  *t = MPI_Wtime() - t0;
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscInt    sizes[16] = {1000, 2000, 3300, 5000}, nsizes = 4, nbs[8] = {64}, nnb = 1, repeat = 3;
  PetscMPIInt size;
  PetscRandom rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  {
    PetscInt  n = 16, nb = 8;
    PetscBool set;

    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-n", sizes, &n, &set));
    if (set) nsizes = n;
    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-nb", nbs, &nb, &set)); /* absent: the default 64 */
    if (set) nnb = nb;
  }
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "method,ranks,threads,nb,n,seconds,gflops\n"));
  for (PetscInt s = 0; s < nsizes; s++) {
    const PetscInt n     = sizes[s];
    const double   flops = 2.0 / 3.0 * n * (double)n * n;
    double         t[64];

    for (int threads = 1; threads <= size; threads++) {
      for (PetscInt r = 0; r < repeat; r++) PetscCall(Lapack(PETSC_COMM_WORLD, n, threads, rnd, &t[r]));
      qsort(t, repeat, sizeof(double), CompareReal);
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "lapack_root,%d,%d,0,%" PetscInt_FMT ",%.4f,%.1f\n", size, threads, n, t[repeat / 2], flops / t[repeat / 2] * 1e-9));
    }
    if (size > 1)
      for (PetscInt b = 0; b < nnb; b++) {
        for (PetscInt r = 0; r < repeat; r++) PetscCall(ScaLapack(PETSC_COMM_WORLD, n, nbs[b], rnd, &t[r]));
        qsort(t, repeat, sizeof(double), CompareReal);
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "scalapack,%d,1,%" PetscInt_FMT ",%" PetscInt_FMT ",%.4f,%.1f\n", size, nbs[b], n, t[repeat / 2], flops / t[repeat / 2] * 1e-9));
      }
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscFinalize());
  return 0;
}
