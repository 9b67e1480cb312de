static const char help[] = "Solves a problem of the FCLib collection (HDF5) by the semismooth* Newton method (SNES type ssstar).\n\
Usage: examples/fclib FILE.hdf5 [-o solution.h5] [options]\n\
  FILE.hdf5                  an FCLib problem: local (/fclib_local: u = W r + q, mu) or global (/fclib_global: M v = H r + f,\n\
                             u = H^T v + w, mu; condensed to W = H^T M^-1 H, q = H^T M^-1 f + w). W must be nonsingular with a\n\
                             positive definite symmetric part: ssstar solves 0 in P u - f + Q(u) with P = W^-1 and f = P q\n\
  -o <solution.h5>           write the problem and FCLib's group /solution (r, u, and v for a global problem; normal first)\n\
  -summary_header <true>     print the header line of the summary\n\
The summary gives the FCLib error (natural map with De Saxce's modified velocity, relative to ||q||), the solver's\n\
||z|| relative to its displacement scale and the worst Coulomb-law violation. An option nothing reads is refused before\n\
any work. Exit status 0 when the solve converged, 2 when it did not (the -o file says so: attributes converged_reason,\n\
residual_norm (||z||), iterations of \"/\"), PETSc's error code for bad input (one\n\
line naming the option or file; -ssstar_traceback adds PETSc's report). -help lists the options and does nothing else.\n";

/*
   FCLib problem files (format of FrictionalContactLibrary/fclib, src/fclib.h): per contact a 3-block with the normal
   component first, u = W r + q and the Coulomb law between the local velocity u and the force r. ssstar's reduced
   form r = P u - f with blocks (t1, t2, n) is the same problem with P = W^-1, f = P q, each block reordered.
   Every rank reads the (small) file and condenses/inverts W itself; the solve is distributed over the ranks, with
   whole contacts on each rank. Starting point u = 0 (docs/derivation.md section 7); /guesses in a file are not used.
*/
#include <ssstar.h>
#include <ssstarscene.h>
#include <petscblaslapack.h>
#include <petsctime.h>
#include <hdf5.h>
#include <sys/stat.h>

#if !defined(PETSC_USE_REAL_DOUBLE)
  #error "examples/fclib reads FCLib's doubles into PetscReal: it needs a PETSc with double precision"
#endif
#if defined(PETSC_USE_64BIT_INDICES)
  #define FCLIB_H5_PETSCINT H5T_NATIVE_INT64
#else
  #define FCLIB_H5_PETSCINT H5T_NATIVE_INT32
#endif

typedef struct {
  const char *file;
  PetscBool   global;             /* /fclib_global (M, H, f, w) or /fclib_local (W, q)               */
  PetscInt    nc;                 /* contacts: W is 3 nc x 3 nc                                      */
  Mat         W;                  /* dense, FCLib's order (n, t1, t2) in each block                  */
  Vec         q;                  /* 3 nc                                                            */
  PetscReal  *mu;                 /* nc                                                              */
  Mat         M, Mlu, H;          /* global problems: M (AIJ), its LU factor, H (dense, dofs x 3 nc) */
  Vec         f;                  /* global problems: the load of M v = H r + f                      */
  PetscReal   condition, asymmetry; /* of W: sigma_max/sigma_min, max|W - W^T|/max|W|               */
} FCLibProblem;

/* Our row i (t1, t2, n per block) is FCLib's row FCLibIndex(i) ((n, t1, t2) per block) */
static inline PetscInt FCLibIndex(PetscInt i)
{
  return 3 * (i / 3) + (i % 3 + 1) % 3;
}

