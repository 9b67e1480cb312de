#ifndef SSSTARREDUCTION_H
#define SSSTARREDUCTION_H

/*
   Reduction of a linear system K u = F (K SPD) to a subset C of its dofs by a Schur complement, and the recovery
   of the whole u from u_C; or none, which keeps K. Linear algebra only: no mesh, no contact law.
*/
#include <petscksp.h>

PETSC_EXTERN PetscLogEvent SSSTAR_Schur, SSSTAR_Recovery;
/* phases of the direct reduction: METIS ordering, MUMPS analysis, factorization with the Schur block, P to its rows */
PETSC_EXTERN PetscLogEvent SSSTAR_SchurOrdering, SSSTAR_SchurAnalysis, SSSTAR_SchurFactor, SSSTAR_SchurScatter;

/*
   Reduction of K u = F to the contact dofs: P = K_CC - K_CI K_II^-1 K_IC, f = F_C - K_CI K_II^-1 F_I, or none (the
   contact problem stays on the whole body). Types are registered by name (SSStarReductionRegisterAll(), one file per
   type in src/reduction/).
*/
typedef const char *SSStarReductionType;
#define SSSTARREDUCTIONDIRECT   "direct"   /* MUMPS through its C API: METIS nested dissection of K_II, C last, on every rank */
#define SSSTARREDUCTIONMUMPS    "mumps"    /* PETSc's MUMPS Schur complement (MatFactorSetSchurIS), computed on rank 0      */
#define SSSTARREDUCTIONEXPLICIT "explicit" /* MATSCHURCOMPLEMENT made explicit, distributed                                */
#define SSSTARREDUCTIONNONE     "none"     /* no reduction: P is never formed, the operator is K                            */
#define SSSTARREDUCTIONAUTO     "auto"     /* not a type: direct where its estimated work is less and it fits, else none (auto.c) */

typedef struct _n_SSStarReduction *SSStarReduction;
PETSC_EXTERN PetscFunctionList SSStarReductionList;
PETSC_EXTERN PetscErrorCode    SSStarReductionRegister(const char[], PetscErrorCode (*)(SSStarReduction, Mat));
PETSC_EXTERN PetscErrorCode    SSStarReductionRegisterAll(void);
PETSC_EXTERN PetscErrorCode    SSStarReductionGetNames(PetscInt *, const char *const *[]);
PETSC_EXTERN PetscErrorCode    SSStarReductionCreate(MPI_Comm, SSStarReduction *);
PETSC_EXTERN PetscErrorCode    SSStarReductionSetType(SSStarReduction, SSStarReductionType);
PETSC_EXTERN PetscErrorCode    SSStarReductionSetOptionsPrefix(SSStarReduction, const char[]);
PETSC_EXTERN PetscErrorCode    SSStarReductionSetMemoryLimit(SSStarReduction, PetscReal);
PETSC_EXTERN PetscErrorCode    SSStarReductionSetUp(SSStarReduction, Mat, IS, IS);
PETSC_EXTERN PetscErrorCode    SSStarReductionGetType(SSStarReduction, SSStarReductionType *);
PETSC_EXTERN PetscErrorCode    SSStarReductionIsWholeBody(SSStarReduction, PetscBool *);
PETSC_EXTERN PetscErrorCode    SSStarReductionGetOperator(SSStarReduction, Mat *);
PETSC_EXTERN PetscErrorCode    SSStarReductionGetSchurComplement(SSStarReduction, Mat *);
PETSC_EXTERN PetscErrorCode    SSStarReductionReduceLoad(SSStarReduction, Vec, Vec);
PETSC_EXTERN PetscErrorCode    SSStarReductionRecover(SSStarReduction, Vec, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode    SSStarReductionDestroy(SSStarReduction *);
PETSC_EXTERN PetscErrorCode    SSStarReductionAutoCosts(PetscReal, PetscReal, PetscReal, PetscReal, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode    SSStarReductionGetAutoCosts(SSStarReduction, PetscBool *, PetscReal *, PetscReal *, PetscReal *);

#endif
