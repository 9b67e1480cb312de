/*
   The direct reduction (docs/derivation.md section 0): one MUMPS Cholesky factorization of the whole K (SYM = 1) through
   MUMPS's C API, with the contact dofs C as its Schur block.

   - Ordering: METIS nested dissection of the node graph of K_II, the contact dofs after it (ICNTL(7) = 1, PERM_IN):
     MUMPS's own orderings turn into AMD as soon as a Schur block is asked for, and this MUMPS has no METIS inside.
   - K goes in distributed (ICNTL(18) = 3, the upper triangle of each rank's rows), the host works (PAR = 1).
   - P comes back complete (ICNTL(19) = 3) on a 1 x size process grid, one block of columns per rank, and is moved to
     the rows of an MPIDENSE matrix (P is symmetric: its columns are its rows); on one rank MUMPS writes into P itself.
   - f = F_C - K_CI K_II^-1 F_I is MUMPS's condensed right-hand side (ICNTL(26) = 1) and u_I = K_II^-1 (F_I - K_IC u_C)
     its expansion (ICNTL(26) = 2), right-hand sides centralized on the host.
*/
#include "reductionimpl.h"
#include <dmumps_c.h>
#include <metis.h>

#define ICNTL(i) icntl[(i) - 1]
#define CNTL(i)  cntl[(i) - 1]
#define INFO(i)  info[(i) - 1]
#define INFOG(i) infog[(i) - 1]
#define RINFO(i)  rinfo[(i) - 1]
#define RINFOG(i) rinfog[(i) - 1]

/* options -<prefix>schur_direct_mumps_icntl_<i> this reduction relies on, and may not be changed */
static const int ReservedICNTL[] = {5, 7, 18, 19, 20, 21, 26, 28};

typedef struct _n_SSStarDirect *SSStarDirect;
struct _n_SSStarDirect {
  DMUMPS_STRUC_C id;
  MPI_Comm       comm;     /* MUMPS's communicator: a duplicate of K's                          */
  PetscMPIInt    rank, size;
  char           icntl[256]; /* -<prefix>schur_direct_mumps_icntl_, for messages                  */
  PetscBool      initialized; /* MUMPS holds data to free (JOB = -2)                             */
  MUMPS_INT     *irn, *jcn; /* the upper triangle of K's local rows (1-based), until factored     */
  PetscScalar   *a;
  MUMPS_INT     *perm, *listvar; /* host: the pivot order and the Schur variables (1-based)     */
  PetscLogDouble estimate; /* MUMPS's estimate of its memory on this rank, bytes                */
  VecScatter     toHost;   /* K's vectors to and from their copy on the host                   */
  Vec            xHost;
  VecScatter     toHostC;  /* P's vectors to and from their copy on the host                   */
  Vec            cHost;
};

/* times a factorization whose workspace MUMPS estimated short is run again with a larger ICNTL(14) */
#define SSSTAR_MUMPS_WORKSPACE_RETRIES 3

/*
   A phase of MUMPS (JOB = job), its error named by what. A factorization whose real workspace the analysis estimated
   short (INFOG(1) = -9: seen on 3-4 ranks after K's Schur block changed) is run again with ICNTL(14), the workspace's
   margin in percent, doubled, as MUMPS's guide advises
*/
static PetscErrorCode RunMUMPS(SSStarDirect d, MUMPS_INT job, const char what[])
{
  PetscFunctionBegin;
  d->id.job = job;
  dmumps_c(&d->id);
  for (PetscInt k = 0; job == 2 && d->id.INFOG(1) == -9 && k < SSSTAR_MUMPS_WORKSPACE_RETRIES; k++) {
    d->id.ICNTL(14) = 2 * PetscMax(d->id.ICNTL(14), 20);
    PetscCall(PetscInfo(NULL, "%s: MUMPS's workspace short by %d entries (INFOG(1) = -9): factored again with ICNTL(14) = %d\n", what, (int)d->id.INFOG(2), (int)d->id.ICNTL(14)));
    dmumps_c(&d->id);
  }
  PetscCall(SSStarReductionCheckMUMPS(d->comm, -1, d->id.INFOG(1), d->id.INFOG(2), d->estimate, what, d->icntl));
  PetscFunctionReturn(0);
}

/* -<prefix>schur_direct_mumps_icntl_<i>, -<prefix>schur_direct_mumps_cntl_<i>: MUMPS's controls, except those the
   reduction relies on */
