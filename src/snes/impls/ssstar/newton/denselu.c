/*
   The LU engine of the dense Newton step: a dense matrix distributed by rows is gathered on rank 0 and factored by
   LAPACK there (with a condition estimate), while the other ranks sleep so that rank 0's OpenBLAS may use their cores.
   docs/guide/large-problems.md, "Several machines", says why not ScaLAPACK: the dense route runs where this LU takes milliseconds.
*/
#if !defined(_GNU_SOURCE)
  #define _GNU_SOURCE /* sched_getaffinity */
#endif
#include "newtonimpl.h"
#include <petscblaslapack.h>
#include <unistd.h>
#include <dlfcn.h>
#if defined(__linux__)
  #include <sched.h>
#endif

/* LAPACK routines PETSc 3.18 does not declare */
#define SSStarLAPACKgecon_ PETSCBLAS(gecon, GECON)
#define SSStarLAPACKlange_ PETSCBLAS(lange, LANGE)
BLAS_EXTERN void      SSStarLAPACKgecon_(const char *, const PetscBLASInt *, const PetscScalar *, const PetscBLASInt *, const PetscReal *, PetscReal *, PetscScalar *, PetscBLASInt *, PetscBLASInt *);
BLAS_EXTERN PetscReal SSStarLAPACKlange_(const char *, const PetscBLASInt *, const PetscBLASInt *, const PetscScalar *, const PetscBLASInt *, PetscReal *);

PetscErrorCode SSStarDenseLUDestroy(SSStarDenseLU *lu)
{
  PetscFunctionBegin;
  PetscCall(PetscFree2(lu->counts, lu->displs));
  PetscCall(PetscFree(lu->lu));
  PetscCall(PetscFree2(lu->work, lu->pivots));
  lu->capacity = 0;
  lu->N        = -1;
  PetscFunctionReturn(0);
}

/*
   On several ranks, the other ranks of rank 0's node sleep while it factors: its BLAS (OpenBLAS) may use their cores.
   The threads asked for (0: as many cores as rank 0 may run on, mpiexec --bind-to none, at most the ranks of its
   node); 0 = leave the BLAS as it is: on one rank, with 1 asked for, or without OpenBLAS.
*/
PetscErrorCode SSStarDenseLUSetThreads(MPI_Comm comm, PetscInt requested, SSStarDenseLU *lu)
{
  PetscMPIInt size, nodeSize;
  MPI_Comm    node;
  int         cpus = 1;

  PetscFunctionBegin;
  lu->threads = 0;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1 || requested == 1 || !dlsym(RTLD_DEFAULT, "openblas_set_num_threads")) PetscFunctionReturn(0);
  if (requested > 1) {
    lu->threads = (int)requested;
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &nodeSize));
  PetscCallMPI(MPI_Comm_free(&node));
#if defined(__linux__)
  {
    cpu_set_t set;

    if (!sched_getaffinity(0, sizeof(set), &set)) cpus = CPU_COUNT(&set);
  }
#endif
  lu->threads = PetscMin(cpus, nodeSize);
  PetscFunctionReturn(0);
}

/* Sets OpenBLAS's thread count and returns the previous one (0: nothing done) */
static int SetBLASThreads(int threads)
{
  void (*set)(int) = (void (*)(int))dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
  int (*get)(void) = (int (*)(void))dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
  int previous;

  if (!threads || !set || !get) return 0;
  previous = get();
  set(threads);
  return previous;
}

/*
   The other ranks wait for rank 0 without spinning in MPI, so that rank 0 (and its BLAS threads) may use their cores:
   they sleep, 10 us at first and up to 1 ms (waking often takes the core from rank 0 on a loaded machine)
*/
static PetscErrorCode WaitForRankZero(MPI_Comm comm)
{
  MPI_Request req;
  PetscMPIInt rank;
  int         done = 0;
  useconds_t  nap  = 10;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Ibarrier(comm, &req));
  if (rank == 0) {
    PetscCallMPI(MPI_Wait(&req, MPI_STATUS_IGNORE));
    done = 1;
  }
  while (!done) {
    PetscCallMPI(MPI_Test(&req, &done, MPI_STATUS_IGNORE));
    if (!done) usleep(nap);
    nap = PetscMin(2 * nap, 1000);
  }
  PetscFunctionReturn(0);
}

