#ifndef SSSTARMEMINFO_H
#define SSSTARMEMINFO_H

/* What the machine has (src/sys/meminfo.c): the scene's check before the mesh and the reduction's before the factorization read it here */
#include <petscsys.h>

PETSC_INTERN PetscErrorCode SSStarMemAvailable(PetscLogDouble *);

/*
   What a whole-body run adds per dof of a rank (bench/memory.py, the prism; one rank, several: PCGAMG's parallel
   Galerkin products keep A P, rows of K by columns of the interpolation, which one rank does not): the mesh, the
   contact nodes, the assembly, the nested start's coarser solves and the output (BODY), and the multigrid's set-up
   with the Krylov steps (SOLVE), with smoothed aggregation or plain (-pc_gamg_agg_nsmooths 0: on several ranks with the
   products P^T A P all at once, which keep no A P; prism levels 16 and 24 on 2 ranks: 0.328 and 0.890 GB per rank,
   89 and 104 bytes per dof beyond BODY)
*/
/*
   From this many dofs the whole body's multigrid aggregates plainly by default (-snes_ssstar_plain_aggregation_dofs):
   prism level 16 (209 088 dofs) on 2 ranks, 1.03x the smoothed default's whole run for 0.68x its peak; level 24,
   0.82x its CPU time for 0.58x its peak (docs/guide/scale.md). Below it the smoothed aggregation's fewer Krylov
   iterations pay and its memory does not matter.
*/
#define SSSTAR_PLAIN_AGGREGATION_DOFS 200000
#define SSSTAR_BODY_BYTES(size)         ((size) == 1 ? 1900.0 : 2200.0)
#define SSSTAR_SOLVE_BYTES(size, plain) ((plain) ? ((size) == 1 ? 410.0 : 100.0) : ((size) == 1 ? 620.0 : 1960.0))
/*
   The dense route's additions (issue 31's slab: 1.64 GB where the whole body's estimate said 0.18): MUMPS's factors of
   K, about SSSTAR_MUMPS_ENTRIES N^(4/3) entries for N dofs (measured 15-25 on the prism, the slab, balls and blocks),
   with 20 % more of its workspace, and its front of the Schur block (NC x NC); then P (NC x NC, rows over the ranks) and
   the Newton step's dense matrices: 2 + 1/size matrices of P's size on the largest rank besides the front (measured on
   the slab at 1, 2 and 3 ranks, 29 Nov: 3.96, 3.80 and 2.87 of P's size in all, against 4, 3 and 2.67 here)
*/
#define SSSTAR_MUMPS_ENTRIES 20.0
#define SSSTAR_DENSE_BYTES(size, dofs, NC) \
  ((8.0 * 1.2 * SSSTAR_MUMPS_ENTRIES * PetscPowReal((PetscReal)(dofs), 4.0 / 3.0) + 8.0 * (NC) * (NC)) / (size) + 8.0 * (NC) * (NC) * (2.0 + 1.0 / (size)))
/* "0.233 GB per rank" (the largest rank's resident memory), with -ssstar_progress_ranks " (rank 0: 0.231, least: 0.210)" */
PETSC_INTERN PetscErrorCode SSStarMemoryText(MPI_Comm, char[], size_t);

#endif
