#ifndef SSSTARREDUCTIONIMPL_H
#define SSSTARREDUCTIONIMPL_H

#include <ssstarreduction.h>

/*
   Dense matrices of P's size that the caller holds beside P while the reduction is alive (the SNES's Newton step:
   S P, the Newton matrix, and its LU factor or ScaLAPACK copy): counted in the memory estimate checked before the
   factorization.
*/
#define SSSTAR_DENSE_WORK 3

/* relative residual of a solve with K_II above which K_II is taken for singular (round-off: ~1e-15 cond(K_II)) */
#define SSSTAR_SINGULAR_RESIDUAL 1e-6

typedef struct _n_SSStarDirect *SSStarDirect;

struct _n_SSStarReduction {
  SSStarReductionType type;
  IS                  isC, isI;
  Mat                 P;
  PetscReal           memoryLimit;   /* GB per rank; 0: MemAvailable of the node split over its ranks   */
  SSStarDirect        direct;        /* direct: MUMPS's factorization of K with the Schur block C         */
  Mat                 Kii, Kic, Kci; /* explicit: blocks of K                                             */
  KSP                 kspI;          /* explicit: K_II^-1                                                 */
  Mat                 Kfactor;       /* mumps: Cholesky of K with the Schur block C, on rank 0            */
  VecScatter          toZero;        /* mumps: K's vectors to and from their copy on rank 0               */
  Vec                 bZero, xZero;
};

PETSC_INTERN PetscErrorCode SSStarDirectCreate(Mat, IS, PetscReal, SSStarDirect *, Mat *);
PETSC_INTERN PetscErrorCode SSStarDirectReduceLoad(SSStarDirect, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarDirectRecover(SSStarDirect, Vec, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarDirectDestroy(SSStarDirect *);

PETSC_INTERN PetscErrorCode SSStarReductionFitsMemory(MPI_Comm, PetscReal, PetscLogDouble, PetscLogDouble, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarReductionCheckMemory(MPI_Comm, PetscReal, PetscLogDouble, PetscLogDouble, const char[]);
PETSC_INTERN PetscErrorCode SSStarReductionCheckMUMPS(MPI_Comm, PetscMPIInt, PetscInt, PetscInt, PetscLogDouble, const char[], const char[]);

#endif