/* H5Lexists on every prefix of path, as H5Lexists fails on a missing intermediate group */
static PetscBool H5PathExists(hid_t fid, const char path[])
{
  char buf[PETSC_MAX_PATH_LEN];

  for (size_t k = 1; path[k - 1]; k++) {
    if (path[k] != '/' && path[k] != 0) continue;
    if (k >= sizeof(buf)) return PETSC_FALSE;
    memcpy(buf, path, k);
    buf[k] = 0;
    if (H5Lexists(fid, buf, H5P_DEFAULT) <= 0) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* The whole dataset path, converted to memtype (elements of size bytes), in a new array of *n entries */
static PetscErrorCode ReadDataset(MPI_Comm comm, hid_t fid, const char file[], const char path[], hid_t memtype, size_t size, PetscInt *n, void **data)
{
  hid_t    dset, space;
  hssize_t npoints;
  herr_t   status;

  PetscFunctionBeginUser;
  PetscCheck(H5PathExists(fid, path), comm, PETSC_ERR_FILE_UNEXPECTED, "%s: no dataset %s", file, path);
  dset = H5Dopen2(fid, path, H5P_DEFAULT);
  PetscCheck(dset >= 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s is not a dataset", file, path);
  space   = H5Dget_space(dset);
  npoints = H5Sget_simple_extent_npoints(space);
  H5Sclose(space);
  PetscCheck(npoints >= 0, comm, PETSC_ERR_FILE_READ, "%s: cannot read the size of %s", file, path);
  *n = (PetscInt)npoints;
  PetscCall(PetscMalloc(PetscMax(npoints, 1) * size, data));
  status = H5Dread(dset, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, *data);
  H5Dclose(dset);
  PetscCheck(status >= 0, comm, PETSC_ERR_FILE_READ, "%s: cannot read %s as numbers", file, path);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadInts(MPI_Comm comm, hid_t fid, const char file[], const char path[], PetscInt *n, PetscInt **x)
{
  PetscFunctionBeginUser;
  PetscCall(ReadDataset(comm, fid, file, path, FCLIB_H5_PETSCINT, sizeof(PetscInt), n, (void **)x));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadInt(MPI_Comm comm, hid_t fid, const char file[], const char path[], PetscInt *value)
{
  PetscInt n, *x;

  PetscFunctionBeginUser;
  PetscCall(ReadInts(comm, fid, file, path, &n, &x));
  PetscCheck(n == 1, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has %" PetscInt_FMT " entries, expected one number", file, path, n);
  *value = x[0];
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}

/* A real dataset of exactly n entries */
static PetscErrorCode ReadReals(MPI_Comm comm, hid_t fid, const char file[], const char path[], PetscInt n, PetscReal **x)
{
  PetscInt len;

  PetscFunctionBeginUser;
  PetscCall(ReadDataset(comm, fid, file, path, H5T_NATIVE_DOUBLE, sizeof(PetscReal), &len, (void **)x));
  PetscCheck(len == n, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s has %" PetscInt_FMT " entries, expected %" PetscInt_FMT, file, path, len, n);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadVec(MPI_Comm comm, hid_t fid, const char file[], const char path[], PetscInt n, Vec *v)
{
  PetscReal *x;

  PetscFunctionBeginUser;
  PetscCall(ReadReals(comm, fid, file, path, n, &x));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, v));
  for (PetscInt i = 0; i < n; i++) PetscCall(VecSetValue(*v, i, x[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(*v));
  PetscCall(VecAssemblyEnd(*v));
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}

/*
   An FCLib sparse matrix (group with m, n, nz, nzmax, p, i, x) as a sequential AIJ matrix. nz = -2: compressed rows
   (p row pointers, i column indices); nz = -1: compressed columns; nz >= 0: nz triplets with i the row and p the column
   indices, as Siconos (CSparse) writes them. Repeated entries are added.
*/
static PetscErrorCode ReadSparseMatrix(MPI_Comm comm, hid_t fid, const char file[], const char group[], Mat *A)
{
  char       path[PETSC_MAX_PATH_LEN];
  PetscInt   m, n, nz, np, ni, nx, nnz, *p, *idx, *row, *col, *perRow;
  PetscReal *x;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/m", group));
  PetscCall(ReadInt(comm, fid, file, path, &m));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/n", group));
  PetscCall(ReadInt(comm, fid, file, path, &n));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/nz", group));
  PetscCall(ReadInt(comm, fid, file, path, &nz));
  PetscCheck(m > 0 && n > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s is %" PetscInt_FMT " x %" PetscInt_FMT, file, group, m, n);
  PetscCheck(nz >= -2, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s/nz = %" PetscInt_FMT " is no FCLib storage (-2 rows, -1 columns, >= 0 triplets)", file, group, nz);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/p", group));
  PetscCall(ReadInts(comm, fid, file, path, &np, &p));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/i", group));
  PetscCall(ReadInts(comm, fid, file, path, &ni, &idx));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/x", group));
  PetscCall(ReadDataset(comm, fid, file, path, H5T_NATIVE_DOUBLE, sizeof(PetscReal), &nx, (void **)&x));
  if (nz < 0) {
    const PetscInt nptr = nz == -2 ? m : n;

    PetscCheck(np == nptr + 1, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s/p has %" PetscInt_FMT " entries, expected %" PetscInt_FMT " pointers", file, group, np, nptr + 1);
    for (PetscInt k = 0; k < nptr; k++) PetscCheck(p[k] >= 0 && p[k] <= p[k + 1], comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s/p is not a nondecreasing list of pointers (entry %" PetscInt_FMT ")", file, group, k);
    nnz = p[nptr];
  } else nnz = nz;
  PetscCheck(ni >= nnz && nx >= nnz && (nz < 0 || np >= nnz), comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s holds fewer than its %" PetscInt_FMT " entries", file, group, nnz);
  PetscCall(PetscMalloc2(nnz, &row, nnz, &col));
  if (nz >= 0) {
    PetscCall(PetscArraycpy(row, idx, nnz));
    PetscCall(PetscArraycpy(col, p, nnz));
  } else {
    for (PetscInt c = 0; c < (nz == -2 ? m : n); c++)
      for (PetscInt k = p[c]; k < p[c + 1]; k++) {
        row[k] = nz == -2 ? c : idx[k];
        col[k] = nz == -2 ? idx[k] : c;
      }
  }
  PetscCall(PetscCalloc1(m, &perRow));
  for (PetscInt k = 0; k < nnz; k++) {
    PetscCheck(row[k] >= 0 && row[k] < m && col[k] >= 0 && col[k] < n, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: entry %" PetscInt_FMT " of %s is (%" PetscInt_FMT ", %" PetscInt_FMT "), outside the %" PetscInt_FMT " x %" PetscInt_FMT " matrix", file, k, group, row[k], col[k], m, n);
    perRow[row[k]]++;
  }
  for (PetscInt i = 0; i < m; i++) perRow[i] = PetscMin(perRow[i], n);
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, m, n, 0, perRow, A));
  for (PetscInt k = 0; k < nnz; k++) PetscCall(MatSetValue(*A, row[k], col[k], x[k], ADD_VALUES));
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(perRow));
  PetscCall(PetscFree2(row, col));
  PetscCall(PetscFree(p));
  PetscCall(PetscFree(idx));
  PetscCall(PetscFree(x));
  PetscFunctionReturn(0);
}

/* Friction coefficients: nc finite values >= 0 */
static PetscErrorCode ReadFriction(MPI_Comm comm, hid_t fid, FCLibProblem *pb, const char path[])
{
  PetscFunctionBeginUser;
  PetscCall(ReadReals(comm, fid, pb->file, path, pb->nc, &pb->mu));
  for (PetscInt c = 0; c < pb->nc; c++) PetscCheck(!PetscIsInfOrNanReal(pb->mu[c]) && pb->mu[c] >= 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %s[%" PetscInt_FMT "] = %g is not a friction coefficient >= 0", pb->file, path, c, (double)pb->mu[c]);
  PetscFunctionReturn(0);
}

/* W = H^T M^-1 H, q = H^T M^-1 f + w by an LU factorization of M (MUMPS; M as stored, it need not be symmetric) */
static PetscErrorCode Condense(MPI_Comm comm, FCLibProblem *pb, Vec w)
{
  MatFactorInfo      info;
  MatFactorError     err;
  PetscInt           n, m;
  Mat                X;
  Vec                y;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(pb->H, &n, &m));
  PetscCall(MatGetFactor(pb->M, MATSOLVERMUMPS, MAT_FACTOR_LU, &pb->Mlu));
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatLUFactorSymbolic(pb->Mlu, pb->M, NULL, NULL, &info));
  PetscCall(MatLUFactorNumeric(pb->Mlu, pb->M, &info));
  PetscCall(MatFactorGetError(pb->Mlu, &err));
  PetscCheck(!err, comm, PETSC_ERR_MAT_LU_ZRPVT, "%s: the LU factorization of /fclib_global/M failed (%s): M is singular", pb->file, err == MAT_FACTOR_OUTMEMORY ? "out of memory" : "zero pivot");
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, m, NULL, &X));
  PetscCall(MatMatSolve(pb->Mlu, pb->H, X));
  PetscCall(MatTransposeMatMult(pb->H, X, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &pb->W));
  PetscCall(VecDuplicate(pb->f, &y));
  PetscCall(MatSolve(pb->Mlu, pb->f, y));
  PetscCall(VecDuplicate(w, &pb->q));
  PetscCall(MatMultTranspose(pb->H, y, pb->q));
  PetscCall(VecAXPY(pb->q, 1.0, w));
  PetscCall(VecDestroy(&y));
  PetscCall(MatDestroy(&X));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadSpaceDimension(MPI_Comm comm, hid_t fid, const char file[], const char group[])
{
  char     path[PETSC_MAX_PATH_LEN];
  PetscInt d;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/spacedim", group));
  PetscCall(ReadInt(comm, fid, file, path, &d));
  PetscCheck(d == 3, comm, PETSC_ERR_SUP, "%s: %s = %" PetscInt_FMT "; ssstar solves 3D contact (spacedim 3)", file, path, d);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadLocalProblem(MPI_Comm comm, hid_t fid, FCLibProblem *pb)
{
  PetscInt m, n;
  Mat      Wsparse;

  PetscFunctionBeginUser;
  PetscCheck(!H5PathExists(fid, "/fclib_local/V") && !H5PathExists(fid, "/fclib_local/R"), comm, PETSC_ERR_SUP, "%s: equality constraints (/fclib_local/V, R) are not supported", pb->file);
  PetscCall(ReadSpaceDimension(comm, fid, pb->file, "/fclib_local"));
  PetscCall(ReadSparseMatrix(comm, fid, pb->file, "/fclib_local/W", &Wsparse));
  PetscCall(MatGetSize(Wsparse, &m, &n));
  PetscCheck(m == n && m % 3 == 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: /fclib_local/W is %" PetscInt_FMT " x %" PetscInt_FMT ", expected square with 3 rows per contact", pb->file, m, n);
  pb->nc = m / 3;
  PetscCall(MatConvert(Wsparse, MATSEQDENSE, MAT_INITIAL_MATRIX, &pb->W));
  PetscCall(MatDestroy(&Wsparse));
  PetscCall(ReadVec(comm, fid, pb->file, "/fclib_local/vectors/q", m, &pb->q));
  PetscCall(ReadFriction(comm, fid, pb, "/fclib_local/vectors/mu"));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadGlobalProblem(MPI_Comm comm, hid_t fid, FCLibProblem *pb)
{
  PetscInt n, nM, m, nH;
  Mat      Hsparse;
  Vec      w;

  PetscFunctionBeginUser;
  PetscCheck(!H5PathExists(fid, "/fclib_global/G"), comm, PETSC_ERR_SUP, "%s: equality constraints (/fclib_global/G, b) are not supported", pb->file);
  PetscCall(ReadSpaceDimension(comm, fid, pb->file, "/fclib_global"));
  PetscCall(ReadSparseMatrix(comm, fid, pb->file, "/fclib_global/M", &pb->M));
  PetscCall(ReadSparseMatrix(comm, fid, pb->file, "/fclib_global/H", &Hsparse));
  PetscCall(MatGetSize(pb->M, &n, &nM));
  PetscCall(MatGetSize(Hsparse, &nH, &m));
  PetscCheck(n == nM && nH == n && m % 3 == 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: /fclib_global/M is %" PetscInt_FMT " x %" PetscInt_FMT " and H %" PetscInt_FMT " x %" PetscInt_FMT "; expected M square and H with as many rows and 3 columns per contact", pb->file, n, nM, nH, m);
  pb->nc = m / 3;
  PetscCall(MatConvert(Hsparse, MATSEQDENSE, MAT_INITIAL_MATRIX, &pb->H));
  PetscCall(MatDestroy(&Hsparse));
  PetscCall(ReadVec(comm, fid, pb->file, "/fclib_global/vectors/f", n, &pb->f));
  PetscCall(ReadVec(comm, fid, pb->file, "/fclib_global/vectors/w", m, &w));
  PetscCall(ReadFriction(comm, fid, pb, "/fclib_global/vectors/mu"));
  PetscCall(Condense(comm, pb, w));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* Reads an FCLib problem (every rank reads the whole file); a global one is condensed to W, q */
static PetscErrorCode FCLibRead(MPI_Comm comm, const char file[], FCLibProblem *pb)
{
  PetscBool readable;
  htri_t    ishdf5;
  hid_t     fid;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(pb, sizeof(*pb)));
  pb->file = file;
  PetscCall(PetscTestFile(file, 'r', &readable));
  PetscCheck(readable, comm, PETSC_ERR_FILE_OPEN, "Cannot read the FCLib problem %s: no such readable file", file);
  ishdf5 = H5Fis_hdf5(file);
  PetscCheck(ishdf5 > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s is not an HDF5 file, so no FCLib problem", file);
  fid = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(fid >= 0, comm, PETSC_ERR_FILE_OPEN, "Cannot open the HDF5 file %s", file);
  pb->global = H5PathExists(fid, "/fclib_global");
  PetscCheck(pb->global || H5PathExists(fid, "/fclib_local"), comm, PETSC_ERR_FILE_UNEXPECTED, "%s is not an FCLib problem: it has neither /fclib_local nor /fclib_global", file);
  if (pb->global) PetscCall(ReadGlobalProblem(comm, fid, pb));
  else PetscCall(ReadLocalProblem(comm, fid, pb));
  H5Fclose(fid);
  PetscFunctionReturn(0);
}

static PetscErrorCode FCLibDestroy(FCLibProblem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&pb->W));
  PetscCall(VecDestroy(&pb->q));
  PetscCall(PetscFree(pb->mu));
  PetscCall(MatDestroy(&pb->M));
  PetscCall(MatDestroy(&pb->Mlu));
  PetscCall(MatDestroy(&pb->H));
  PetscCall(VecDestroy(&pb->f));
  PetscFunctionReturn(0);
}

/*
   P = W^-1 by LAPACK (getrf, getri) after two checks that refuse what ssstar cannot solve: W singular (numerical rank
   below N by its singular values, the rank rule of LAPACK and numpy: sigma_i > N eps sigma_max) and a symmetric part
   (W + W^T)/2 that is not positive definite (Cholesky, potrf).
*/
static PetscErrorCode InvertW(MPI_Comm comm, FCLibProblem *pb, Mat *P)
{
  const PetscScalar *w;
  PetscScalar       *a, *pa, *work, lworkOpt;
  PetscReal         *sigma, wmax = 0, amax = 0;
  PetscInt           N = 3 * pb->nc, lda, rank = 0;
  PetscBLASInt       bn, lwork = -1, info, one = 1, *pivots;

  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(N, &bn));
  PetscCall(MatDenseGetLDA(pb->W, &lda));
  PetscCall(MatDenseGetArrayRead(pb->W, &w));
  PetscCall(PetscMalloc2(N * N, &a, N, &sigma));
  for (PetscInt j = 0; j < N; j++)
    for (PetscInt i = 0; i < N; i++) {
      a[i + j * N] = w[i + j * lda];
      wmax         = PetscMax(wmax, PetscAbsScalar(w[i + j * lda]));
      amax         = PetscMax(amax, PetscAbsScalar(w[i + j * lda] - w[j + i * lda]));
    }
  pb->asymmetry = wmax > 0 ? amax / wmax : 0;

  PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("N", "N", &bn, &bn, a, &bn, sigma, NULL, &one, NULL, &one, &lworkOpt, &lwork, &info));
  lwork = (PetscBLASInt)PetscRealPart(lworkOpt);
  PetscCall(PetscMalloc1(lwork, &work));
  PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("N", "N", &bn, &bn, a, &bn, sigma, NULL, &one, NULL, &one, work, &lwork, &info));
  PetscCall(PetscFree(work));
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "%s: the singular values of W did not converge (LAPACK gesvd info %d)", pb->file, (int)info);
  for (PetscInt i = 0; i < N; i++) rank += sigma[i] > N * PETSC_MACHINE_EPSILON * sigma[0];
  pb->condition = sigma[N - 1] > 0 ? sigma[0] / sigma[N - 1] : PETSC_INFINITY;
  PetscCheck(rank == N, comm, PETSC_ERR_SUP, "%s: W is singular: numerical rank %" PetscInt_FMT " of %" PetscInt_FMT " (condition number %.3g). ssstar solves r = P u - f with P = W^-1 and cannot take a singular W (as in rigid-body problems with more contact dofs than body dofs)", pb->file, rank, N, (double)pb->condition);

  for (PetscInt j = 0; j < N; j++)
    for (PetscInt i = 0; i < N; i++) a[i + j * N] = 0.5 * (w[i + j * lda] + w[j + i * lda]);
  PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("L", &bn, a, &bn, &info));
  PetscCheck(info <= 0, comm, PETSC_ERR_SUP, "%s: W is not positive definite: the Cholesky factorization of its symmetric part (W + W^T)/2 fails at row %d (contact %d); ssstar needs P = W^-1 with a positive definite symmetric part", pb->file, (int)info - 1, ((int)info - 1) / 3);

  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, N, N, NULL, P));
  PetscCall(MatDenseGetArray(*P, &pa));
  for (PetscInt j = 0; j < N; j++)
    for (PetscInt i = 0; i < N; i++) pa[i + j * N] = w[i + j * lda];
  PetscCall(MatDenseRestoreArrayRead(pb->W, &w));
  PetscCall(PetscMalloc1(N, &pivots));
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, pa, &bn, pivots, &info));
  PetscCheck(!info, comm, PETSC_ERR_MAT_LU_ZRPVT, "%s: the LU factorization of W failed (LAPACK getrf info %d)", pb->file, (int)info);
  lwork = -1;
  PetscCallBLAS("LAPACKgetri", LAPACKgetri_(&bn, pa, &bn, pivots, &lworkOpt, &lwork, &info));
  lwork = (PetscBLASInt)PetscRealPart(lworkOpt);
  PetscCall(PetscMalloc1(lwork, &work));
  PetscCallBLAS("LAPACKgetri", LAPACKgetri_(&bn, pa, &bn, pivots, work, &lwork, &info));
  PetscCheck(!info, comm, PETSC_ERR_MAT_LU_ZRPVT, "%s: the inversion of W failed (LAPACK getri info %d)", pb->file, (int)info);
  PetscCall(PetscFree(work));
  PetscCall(PetscFree(pivots));
  PetscCall(MatDenseRestoreArray(*P, &pa));
  PetscCall(PetscFree2(a, sigma));
  PetscFunctionReturn(0);
}

/* ssstar's reduced problem on comm, whole contacts per rank: P and f = P q with blocks (t1, t2, n), one mu per contact */
static PetscErrorCode CreateContactProblem(MPI_Comm comm, const FCLibProblem *pb, Mat Pfc, Mat *P, Vec *f, Vec *mu)
{
  PetscInt           nloc = PETSC_DECIDE, nc = pb->nc, N = 3 * pb->nc, lo, hi, *cols;
  const PetscScalar *pa, *fa;
  PetscScalar       *row;
  Vec                Pq;

  PetscFunctionBeginUser;
  PetscCall(PetscSplitOwnership(comm, &nloc, &nc));
  PetscCall(MatCreateDense(comm, 3 * nloc, 3 * nloc, N, N, NULL, P));
  PetscCall(MatGetOwnershipRange(*P, &lo, &hi));
  PetscCall(PetscMalloc2(N, &cols, N, &row));
  for (PetscInt j = 0; j < N; j++) cols[j] = j;
  PetscCall(MatDenseGetArrayRead(Pfc, &pa));
  for (PetscInt i = lo; i < hi; i++) {
    for (PetscInt j = 0; j < N; j++) row[j] = pa[FCLibIndex(i) + FCLibIndex(j) * N];
    PetscCall(MatSetValues(*P, 1, &i, N, cols, row, INSERT_VALUES));
  }
  PetscCall(MatDenseRestoreArrayRead(Pfc, &pa));
  PetscCall(MatAssemblyBegin(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree2(cols, row));

  PetscCall(VecDuplicate(pb->q, &Pq));
  PetscCall(MatMult(Pfc, pb->q, Pq));
  PetscCall(MatCreateVecs(*P, NULL, f));
  PetscCall(VecGetArrayRead(Pq, &fa));
  for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(*f, i, fa[FCLibIndex(i)], INSERT_VALUES));
  PetscCall(VecRestoreArrayRead(Pq, &fa));
  PetscCall(VecAssemblyBegin(*f));
  PetscCall(VecAssemblyEnd(*f));
  PetscCall(VecDestroy(&Pq));

  PetscCall(VecCreateMPI(comm, nloc, pb->nc, mu));
  for (PetscInt c = lo / 3; c < hi / 3; c++) PetscCall(VecSetValue(*mu, c, pb->mu[c], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(*mu));
  PetscCall(VecAssemblyEnd(*mu));
  PetscFunctionReturn(0);
}

/* The distributed x (blocks (t1, t2, n)) on every rank, in FCLib's order (n, t1, t2) */
static PetscErrorCode GatherFCLibOrder(Vec x, Vec *xfc)
{
  VecScatter         toAll;
  Vec                all;
  const PetscScalar *a;
  PetscScalar       *b;
  PetscInt           N;

  PetscFunctionBeginUser;
  PetscCall(VecScatterCreateToAll(x, &toAll, &all));
  PetscCall(VecScatterBegin(toAll, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(toAll, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecDuplicate(all, xfc));
  PetscCall(VecGetSize(all, &N));
  PetscCall(VecGetArrayRead(all, &a));
  PetscCall(VecGetArrayWrite(*xfc, &b));
  for (PetscInt i = 0; i < N; i++) b[FCLibIndex(i)] = a[i];
  PetscCall(VecRestoreArrayWrite(*xfc, &b));
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecDestroy(&all));
  PetscCall(VecScatterDestroy(&toAll));
  PetscFunctionReturn(0);
}

/* Projection on the Coulomb cone {|x_t| <= mu x_n} of x = (x_n, x_t1, x_t2) (Siconos's projectionOnCone) */
static void ProjectOnCone(PetscReal x[3], PetscReal mu)
{
  const PetscReal xt = PetscHypotReal(x[1], x[2]);

  if (mu * xt <= -x[0]) x[0] = x[1] = x[2] = 0; /* in the polar cone */
  else if (xt > mu * x[0]) {
    x[0] = (mu * xt + x[0]) / (mu * mu + 1);
    x[1] *= mu * x[0] / xt;
    x[2] *= mu * x[0] / xt;
  }
}

/*
   FCLib's error measure, as Siconos numerics computes it (fc3d_compute_error.c, called by its solvers with
   norm = ||q||; the natural map is that of FCLib's own fclib_merit_local, MERIT_1): with u = W r + q and De Saxce's
   modified velocity u^ = u + mu |u_t| e_n, per contact F = r - proj_C(r - u^), and error = ||F|| / ||q|| (||F|| when
   ||q|| <= eps). fclib_merit_local divides by 1 + sqrt(||q||) and older Siconos by 1 + ||q||: nearly absolute
   measures when ||q|| << 1, as in the FEM problems (||q|| from 6e-12 to 0.18), so the relative one is reported.
*/
static PetscErrorCode FCLibError(const FCLibProblem *pb, Vec r, PetscReal *error)
{
  Vec                u;
  const PetscScalar *ra, *ua;
  PetscReal          sum = 0, qnorm;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(pb->q, &u));
  PetscCall(MatMult(pb->W, r, u));
  PetscCall(VecAXPY(u, 1.0, pb->q));
  PetscCall(VecGetArrayRead(r, &ra));
  PetscCall(VecGetArrayRead(u, &ua));
  for (PetscInt c = 0; c < pb->nc; c++) {
    const PetscScalar *rc = &ra[3 * c], *uc = &ua[3 * c];
    PetscReal          x[3];

    x[0] = rc[0] - (uc[0] + pb->mu[c] * PetscHypotReal(uc[1], uc[2]));
    x[1] = rc[1] - uc[1];
    x[2] = rc[2] - uc[2];
    ProjectOnCone(x, pb->mu[c]);
    for (PetscInt k = 0; k < 3; k++) sum += PetscSqr(rc[k] - x[k]);
  }
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(VecDestroy(&u));
  PetscCall(VecNorm(pb->q, NORM_2, &qnorm));
  *error = qnorm > PETSC_MACHINE_EPSILON ? PetscSqrtReal(sum) / qnorm : PetscSqrtReal(sum);
  PetscFunctionReturn(0);
}

/*
   The worst violation of the Coulomb law over the contacts (FCLib order), relative to max|u| and max|r| as
   tests/check_solution.py measures it: u_n >= 0, r_n >= 0, u_n r_n = 0, |r_t| <= mu r_n, and the sliding rule
   r_t = -mu r_n u_t/|u_t| multiplied by |u_t| (r_t |u_t| + mu r_n u_t = 0, which needs no threshold on |u_t|).
*/
static PetscErrorCode CoulombViolation(const FCLibProblem *pb, Vec u, Vec r, PetscReal *violation)
{
  const PetscScalar *ua, *ra;
  PetscReal          umax, rmax, worst = 0;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(u, NORM_INFINITY, &umax));
  PetscCall(VecNorm(r, NORM_INFINITY, &rmax));
  umax = umax > 0 ? umax : 1; /* u = 0: the terms in u vanish */
  rmax = rmax > 0 ? rmax : 1;
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(r, &ra));
  for (PetscInt c = 0; c < pb->nc; c++) {
    const PetscScalar *uc = &ua[3 * c], *rc = &ra[3 * c];
    const PetscReal    ut = PetscHypotReal(uc[1], uc[2]), rt = PetscHypotReal(rc[1], rc[2]), mu = pb->mu[c];
    const PetscReal    slip = PetscHypotReal(rc[1] * ut + mu * rc[0] * uc[1], rc[2] * ut + mu * rc[0] * uc[2]);

    worst = PetscMax(worst, -uc[0] / umax);
    worst = PetscMax(worst, -rc[0] / rmax);
    worst = PetscMax(worst, PetscAbsReal(uc[0] * rc[0]) / (umax * rmax));
    worst = PetscMax(worst, (rt - mu * rc[0]) / rmax);
    worst = PetscMax(worst, slip / (umax * rmax));
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(VecRestoreArrayRead(u, &ua));
  *violation = worst;
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteDataset(const char out[], hid_t group, const char name[], Vec x)
{
  const PetscScalar *xa;
  PetscInt           n;
  hsize_t            dim;
  hid_t              space, dset;
  herr_t             status;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(x, &n));
  dim   = (hsize_t)n;
  space = H5Screate_simple(1, &dim, NULL);
  dset  = H5Dcreate2(group, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Sclose(space);
  PetscCheck(dset >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot create /solution/%s in %s", name, out);
  PetscCall(VecGetArrayRead(x, &xa));
  status = H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, xa);
  PetscCall(VecRestoreArrayRead(x, &xa));
  H5Dclose(dset);
  PetscCheck(status >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write /solution/%s to %s", name, out);
  PetscFunctionReturn(0);
}

/* How the solve ended, as attributes of "/" (those of SSStarWriteOutcome()) */
static PetscErrorCode WriteOutcome(const char out[], hid_t fout, const char reason[], PetscReal znorm, PetscInt its)
{
  const double norm = (double)znorm;
  const int    iterations = (int)its;
  hid_t        space, type, attr;
  herr_t       status;

  PetscFunctionBeginUser;
  space  = H5Screate(H5S_SCALAR);
  type   = H5Tcopy(H5T_C_S1);
  status = H5Tset_size(type, strlen(reason) + 1);
  attr   = H5Acreate2(fout, "converged_reason", type, space, H5P_DEFAULT, H5P_DEFAULT);
  status = attr < 0 || status < 0 ? -1 : H5Awrite(attr, type, reason);
  if (attr >= 0) H5Aclose(attr);
  H5Tclose(type);
  PetscCheck(status >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write the attribute converged_reason of %s", out);
  attr   = H5Acreate2(fout, "residual_norm", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  status = attr < 0 ? -1 : H5Awrite(attr, H5T_NATIVE_DOUBLE, &norm);
  if (attr >= 0) H5Aclose(attr);
  PetscCheck(status >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write the attribute residual_norm of %s", out);
  attr   = H5Acreate2(fout, "iterations", H5T_NATIVE_INT, space, H5P_DEFAULT, H5P_DEFAULT);
  status = attr < 0 ? -1 : H5Awrite(attr, H5T_NATIVE_INT, &iterations);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  PetscCheck(status >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write the attribute iterations of %s", out);
  PetscFunctionReturn(0);
}

/* out: a copy of the problem group and FCLib's /solution (r, u, and v if v), normal first, and how the solve ended (rank 0 only) */
static PetscErrorCode WriteSolution(const char out[], const FCLibProblem *pb, Vec r, Vec u, Vec v, const char reason[], PetscReal znorm, PetscInt its)
{
  const char *group = pb->global ? "/fclib_global" : "/fclib_local";
  hid_t       fin, fout, sol;
  herr_t      status;

  PetscFunctionBeginUser;
  fout = H5Fcreate(out, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(fout >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot create the HDF5 file %s", out);
  fin = H5Fopen(pb->file, H5F_ACC_RDONLY, H5P_DEFAULT);
  PetscCheck(fin >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot open %s again to copy its problem", pb->file);
  status = H5Ocopy(fin, group, fout, group, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(fin);
  PetscCheck(status >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot copy %s of %s to %s", group, pb->file, out);
  sol = H5Gcreate2(fout, "/solution", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(sol >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot create /solution in %s", out);
  PetscCall(WriteDataset(out, sol, "r", r));
  PetscCall(WriteDataset(out, sol, "u", u));
  if (v) PetscCall(WriteDataset(out, sol, "v", v));
  H5Gclose(sol);
  PetscCall(WriteOutcome(out, fout, reason, znorm, its));
  PetscCheck(H5Fclose(fout) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot close %s", out);
  PetscFunctionReturn(0);
}

/* Refuses an output file that is the problem file itself */
static PetscErrorCode CheckOutputIsNotInput(MPI_Comm comm, const char file[], const char out[])
{
  struct stat in, o;

  PetscFunctionBeginUser;
  PetscCall(SSStarCheckOutputFile(comm, out));
  PetscCheck(stat(out, &o) || stat(file, &in) || in.st_dev != o.st_dev || in.st_ino != o.st_ino, comm, PETSC_ERR_ARG_WRONG, "-o %s is the problem file %s: it would be overwritten", out, file);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MPI_Comm            comm;
  FCLibProblem        pb;
  const char         *file = argc > 1 && argv[1][0] != '-' ? argv[1] : NULL, *base;
  char                out[PETSC_MAX_PATH_LEN] = "";
  PetscBool           hasOut, header = PETSC_TRUE, hasHelp, isssstar;
  PetscLogStage       stageSetUp, stageSolve;
  PetscLogDouble      t0, t1, t2;
  Mat                 Pfc, P;
  Vec                 f, mu, u, r, ufc, rfc, v = NULL;
  SNES                snes;
  SNESConvergedReason reason;
  PetscInt            its;
  PetscReal           fclibError = 0, znorm, unorm, fnorm, gamma, violation = 0;
  PetscMPIInt         rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(SSStarPushErrorHandler());
  comm = PETSC_COMM_WORLD;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* errors are reported by PETSc, naming the file and dataset */
  PetscOptionsBegin(comm, NULL, "FCLib problem", "ssstar");
  PetscCall(PetscOptionsString("-o", "Output file: the problem and FCLib's /solution group", NULL, out, out, sizeof(out), &hasOut));
  PetscCall(PetscOptionsBool("-summary_header", "Print the header of the summary", NULL, header, &header, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(NULL, &hasHelp));
  PetscCall(SNESCreate(comm, &snes));
  PetscCall(SNESSetType(snes, SNESSSSTAR));
  PetscCall(SNESSetFromOptions(snes));
  if (hasHelp) { /* the options are listed, with or without a file: no solve, no file */
    PetscCall(SNESDestroy(&snes));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCheck(file, comm, PETSC_ERR_ARG_WRONG, "Usage: %s FILE.hdf5 [-o solution.h5] [options]: name an FCLib problem file first", argv[0]);
  if (hasOut) PetscCall(CheckOutputIsNotInput(comm, file, out));
  PetscCall(PetscLogStageRegister("FCLib set-up", &stageSetUp));
  PetscCall(PetscLogStageRegister("FCLib solve", &stageSolve));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  PetscCheck(isssstar, comm, PETSC_ERR_ARG_WRONG, "examples/fclib reports the stopping quantity of ssstar: run it with -snes_type ssstar");
  PetscCall(SSStarCheckOptionsUsed(comm, (const char *const[]){help, NULL}, snes)); /* every option read, before any work */

  /* the problem in ssstar's form */
  PetscCall(PetscTime(&t0));
  PetscCall(PetscLogStagePush(stageSetUp));
  PetscCall(FCLibRead(comm, file, &pb));
  PetscCall(InvertW(comm, &pb, &Pfc));
  PetscCall(CreateContactProblem(comm, &pb, Pfc, &P, &f, &mu));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscTime(&t1));

  PetscCall(SNESSSStarSetLinearProblem(snes, P, f));
  PetscCall(SNESSSStarSetNodeLawParameter(snes, "friction", mu));
  PetscCall(VecDuplicate(f, &u));
  PetscCall(VecZeroEntries(u));
  PetscCall(PetscLogStagePush(stageSolve));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscTime(&t2));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetFunction(snes, &r, NULL, NULL)); /* r = P u - f, the contact force */

  /* the errors, on every rank, in FCLib's order */
  PetscCall(GatherFCLibOrder(u, &ufc));
  PetscCall(GatherFCLibOrder(r, &rfc));
  PetscCall(FCLibError(&pb, rfc, &fclibError));
  PetscCall(CoulombViolation(&pb, ufc, rfc, &violation));
  PetscCall(SNESGetFunctionNorm(snes, &znorm));
  PetscCall(SNESSSStarGetScaling(snes, &gamma));
  PetscCall(VecNorm(u, NORM_2, &unorm));
  PetscCall(VecNorm(f, NORM_2, &fnorm));

  base = strrchr(file, '/');
  base = base ? base + 1 : file;
  if (header) PetscCall(PetscPrintf(comm, "%-44s %-6s %8s %8s %8s %5s %9s %9s %11s %11s %8s reason\n", "problem", "kind", "contacts", "cond(W)", "asym(W)", "iters", "setup[s]", "solve[s]", "FCLib-error", "||z||/scale", "Coulomb"));
  PetscCall(PetscPrintf(comm, "%-44s %-6s %8" PetscInt_FMT " %8.1e %8.1e %5" PetscInt_FMT " %9.2e %9.2e %11.1e %11.1e %8.1e %s\n", base, pb.global ? "global" : "local", pb.nc, (double)pb.condition, (double)pb.asymmetry, its, t1 - t0, t2 - t1, (double)fclibError, (double)(znorm / PetscMax(unorm, gamma * fnorm)), (double)violation, SNESConvergedReasons[reason]));

  if (hasOut) {
    if (pb.global) { /* v = M^-1 (H r + f) */
      Vec Hr;

      PetscCall(VecDuplicate(pb.f, &Hr));
      PetscCall(VecDuplicate(pb.f, &v));
      PetscCall(MatMult(pb.H, rfc, Hr));
      PetscCall(VecAXPY(Hr, 1.0, pb.f));
      PetscCall(MatSolve(pb.Mlu, Hr, v));
      PetscCall(VecDestroy(&Hr));
    }
    if (rank == 0) PetscCall(WriteSolution(out, &pb, rfc, ufc, v, SNESConvergedReasons[reason], znorm, its));
    PetscCall(VecDestroy(&v));
  }

  PetscCall(VecDestroy(&ufc));
  PetscCall(VecDestroy(&rfc));
  PetscCall(VecDestroy(&u));
  PetscCall(SNESDestroy(&snes));
  PetscCall(VecDestroy(&mu));
  PetscCall(VecDestroy(&f));
  PetscCall(MatDestroy(&P));
  PetscCall(MatDestroy(&Pfc));
  PetscCall(FCLibDestroy(&pb));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : SSSTAR_EXIT_NOT_CONVERGED;
}