static PetscErrorCode SetControlsFromOptions(SSStarDirect d, const char prefix[])
{
  char      name[64];
  PetscInt  ival;
  PetscReal rval;
  PetscBool set;

  PetscFunctionBegin;
  for (int i = 1; i <= 60; i++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "-schur_direct_mumps_icntl_%d", i));
    PetscCall(PetscOptionsGetInt(NULL, prefix, name, &ival, &set));
    if (!set) continue;
    for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(ReservedICNTL); k++) PetscCheck(ReservedICNTL[k] != i, d->comm, PETSC_ERR_ARG_WRONG, "%s%d: ICNTL(%d) is set by the direct reduction itself", d->icntl, i, i);
    d->id.ICNTL(i) = (MUMPS_INT)ival;
  }
  for (int i = 1; i <= 15; i++) {
    PetscCall(PetscSNPrintf(name, sizeof(name), "-schur_direct_mumps_cntl_%d", i));
    PetscCall(PetscOptionsGetReal(NULL, prefix, name, &rval, &set));
    if (set) d->id.CNTL(i) = rval;
  }
  PetscFunctionReturn(0);
}

/* The upper triangle (j >= i) of K's local rows as 1-based triples: what MUMPS reads of a symmetric matrix */
static PetscErrorCode GetUpperTriangle(SSStarDirect d, Mat K)
{
  PetscInt           rstart, rend, ncols;
  const PetscInt    *cols;
  const PetscScalar *vals;
  PetscCount         nz = 0;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  for (PetscInt i = rstart; i < rend; i++) {
    PetscCall(MatGetRow(K, i, &ncols, &cols, NULL));
    for (PetscInt k = 0; k < ncols; k++) nz += cols[k] >= i;
    PetscCall(MatRestoreRow(K, i, &ncols, &cols, NULL));
  }
  PetscCall(PetscMalloc3(nz, &d->irn, nz, &d->jcn, nz, &d->a));
  nz = 0;
  for (PetscInt i = rstart; i < rend; i++) {
    PetscCall(MatGetRow(K, i, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; k++) {
      if (cols[k] < i) continue;
      d->irn[nz] = (MUMPS_INT)(i + 1);
      d->jcn[nz] = (MUMPS_INT)(cols[k] + 1);
      d->a[nz++] = vals[k];
    }
    PetscCall(MatRestoreRow(K, i, &ncols, &cols, &vals));
  }
  d->id.nnz_loc = (MUMPS_INT8)nz;
  d->id.irn_loc = d->irn;
  d->id.jcn_loc = d->jcn;
  d->id.a_loc   = d->a;
  PetscFunctionReturn(0);
}

/*
   Nodes for the ordering: blocks of K's block size when no block mixes contact and other dofs (and the ownership is
   block-aligned), else single dofs.
*/
static PetscErrorCode GetNodeSize(Mat K, IS isC, PetscInt *bs)
{
  PetscInt        rstart, rend, n, nC, b;
  const PetscInt *idx;
  PetscBool      *contact, ok;

  PetscFunctionBegin;
  PetscCall(MatGetBlockSize(K, &b));
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  ok = (PetscBool)(rstart % b == 0 && rend % b == 0);
  n  = rend - rstart;
  PetscCall(PetscCalloc1(n, &contact));
  PetscCall(ISGetLocalSize(isC, &nC));
  PetscCall(ISGetIndices(isC, &idx));
  for (PetscInt k = 0; k < nC; k++) {
    if (idx[k] < rstart || idx[k] >= rend) ok = PETSC_FALSE; /* contact dofs are owned dofs */
    else contact[idx[k] - rstart] = PETSC_TRUE;
  }
  PetscCall(ISRestoreIndices(isC, &idx));
  for (PetscInt i = 0; ok && i + b <= n; i += b)
    for (PetscInt k = 1; k < b; k++)
      if (contact[i + k] != contact[i]) ok = PETSC_FALSE;
  PetscCall(PetscFree(contact));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ok, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)K)));
  *bs = ok ? b : 1;
  PetscFunctionReturn(0);
}

