#ifndef SSSTARREDUCTIONIMPL_H
#define SSSTARREDUCTIONIMPL_H

#include <ssstarreduction.h>

/*
   A reduction behind an ops table, one implementation per file, registered by name (regall.c): direct.c (MUMPS's C API
   + METIS), mumps.c (PETSc's MUMPS Schur complement), explicit.c (MATSCHURCOMPLEMENT made explicit), none.c (no
   reduction: the operator is K itself). Create_<type> computes P (or keeps K) and fills the ops. The options of a
   reduction's solvers are -<prefix>schur_... and -<prefix>interior_... (SSStarReductionSetOptionsPrefix()).
*/
typedef struct _SSStarReductionOps *SSStarReductionOps;
struct _SSStarReductionOps {
  PetscErrorCode (*reduceload)(SSStarReduction, Vec, Vec);         /* F -> f                                   */
  PetscErrorCode (*recover)(SSStarReduction, Vec, Vec, Vec, Vec);  /* F, u_C, r_C = P u_C - f -> u             */
  PetscErrorCode (*destroy)(SSStarReduction);
};

struct _n_SSStarReduction {
  struct _SSStarReductionOps ops;
  MPI_Comm                   comm;
  char                      *type;        /* as set (auto, or a registered type); after the set-up as resolved  */
  char                      *prefix;      /* of the options of its solvers, or NULL                          */
  PetscBool                  wholeBody;   /* the operator is K itself (none): the interior dofs stay unknowns */
  IS                         isC, isI;
  Mat                        P;           /* the operator: the Schur complement, or K for none                */
  PetscReal                  memoryLimit; /* GB per rank; 0: MemAvailable of the node split over its ranks    */
  PetscBool                  autoChosen;  /* auto resolved to this type, with the costs below                  */
  PetscReal                  autoCost[2]; /* auto's estimates: the dense route, the whole body (dense-LU flops)  */
  PetscReal                  autoHolding; /* how firmly K holds the body (SSStarReductionAutoCosts())          */
  void                      *data;        /* the implementation's                                             */
};

/*
   Dense matrices of P's size that the caller holds beside P while the reduction is alive (the SNES's Newton step:
   S P, the Newton matrix, and its LU factor): counted in the memory estimate checked before the factorization.
*/
#define SSSTAR_DENSE_WORK 3

/* relative residual of a solve with K_II above which K_II is taken for singular (round-off: ~1e-15 cond(K_II)) */
#define SSSTAR_SINGULAR_RESIDUAL 1e-6

PETSC_EXTERN PetscBool      SSStarReductionRegisterAllCalled;
PETSC_INTERN PetscErrorCode SSStarReductionCreate_Direct(SSStarReduction, Mat);
PETSC_INTERN PetscErrorCode SSStarReductionAnalyse_Direct(SSStarReduction, Mat, PetscLogDouble *, PetscLogDouble *, PetscLogDouble *);
PETSC_INTERN PetscErrorCode SSStarReductionResolveAuto(SSStarReduction, Mat, SSStarReductionType *);
PETSC_INTERN PetscErrorCode SSStarReductionCreate_MUMPS(SSStarReduction, Mat);
PETSC_INTERN PetscErrorCode SSStarReductionCreate_Explicit(SSStarReduction, Mat);
PETSC_INTERN PetscErrorCode SSStarReductionCreate_None(SSStarReduction, Mat);

/* "-<prefix>schur_direct_mumps_icntl_": an option of the reduction's solvers with its prefix, for messages and queries */
PETSC_INTERN PetscErrorCode SSStarReductionOptionName(SSStarReduction, const char[], char[], size_t);

PETSC_INTERN PetscErrorCode SSStarReductionFitsMemory(MPI_Comm, PetscReal, PetscLogDouble, PetscLogDouble, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarReductionCheckMemory(MPI_Comm, PetscReal, PetscLogDouble, PetscLogDouble, const char[]);
PETSC_INTERN PetscErrorCode SSStarReductionCheckMUMPS(MPI_Comm, PetscMPIInt, PetscInt, PetscInt, PetscLogDouble, const char[], const char[]);
PETSC_INTERN PetscErrorCode SSStarReductionCheckFactor(MPI_Comm, PetscMPIInt, Mat, PetscLogDouble, const char[], const char[]);

#endif
