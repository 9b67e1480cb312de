#ifndef SSSTARIMPL_H
#define SSSTARIMPL_H

#include <ssstar.h>
#include <petsc/private/snesimpl.h>

PETSC_EXTERN PetscLogEvent SSSTAR_ApproxStep, SSSTAR_NewtonStep;

typedef struct {
  PetscReal    friction;      /* phi                                                 */
  PetscReal    scaling_user;  /* gamma as set by the user; 0 means 1/mean(diag P)    */
  PetscReal    scaling;       /* gamma in use for the current solve                  */
  PetscReal    atol;          /* stopping rule ||z|| <= atol                          */
  PetscReal    state_tol;     /* tau of the classification (section 2)               */
  SSStarReason reason;
  PetscInt     nnodes;        /* contact nodes owned by this rank                    */
  SSStarState *states;        /* state of each local node at the last iterate        */
  PetscInt     counts[SSSTAR_NUM_STATES]; /* global counts per state                 */
  Mat          S, T;          /* block-diagonal factors of the 3p Newton system      */
  Mat          P;             /* the P that SP was computed with (not referenced)   */
  Mat          SP, A;         /* S P and the Newton matrix A = gamma S P + T         */
  PetscBool    scalapack;     /* A is distributed dense: factor a MATSCALAPACK copy   */
  Mat          Ascalapack;
  Vec          yScalapack, duScalapack;
  VecScatter   toScalapack;
} SNES_SSStar;

#endif