/* For each local node (block of bs rows of K), the other nodes its rows couple to: deg[] and adj[] (global nodes) */
static PetscErrorCode GetLocalNodeGraph(Mat K, PetscInt bs, PetscInt *nnodes, PetscInt **deg, PetscInt *nadj, PetscInt **adj)
{
  PetscInt       rstart, rend, ncols, cap = 64, n;
  const PetscInt *cols;
  PetscInt      *row;
  PetscSegBuffer seg;

  PetscFunctionBegin;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  *nnodes = (rend - rstart) / bs;
  PetscCall(PetscMalloc1(*nnodes, deg));
  PetscCall(PetscMalloc1(cap, &row));
  PetscCall(PetscSegBufferCreate(sizeof(PetscInt), 16 * (*nnodes) + 1, &seg));
  *nadj = 0;
  for (PetscInt v = 0; v < *nnodes; v++) {
    const PetscInt node = rstart / bs + v;
    PetscInt      *dst;

    n = 0;
    for (PetscInt r = rstart + v * bs; r < rstart + (v + 1) * bs; r++) {
      PetscCall(MatGetRow(K, r, &ncols, &cols, NULL));
      if (n + ncols > cap) {
        cap = 2 * (n + ncols);
        PetscCall(PetscRealloc(cap * sizeof(PetscInt), &row));
      }
      for (PetscInt k = 0; k < ncols; k++)
        if (cols[k] / bs != node) row[n++] = cols[k] / bs;
      PetscCall(MatRestoreRow(K, r, &ncols, &cols, NULL));
    }
    PetscCall(PetscSortRemoveDupsInt(&n, row));
    PetscCall(PetscSegBufferGetInts(seg, n, &dst));
    PetscCall(PetscArraycpy(dst, row, n));
    (*deg)[v] = n;
    *nadj += n;
  }
  PetscCall(PetscFree(row));
  PetscCall(PetscSegBufferExtractAlloc(seg, adj));
  PetscCall(PetscSegBufferDestroy(&seg));
  PetscFunctionReturn(0);
}

/*
   The pivot order (host): METIS nested dissection of the graph of the interior nodes (deg/adj of every node, in node
   order), every interior dof of a node in a row, then the contact dofs in the order of listvar.
*/
static PetscErrorCode OrderOnHost(PetscInt N, PetscInt bs, PetscInt NC, const MUMPS_INT listvar[], const PetscInt deg[], const PetscInt adj[], MUMPS_INT perm[])
{
  const PetscInt nb = N / bs;
  PetscInt      *inode, nI = 0, pos;
  idx_t         *xadj, *adjncy, *mperm, *miperm, nvtxs, options[METIS_NOPTIONS];
  PetscInt      *fill, *row, maxrow = 0;
  int            status;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(nb, &inode));
  for (PetscInt b = 0; b < nb; b++) inode[b] = 0;
  for (PetscInt j = 0; j < NC; j++) inode[(listvar[j] - 1) / bs] = -1;
  for (PetscInt b = 0; b < nb; b++)
    if (inode[b] == 0) inode[b] = nI++;
    else inode[b] = -1;
  /* symmetric adjacency of the interior nodes: count both directions, fill, then drop duplicates */
  PetscCall(PetscCalloc1(nI + 1, &xadj));
  PetscCall(PetscCalloc1(nI, &fill));
  pos = 0;
  for (PetscInt b = 0; b < nb; b++) {
    for (PetscInt k = pos; k < pos + deg[b]; k++)
      if (inode[b] >= 0 && inode[adj[k]] >= 0) {
        xadj[inode[b] + 1]++;
        xadj[inode[adj[k]] + 1]++;
      }
    pos += deg[b];
  }
  for (PetscInt v = 0; v < nI; v++) xadj[v + 1] += xadj[v];
  PetscCall(PetscMalloc1(xadj[nI], &adjncy));
  pos = 0;
  for (PetscInt b = 0; b < nb; b++) {
    for (PetscInt k = pos; k < pos + deg[b]; k++)
      if (inode[b] >= 0 && inode[adj[k]] >= 0) {
        const PetscInt u = inode[b], w = inode[adj[k]];
        adjncy[xadj[u] + fill[u]++] = (idx_t)w;
        adjncy[xadj[w] + fill[w]++] = (idx_t)u;
      }
    pos += deg[b];
  }
  PetscCall(PetscFree(fill));
  for (PetscInt v = 0; v < nI; v++) maxrow = PetscMax(maxrow, (PetscInt)(xadj[v + 1] - xadj[v]));
  PetscCall(PetscMalloc1(maxrow, &row));
  { /* drop the duplicates (each edge of a symmetric K came twice), compacting in place */
    idx_t start = 0, out = 0;

    for (PetscInt v = 0; v < nI; v++) {
      const idx_t end = xadj[v + 1];
      PetscInt    n   = (PetscInt)(end - start);

      for (PetscInt k = 0; k < n; k++) row[k] = (PetscInt)adjncy[start + k];
      PetscCall(PetscSortRemoveDupsInt(&n, row));
      for (PetscInt k = 0; k < n; k++) adjncy[out + k] = (idx_t)row[k];
      xadj[v] = out;
      out += n;
      start = end;
    }
    xadj[nI] = out;
  }
  PetscCall(PetscFree(row));
  PetscCall(PetscMalloc2(nI, &mperm, nI, &miperm));
  nvtxs = (idx_t)nI;
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  if (nI > 0) {
    status = METIS_NodeND(&nvtxs, xadj, adjncy, NULL, options, mperm, miperm);
    PetscCheck(status == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_NodeND failed (status %d) on the graph of K_II, %" PetscInt_FMT " nodes", status, nI);
  }
  for (PetscInt dof = 0; dof < N; dof++) {
    const PetscInt v = inode[dof / bs];

    if (v >= 0) perm[dof] = (MUMPS_INT)(bs * miperm[v] + dof % bs + 1);
  }
  for (PetscInt j = 0; j < NC; j++) perm[listvar[j] - 1] = (MUMPS_INT)(bs * nI + j + 1);
  PetscCall(PetscFree2(mperm, miperm));
  PetscCall(PetscFree(adjncy));
  PetscCall(PetscFree(xadj));
  PetscCall(PetscFree(inode));
  PetscFunctionReturn(0);
}