/* Gathers the rows of A (dense, local rows) on rank 0 and factors them there; ok on every rank */
PetscErrorCode SSStarDenseLUFactor(Mat A, SSStarDenseLU *lu, PetscBool *ok)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)A);
  PetscMPIInt        rank, size, nloc;
  PetscInt           N, n, lda;
  const PetscScalar *aa;
  PetscReal          result[2] = {0, -1}; /* info, rcond */

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetSize(A, &N, NULL));
  PetscCall(MatGetLocalSize(A, &n, NULL));
  PetscCall(MatDenseGetLDA(A, &lda));
  PetscCheck(lda == n || n == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Newton matrix with leading dimension %" PetscInt_FMT " != %" PetscInt_FMT " rows", lda, n);
  if (!lu->counts) PetscCall(PetscMalloc2(size, &lu->counts, size + 1, &lu->displs));
  PetscCall(PetscMPIIntCast(n, &nloc));
  PetscCallMPI(MPI_Allgather(&nloc, 1, MPI_INT, lu->counts, 1, MPI_INT, comm));
  lu->displs[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) lu->displs[r + 1] = lu->displs[r] + lu->counts[r];
  if (rank == 0 && (size_t)N * N > lu->capacity) {
    PetscCall(PetscFree(lu->lu));
    PetscCall(PetscMalloc1((size_t)N * N, &lu->lu));
    lu->capacity = (size_t)N * N;
  }
  if (rank == 0 && N != lu->N) {
    PetscCall(PetscFree2(lu->work, lu->pivots));
    PetscCall(PetscMalloc2(PetscMax(4 * N, 1), &lu->work, PetscMax(N, 1), &lu->pivots));
  }
  lu->N = N;
  PetscCall(MatDenseGetArrayRead(A, &aa));
  if (rank == 0) {
    MPI_Request *reqs;
    MPI_Datatype *types;
    PetscBLASInt  bn, info, *iwork;
    PetscReal     anorm;

    PetscCall(PetscMalloc2(size, &reqs, size, &types));
    for (PetscMPIInt r = 1; r < size; r++) {
      reqs[r] = MPI_REQUEST_NULL;
      if (!lu->counts[r]) continue;
      PetscCallMPI(MPI_Type_vector((PetscMPIInt)N, lu->counts[r], (PetscMPIInt)N, MPIU_SCALAR, &types[r]));
      PetscCallMPI(MPI_Type_commit(&types[r]));
      PetscCallMPI(MPI_Irecv(lu->lu + lu->displs[r], 1, types[r], r, 0, comm, &reqs[r]));
    }
    for (PetscInt c = 0; c < N; c++) PetscCall(PetscArraycpy(lu->lu + c * N, aa + c * n, n));
    if (size > 1) PetscCallMPI(MPI_Waitall(size - 1, reqs + 1, MPI_STATUSES_IGNORE));
    for (PetscMPIInt r = 1; r < size; r++)
      if (lu->counts[r]) PetscCallMPI(MPI_Type_free(&types[r]));
    PetscCall(PetscFree2(reqs, types));

    PetscCall(PetscBLASIntCast(N, &bn));
    if (N > 0) {
      PetscCall(PetscMalloc1(N, &iwork));
      anorm = SSStarLAPACKlange_("1", &bn, &bn, lu->lu, &bn, (PetscReal *)lu->work);
      const int previous = SetBLASThreads(lu->threads);

      PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, lu->lu, &bn, lu->pivots, &info));
      SetBLASThreads(previous);
      result[0] = info;
      if (!info) {
        PetscCallBLAS("LAPACKgecon", SSStarLAPACKgecon_("1", &bn, lu->lu, &bn, &anorm, &result[1], lu->work, iwork, &info));
        PetscCall(PetscLogFlops(2.0 / 3.0 * N * (double)N * N));
      }
      PetscCall(PetscFree(iwork));
    } else result[1] = 1;
  } else if (nloc) PetscCallMPI(MPI_Send(aa, nloc * (PetscMPIInt)N, MPIU_SCALAR, 0, 0, comm));
  PetscCall(MatDenseRestoreArrayRead(A, &aa));
  if (size > 1) PetscCall(WaitForRankZero(comm));
  PetscCallMPI(MPI_Bcast(result, 2, MPIU_REAL, 0, comm));
  *ok       = (PetscBool)(result[0] == 0);
  lu->rcond = result[1];
  PetscFunctionReturn(0);
}

/* x = A^-1 b by the factors of DenseLUFactor; b and x in the row layout of the factored A */
PetscErrorCode SSStarDenseLUSolve(MPI_Comm comm, SSStarDenseLU *lu, Vec b, Vec x)
{
  PetscMPIInt        rank, nloc;
  PetscInt           n;
  const PetscScalar *ba;
  PetscScalar       *xa;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecGetLocalSize(b, &n));
  PetscCall(PetscMPIIntCast(n, &nloc));
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCallMPI(MPI_Gatherv(ba, nloc, MPIU_SCALAR, lu->work, lu->counts, lu->displs, MPIU_SCALAR, 0, comm));
  PetscCall(VecRestoreArrayRead(b, &ba));
  if (rank == 0 && lu->N > 0) {
    PetscBLASInt bn, one = 1, info;

    PetscCall(PetscBLASIntCast(lu->N, &bn));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, lu->lu, &bn, lu->pivots, lu->work, &bn, &info));
    PetscCall(PetscLogFlops(2.0 * lu->N * (double)lu->N));
  }
  PetscCall(VecGetArrayWrite(x, &xa));
  PetscCallMPI(MPI_Scatterv(lu->work, lu->counts, lu->displs, MPIU_SCALAR, xa, nloc, MPIU_SCALAR, 0, comm));
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscFunctionReturn(0);
}

