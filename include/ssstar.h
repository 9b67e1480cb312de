#ifndef SSSTAR_H
#define SSSTAR_H

/*
   ssstar: the semismooth* Newton method for 3D static contact with Coulomb friction
   (Gfrerer, Mandlmayr, Outrata, Valdman) as a PETSc SNES type.

   The SNES solves the generalized equation 0 in c(u) + Q(u) with c(u) = P u - f given by the
   user's SNES function (F(u) = P u - f, or F(u) = P u with SNESSolve(snes, f, u)) and P by the
   user's Jacobian. Every SNES vector is a sequence of 3-blocks (u_t1, u_t2, u_n), one per contact
   node, with non-penetration u_n >= 0; Q is the Coulomb friction law (DERIVATION.md section 0).
*/
#include <petscsnes.h>

#if defined(PETSC_USE_COMPLEX)
  #error "ssstar needs a PETSc with real scalars"
#endif

#define SNESSSSTAR "ssstar"

/* The contact states of Table 1 (DERIVATION.md section 2); values are written to output files. */
typedef enum {
  SSSTAR_STATE_L   = 0, /* no contact                       */
  SSSTAR_STATE_M1  = 1, /* strong contact, sliding          */
  SSSTAR_STATE_M2  = 2, /* weak contact, sliding            */
  SSSTAR_STATE_M3P = 3, /* strong contact, strong sticking  */
  SSSTAR_STATE_M3M = 4, /* strong contact, weak sticking    */
  SSSTAR_STATE_M4  = 5  /* weak contact, weak sticking      */
} SSStarState;
#define SSSTAR_NUM_STATES 6
PETSC_EXTERN const char *const SSStarStateNames[];

/* Why an ssstar solve stopped, finer than SNESConvergedReason. */
typedef enum {
  SSSTAR_REASON_ITERATING = 0,
  SSSTAR_REASON_CONVERGED,        /* ||z|| <= atol                                 */
  SSSTAR_REASON_MAX_IT,           /* no convergence within -snes_max_it            */
  SSSTAR_REASON_NAN,              /* ||z|| is NaN or Inf                            */
  SSSTAR_REASON_SINGULAR_NEWTON   /* the reduced Newton matrix S P + T is singular  */
} SSStarReason;
PETSC_EXTERN const char *const SSStarReasons[];

PETSC_EXTERN PetscErrorCode SSStarInitializePackage(void);
PETSC_EXTERN PetscErrorCode SNESSSStarSetContactProblem(SNES, Mat, Vec);
PETSC_EXTERN PetscErrorCode SSStarFinalizePackage(void);

PETSC_EXTERN PetscErrorCode SNESSSStarSetFriction(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetFriction(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetScaling(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetScaling(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetTolerance(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetTolerance(SNES, PetscReal *);
PETSC_EXTERN PetscErrorCode SNESSSStarSetStateTolerance(SNES, PetscReal);
PETSC_EXTERN PetscErrorCode SNESSSStarGetStates(SNES, const SSStarState *[], PetscInt[SSSTAR_NUM_STATES]);
PETSC_EXTERN PetscErrorCode SNESSSStarGetReason(SNES, SSStarReason *);
PETSC_EXTERN PetscErrorCode SNESSSStarMonitorStates(SNES, PetscInt, PetscReal, PetscViewerAndFormat *);

/*
   Per-node kernels: pure functions on 3-vectors (tangential components first, normal last).
   Matrices are 3x3, row-major.
*/
/* Approximation step (11)-(12), DERIVATION.md section 1: from the iterate u and c = P u - f. */
PETSC_EXTERN void SSStarApproximationStep(PetscReal phi, const PetscReal u[3], const PetscReal c[3], PetscReal z[3], PetscReal d[3], PetscReal b[3]);
/* Table 1 for (d, b) in gph Q, section 2. */
PETSC_EXTERN SSStarState SSStarClassify(PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal tol_d, PetscReal tol_b);
/* G, H with range [G; H] = tangent space of gph Q at (d, b), section 3. */
PETSC_EXTERN void SSStarTangentBlocks(SSStarState state, PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal G[9], PetscReal H[9]);
/* S, T of the 3p Newton system (S P + T) du = (S + T) z, section 5. */
PETSC_EXTERN void SSStarReducedBlocks(SSStarState state, PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal S[9], PetscReal T[9]);

#endif