/* The Schur variables (host, in the order of isC) and the pivot order of every dof (host) */
static PetscErrorCode SetOrdering(SSStarDirect d, Mat K, IS isC)
{
  PetscInt        N, NC, bs = 1, nnodes = 0, nadj = 0, *deg, *adj, *allDeg = NULL, *allAdj = NULL;
  IS              isCall;
  const PetscInt *cidx;
  PetscMPIInt     cnt[2], *counts = NULL, *displs = NULL, *acounts = NULL, *adispls = NULL;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_SchurOrdering, K, 0, 0, 0));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(ISGetSize(isC, &NC));
  PetscCall(GetNodeSize(K, isC, &bs));
  PetscCall(GetLocalNodeGraph(K, bs, &nnodes, &deg, &nadj, &adj));
  PetscCall(PetscMPIIntCast(nnodes, &cnt[0]));
  PetscCall(PetscMPIIntCast(nadj, &cnt[1]));
  if (d->rank == 0) PetscCall(PetscMalloc4(d->size, &counts, d->size, &displs, d->size, &acounts, d->size, &adispls));
  {
    PetscMPIInt *both = NULL;

    if (d->rank == 0) PetscCall(PetscMalloc1(2 * d->size, &both));
    PetscCallMPI(MPI_Gather(cnt, 2, MPI_INT, both, 2, MPI_INT, 0, d->comm));
    if (d->rank == 0) {
      PetscInt totDeg = 0, totAdj = 0;

      for (PetscMPIInt r = 0; r < d->size; r++) {
        counts[r]  = both[2 * r];
        acounts[r] = both[2 * r + 1];
        displs[r]  = (PetscMPIInt)totDeg;
        adispls[r] = (PetscMPIInt)totAdj;
        totDeg += counts[r];
        totAdj += acounts[r];
      }
      PetscCheck(totAdj < PETSC_MPI_INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "The node graph of K has %" PetscInt_FMT " edges, too many for one MPI message", totAdj);
      PetscCall(PetscMalloc2(totDeg, &allDeg, totAdj, &allAdj));
      PetscCall(PetscFree(both));
    }
  }
  PetscCallMPI(MPI_Gatherv(deg, cnt[0], MPIU_INT, allDeg, counts, displs, MPIU_INT, 0, d->comm));
  PetscCallMPI(MPI_Gatherv(adj, cnt[1], MPIU_INT, allAdj, acounts, adispls, MPIU_INT, 0, d->comm));
  PetscCall(PetscFree(deg));
  PetscCall(PetscFree(adj));

  PetscCall(ISAllGather(isC, &isCall));
  if (d->rank == 0) {
    PetscCall(PetscMalloc2(NC, &d->listvar, N, &d->perm));
    PetscCall(ISGetIndices(isCall, &cidx));
    for (PetscInt j = 0; j < NC; j++) d->listvar[j] = (MUMPS_INT)(cidx[j] + 1);
    PetscCall(ISRestoreIndices(isCall, &cidx));
    PetscCall(OrderOnHost(N, bs, NC, d->listvar, allDeg, allAdj, d->perm));
    PetscCall(PetscFree2(allDeg, allAdj));
    PetscCall(PetscFree4(counts, displs, acounts, adispls));
    d->id.perm_in       = d->perm;
    d->id.listvar_schur = d->listvar;
  }
  PetscCall(ISDestroy(&isCall));
  PetscCall(PetscLogEventEnd(SSSTAR_SchurOrdering, K, 0, 0, 0));
  PetscFunctionReturn(0);
}

/*
   Moves P from MUMPS's layout (this rank: columns [rank nb, rank nb + nloc), every row, leading dimension NC) to the
   rows of the MPIDENSE P. P = P^T, so rank r's rows [r0, r1) of P are the rows [r0, r1) of every rank's columns.
*/
static PetscErrorCode MoveSchurToRows(SSStarDirect d, PetscInt NC, PetscInt nb, const PetscScalar *S, Mat P)
{
  const PetscInt *ranges;
  PetscInt        lda, mloc;
  PetscScalar    *pa;
  MPI_Request    *reqs;
  MPI_Datatype   *types;
  PetscMPIInt     nreq = 0, tag = 7341;
  const PetscInt  c0 = PetscMin(NC, d->rank * nb), c1 = PetscMin(NC, c0 + nb);

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(SSSTAR_SchurScatter, P, 0, 0, 0));
  PetscCall(MatGetOwnershipRanges(P, &ranges));
  PetscCall(MatGetLocalSize(P, &mloc, NULL));
  PetscCall(MatDenseGetLDA(P, &lda));
  PetscCall(MatDenseGetArrayWrite(P, &pa));
  PetscCall(PetscMalloc2(2 * d->size, &reqs, 2 * d->size, &types));
  for (PetscMPIInt q = 0; q < d->size; q++) { /* my rows of the columns of rank q */
    const PetscInt q0 = PetscMin(NC, q * nb), q1 = PetscMin(NC, q0 + nb);
    PetscMPIInt    ncols, blen, stride;

    if (q1 == q0 || mloc == 0) continue;
    PetscCall(PetscMPIIntCast(q1 - q0, &ncols));
    PetscCall(PetscMPIIntCast(mloc, &blen));
    PetscCall(PetscMPIIntCast(lda, &stride));
    PetscCallMPI(MPI_Type_vector(ncols, blen, stride, MPIU_SCALAR, &types[nreq]));
    PetscCallMPI(MPI_Type_commit(&types[nreq]));
    PetscCallMPI(MPI_Irecv(pa + q0 * lda, 1, types[nreq], q, tag, d->comm, &reqs[nreq]));
    nreq++;
  }
  for (PetscMPIInt r = 0; r < d->size; r++) { /* the rows of rank r of my columns */
    const PetscInt r0 = ranges[r], r1 = ranges[r + 1];
    PetscMPIInt    ncols, blen, stride;

    if (r1 == r0 || c1 == c0) continue;
    PetscCall(PetscMPIIntCast(c1 - c0, &ncols));
    PetscCall(PetscMPIIntCast(r1 - r0, &blen));
    PetscCall(PetscMPIIntCast(NC, &stride));
    PetscCallMPI(MPI_Type_vector(ncols, blen, stride, MPIU_SCALAR, &types[nreq]));
    PetscCallMPI(MPI_Type_commit(&types[nreq]));
    PetscCallMPI(MPI_Isend(S + r0, 1, types[nreq], r, tag, d->comm, &reqs[nreq]));
    nreq++;
  }
  PetscCallMPI(MPI_Waitall(nreq, reqs, MPI_STATUSES_IGNORE));
  for (PetscMPIInt k = 0; k < nreq; k++) PetscCallMPI(MPI_Type_free(&types[k]));
  PetscCall(PetscFree2(reqs, types));
  PetscCall(MatDenseRestoreArrayWrite(P, &pa));
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(SSSTAR_SchurScatter, P, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* MUMPS set up for K with the Schur block isC, ordered and analysed (JOB = 1): its estimates of the flops and memory */
static PetscErrorCode DirectAnalyse(SSStarDirect d, Mat K, IS isC, const char prefix[])
{
  PetscInt N, NC, nb;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_dup(PetscObjectComm((PetscObject)K), &d->comm));
  PetscCallMPI(MPI_Comm_rank(d->comm, &d->rank));
  PetscCallMPI(MPI_Comm_size(d->comm, &d->size));
  PetscCall(MatGetSize(K, &N, NULL));
  PetscCall(ISGetSize(isC, &NC));
  PetscCheck(NC > 0, d->comm, PETSC_ERR_ARG_WRONG, "No contact dofs to reduce K to");
  PetscCheck(N < PETSC_MPI_INT_MAX, d->comm, PETSC_ERR_SUP, "K has %" PetscInt_FMT " rows, more than MUMPS's 32-bit indices hold", N);

  d->id.comm_fortran = (MUMPS_INT)MPI_Comm_c2f(d->comm);
  d->id.par          = 1;
  d->id.sym          = 1;
  PetscCall(RunMUMPS(d, -1, "the initialization of MUMPS"));
  d->initialized = PETSC_TRUE;
  d->id.ICNTL(1)  = -1; /* errors are reported by the reduction, with their INFOG */
  d->id.ICNTL(2)  = -1;
  d->id.ICNTL(3)  = -1;
  d->id.ICNTL(4)  = 0;
  d->id.ICNTL(5)  = 0; /* assembled */
  d->id.ICNTL(18) = 3; /* distributed by the ranks' rows */
  d->id.ICNTL(7)  = 1; /* PERM_IN */
  d->id.ICNTL(28) = 1; /* sequential analysis: the one that reads PERM_IN */
  d->id.ICNTL(19) = 3; /* complete Schur complement, distributed by columns */
  d->id.ICNTL(20) = 0; /* dense right-hand sides ... */
  d->id.ICNTL(21) = 0; /* ... and solutions, on the host */
  PetscCall(SetControlsFromOptions(d, prefix));
  d->id.n = (MUMPS_INT)N;
  PetscCall(GetUpperTriangle(d, K));
  PetscCall(SetOrdering(d, K, isC));

  nb               = (NC + d->size - 1) / d->size;
  d->id.size_schur = (MUMPS_INT)NC;
  d->id.nprow      = 1;
  d->id.npcol      = (MUMPS_INT)d->size;
  d->id.mblock     = (MUMPS_INT)nb;
  d->id.nblock     = (MUMPS_INT)nb;
  PetscCall(PetscLogEventBegin(SSSTAR_SchurAnalysis, K, 0, 0, 0));
  PetscCall(RunMUMPS(d, 1, "the analysis of K (MUMPS)"));
  PetscCall(PetscLogEventEnd(SSSTAR_SchurAnalysis, K, 0, 0, 0));
  PetscCall(PetscInfo(K, "MUMPS analysis: %g flops to factor, %g entries in the factors, memory %d MB per rank at most, %d MB in all (out of core: %d MB, %d MB)\n", (double)d->id.RINFOG(1), (double)d->id.INFOG(20), (int)d->id.INFOG(16), (int)d->id.INFOG(17), (int)d->id.INFOG(26), (int)d->id.INFOG(27)));
  {
    const PetscInt expect = PetscMax(0, PetscMin(NC, (d->rank + 1) * nb) - PetscMin(NC, d->rank * nb));

    PetscCheck(d->id.schur_mloc == NC && d->id.schur_nloc == expect, PETSC_COMM_SELF, PETSC_ERR_LIB, "MUMPS laid the Schur complement out as %d x %d on rank %d, not %" PetscInt_FMT " x %" PetscInt_FMT, (int)d->id.schur_mloc, (int)d->id.schur_nloc, d->rank, NC, expect);
  }
  PetscFunctionReturn(0);
}

/* The dense memory of this rank beside MUMPS's factors: P, and MUMPS's Schur block (several ranks) or later the caller's dense work */
static PetscLogDouble DenseBytes(SSStarDirect d, PetscInt NC, PetscInt mC)
{
  return 8.0 * NC * (mC + PetscMax(d->size > 1 ? d->id.schur_nloc : 0, SSSTAR_DENSE_WORK * (PetscLogDouble)mC));
}

/*
   Factors the analysed K with its Schur block isC and returns P (MPIDENSE, rows like isC); refuses before the
   factorization when MUMPS's estimate, P and the caller's dense work exceed memoryLimit (GB per rank, 0: MemAvailable)
*/
static PetscErrorCode DirectFactor(SSStarDirect d, Mat K, IS isC, PetscReal memoryLimit, Mat *P)
{
  PetscInt       NC, mC, nb;
  PetscLogDouble dense;
  PetscScalar   *schur;
  Vec            x, c;

  PetscFunctionBegin;
  PetscCall(ISGetSize(isC, &NC));
  PetscCall(ISGetLocalSize(isC, &mC));
  nb = (NC + d->size - 1) / d->size;
  /*
     Memory, before any of it is taken: MUMPS's estimate (MB = 1e6 bytes), P, and MUMPS's Schur block (several ranks)
     or later the caller's dense work. When MUMPS's factors do not fit in core, they go out of core (to disk,
     MUMPS_OOC_TMPDIR) if that fits.
  */
  dense = DenseBytes(d, NC, mC);
  if (!d->id.ICNTL(22)) {
    PetscBool fits;

    PetscCall(SSStarReductionFitsMemory(d->comm, memoryLimit, 1e6 * (PetscLogDouble)d->id.INFO(15), dense, &fits));
    if (!fits) d->id.ICNTL(22) = 1;
  }
  d->estimate = 1e6 * (PetscLogDouble)(d->id.ICNTL(22) ? d->id.INFO(17) : d->id.INFO(15));
  PetscCall(PetscInfo(K, "MUMPS's factors in core: %d MB, out of core: %d MB on this rank; %s\n", (int)d->id.INFO(15), (int)d->id.INFO(17), d->id.ICNTL(22) ? "out of core" : "in core"));
  PetscCall(SSStarReductionCheckMemory(d->comm, memoryLimit, d->estimate, dense, d->id.ICNTL(22) ? "The direct Schur reduction with MUMPS's factors out of core (on disk)" : "The direct Schur reduction"));

  PetscCall(MatCreateDense(PetscObjectComm((PetscObject)K), mC, mC, NC, NC, NULL, P));
  if (d->size == 1) PetscCall(MatDenseGetArrayWrite(*P, &schur)); /* MUMPS writes P itself */
  else PetscCall(PetscMalloc1((size_t)NC * d->id.schur_nloc, &schur));
  d->id.schur_lld = (MUMPS_INT)NC;
  d->id.schur     = schur;
  PetscCall(PetscLogEventBegin(SSSTAR_SchurFactor, K, 0, 0, 0));
  PetscCall(RunMUMPS(d, 2, "the factorization of K with the Schur block (MUMPS)"));
  PetscCall(PetscLogFlops(d->id.RINFO(3)));
  PetscCall(PetscInfo(K, "MUMPS factorization: %g flops (full rank), %g flops with low-rank blocks (RINFOG(14), ICNTL(35) > 0), %g entries in the factors (INFOG(29))\n", (double)d->id.RINFOG(3), (double)d->id.RINFOG(14), (double)d->id.INFOG(29)));
  PetscCall(PetscLogEventEnd(SSSTAR_SchurFactor, K, 0, 0, 0));
  d->id.schur = NULL;
  PetscCall(PetscFree3(d->irn, d->jcn, d->a)); /* the factors are all the solves need */
  d->id.irn_loc = d->id.jcn_loc = NULL;
  d->id.a_loc   = NULL;
  if (d->size == 1) {
    PetscCall(MatDenseRestoreArrayWrite(*P, &schur));
    PetscCall(MatAssemblyBegin(*P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(*P, MAT_FINAL_ASSEMBLY));
  } else {
    PetscCall(MoveSchurToRows(d, NC, nb, schur, *P));
    PetscCall(PetscFree(schur));
  }

  PetscCall(MatCreateVecs(K, &x, NULL));
  PetscCall(VecScatterCreateToZero(x, &d->toHost, &d->xHost));
  PetscCall(VecDestroy(&x));
  PetscCall(MatCreateVecs(*P, &c, NULL));
  PetscCall(VecScatterCreateToZero(c, &d->toHostC, &d->cHost));
  PetscCall(VecDestroy(&c));
  PetscFunctionReturn(0);
}

/* On the host: the condensed right-hand side of F (in xHost) into cHost; xHost is overwritten */
static PetscErrorCode Condense(SSStarDirect d)
{
  PetscScalar *x, *c;

  PetscFunctionBegin;
  PetscCall(VecGetArray(d->xHost, &x));
  PetscCall(VecGetArray(d->cHost, &c));
  d->id.rhs       = x;
  d->id.nrhs      = 1;
  d->id.lrhs      = d->id.n;
  d->id.redrhs    = c;
  d->id.lredrhs   = d->id.size_schur;
  d->id.ICNTL(26) = 1;
  PetscCall(RunMUMPS(d, 3, "the condensation of the load on the contact dofs (MUMPS)"));
  PetscCall(VecRestoreArray(d->cHost, &c));
  PetscCall(VecRestoreArray(d->xHost, &x));
  PetscFunctionReturn(0);
}

/* f = F_C - K_CI K_II^-1 F_I */
static PetscErrorCode SSStarReductionReduceLoad_Direct(SSStarReduction red, Vec F, Vec f)
{
  SSStarDirect d = (SSStarDirect)red->data;

  PetscFunctionBegin;
  PetscCall(VecScatterBegin(d->toHost, F, d->xHost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(d->toHost, F, d->xHost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(Condense(d));
  PetscCall(VecScatterBegin(d->toHostC, d->cHost, f, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(d->toHostC, d->cHost, f, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

/* u with u_I = K_II^-1 (F_I - K_IC u_C): MUMPS's expansion, which needs the condensation of the same F just before */
static PetscErrorCode SSStarReductionRecover_Direct(SSStarReduction red, Vec F, Vec uC, Vec rC, Vec u)
{
  SSStarDirect d = (SSStarDirect)red->data;
  PetscScalar *x, *c;

  PetscFunctionBegin;
  PetscCall(VecScatterBegin(d->toHost, F, d->xHost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(d->toHost, F, d->xHost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(Condense(d));
  PetscCall(VecScatterBegin(d->toHostC, uC, d->cHost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(d->toHostC, uC, d->cHost, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArray(d->xHost, &x));
  PetscCall(VecGetArray(d->cHost, &c));
  d->id.rhs       = x;
  d->id.redrhs    = c;
  d->id.ICNTL(26) = 2;
  PetscCall(RunMUMPS(d, 3, "the expansion of the contact displacement to the whole body (MUMPS)"));
  PetscCall(VecRestoreArray(d->cHost, &c));
  PetscCall(VecRestoreArray(d->xHost, &x));
  PetscCall(VecScatterBegin(d->toHost, d->xHost, u, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(d->toHost, d->xHost, u, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode SSStarReductionDestroy_Direct(SSStarReduction red)
{
  SSStarDirect d = (SSStarDirect)red->data;

  PetscFunctionBegin;
  if (d->initialized) {
    d->id.job = -2;
    dmumps_c(&d->id);
  }
  PetscCall(PetscFree3(d->irn, d->jcn, d->a));
  PetscCall(PetscFree2(d->listvar, d->perm));
  PetscCall(VecScatterDestroy(&d->toHost));
  PetscCall(VecDestroy(&d->xHost));
  PetscCall(VecScatterDestroy(&d->toHostC));
  PetscCall(VecDestroy(&d->cHost));
  if (d->comm != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_free(&d->comm));
  PetscFunctionReturn(0);
}

/*
   The direct reduction ordered and analysed, not factored (auto's cost model reads MUMPS's estimates, then either
   SSStarReductionCreate_Direct() factors it or the reduction is dropped): MUMPS's flops to factor K with its Schur
   block (RINFOG(1)) and the bytes of this rank (its factors in core, P and the dense work) for the memory check
*/
PetscErrorCode SSStarReductionAnalyse_Direct(SSStarReduction red, Mat K, PetscLogDouble *flops, PetscLogDouble *sparse, PetscLogDouble *dense)
{
  SSStarDirect d;
  PetscInt     NC, mC;

  PetscFunctionBegin;
  PetscCall(PetscNew(&d));
  d->comm             = MPI_COMM_NULL;
  red->data           = d;
  red->ops.reduceload = SSStarReductionReduceLoad_Direct;
  red->ops.recover    = SSStarReductionRecover_Direct;
  red->ops.destroy    = SSStarReductionDestroy_Direct;
  PetscCall(SSStarReductionOptionName(red, "schur_direct_mumps_icntl_", d->icntl, sizeof(d->icntl)));
  PetscCall(DirectAnalyse(d, K, red->isC, red->prefix));
  PetscCall(ISGetSize(red->isC, &NC));
  PetscCall(ISGetLocalSize(red->isC, &mC));
  *flops  = d->id.RINFOG(1);
  *sparse = 1e6 * (PetscLogDouble)d->id.INFO(15);
  *dense  = DenseBytes(d, NC, mC);
  PetscFunctionReturn(0);
}

PetscErrorCode SSStarReductionCreate_Direct(SSStarReduction red, Mat K)
{
  PetscLogDouble flops, sparse, dense;

  PetscFunctionBegin;
  if (!red->data) PetscCall(SSStarReductionAnalyse_Direct(red, K, &flops, &sparse, &dense)); /* auto analysed it already */
  PetscCall(DirectFactor((SSStarDirect)red->data, K, red->isC, red->memoryLimit, &red->P));
  PetscFunctionReturn(0);
}
