#ifndef SSSTARNEWTONIMPL_H
#define SSSTARNEWTONIMPL_H

/*
   The Newton step of ssstar (docs/derivation.md section 5) behind an ops table, one implementation per file,
   registered by name (newtonregall.c):

     newton_dense.c   P dense (a Schur complement): the known dofs eliminated, LU of the rest (denselu.c), GMRES on an
                      older LU while few nodes changed
     newton_sparse.c  P sparse (a reduced problem given by the user): the Newton matrix formed and factored by a KSP
     newton_wholebody.c    the whole body, P never formed: K with each contact node's rows, Krylov + algebraic multigrid

   Every implementation solves, for the per-node blocks S, T (row-major 3x3, nodes' frames) and y in the layout of the
   vectors of A (the contact nodes' entries in their frames, the other entries free dofs),

     contact node i:  gamma S_i R_i (A du)_i + T_i R_i du_i = y_i
     free dof j:      gamma (A du)_j = y_j

   for du (global frame, the layout of A's vectors). A is P in a reduced space (no free dofs: section 5
   itself) and K on the whole body, whose free rows keep the body in equilibrium. SolveKnown is the same system with
   every contact dof known (S_i = 0, T_i = I): du_i = R_i^T y_i, and on the whole body the free dofs follow.

   Floating bodies (layout.floating, docs/derivation.md (14.5)): the rigid-body motions U the step's states leave free
   (floating->nfree of them, at the contact dofs) get a proximal term, A + SSSTAR_FREE_STIFFNESS / gamma U U^T.
*/
#include "../ssstarimpl.h"

typedef struct _SSStarNewtonOps *SSStarNewtonOps;
struct _SSStarNewtonOps {
  PetscErrorCode (*setup)(SSStarNewton);                                                                   /* for nt->A */
  PetscErrorCode (*setscaling)(SSStarNewton);                                                              /* nt->gamma changed */
  PetscErrorCode (*solve)(SSStarNewton, const PetscReal[], const PetscReal[], Vec, Vec, PetscBool *);       /* S, T, y, du */
  PetscErrorCode (*solveknown)(SSStarNewton, Vec, Vec, PetscBool *);                                       /* y, du; NULL: du = R^T y */
  PetscErrorCode (*refine)(SSStarNewton, Vec, PetscBool *);                                                /* du; NULL: solves are exact */
  PetscErrorCode (*view)(SSStarNewton, PetscViewer);
  PetscErrorCode (*reset)(SSStarNewton); /* drops what was built for A */
};

struct _n_SSStarNewton {
  struct _SSStarNewtonOps ops;
  char                   *type; /* its registered name */
  void                   *data; /* the implementation's */
  SNES                    snes;

  /* the stiffness A of the current solve (P, or K on the whole body) */
  Mat                 A;
  PetscObjectState    Astate; /* A's state when the implementation was set up for it */
  PetscReal           gamma;
  SSStarContactLayout layout;

  /* settings, kept across stiffnesses and types */
  PetscReal reuse;     /* dense: solve on an older LU while at most this fraction of the nodes changed their known dofs  */
  PetscInt  luThreads; /* dense: rank 0's BLAS threads for the LU on several ranks; 0: the cores it may use             */
  PetscReal pcReuse;   /* whole body: keep the multigrid of an earlier Newton matrix while at most this fraction changed */
  PetscInt  plainDofs; /* whole body: plain aggregation from this many dofs of K (negative: only where smoothed does not fit) */
  PetscInt  smoothedFits; /* whole body: the caller's estimate says smoothed aggregation fits the memory (1) or not (0); -1: none given */
  PetscReal overCorrection; /* whole body: the W-cycled levels' coarse corrections times this (1: as the Galerkin ones) */
  PetscInt  wLevels;        /* whole body: plain aggregation's finest levels that W-cycle                               */
  PetscReal rtol, atol; /* whole body: tolerances of the next linear solve (its residual in the units of gamma^-1 y)    */

  /* counts of the current SNESSolve */
  PetscReal rcond;     /* of the last factored Newton matrix, -1 if unknown                       */
  PetscInt  nSteps;    /* Newton systems solved (SolveKnown included)                              */
  PetscInt  nFactor;   /* dense, sparse: LU factorizations; whole body: multigrid set-ups         */
  PetscLogDouble factorSeconds; /* the wall time of the factorizations or multigrid set-ups                */
  PetscInt  nReused;   /* steps solved on an older factorization or multigrid                      */
  PetscInt  nKrylov;   /* Krylov iterations of all steps                                           */
  PetscInt  nFallback; /* dense: steps on an old LU that fell back to a fresh one                  */
  PetscInt  nRefined;  /* whole body: steps solved on to tighter tolerances after their first solve */
};

/* the proximal term on the free motions of floating bodies, in units of 1/gamma: the approximation step's stiffness */
#define SSSTAR_FREE_STIFFNESS 1.0

/* Create_<type> fills the ops and says whether the SNES's KSP is its (snes->usesksp) */
PETSC_INTERN PetscErrorCode SSStarNewtonCreate_Dense(SSStarNewton);
PETSC_INTERN PetscErrorCode SSStarNewtonCreate_Sparse(SSStarNewton);
PETSC_INTERN PetscErrorCode SSStarNewtonCreate_WholeBody(SSStarNewton);

/* The SNES's KSP solves the Newton systems of the sparse and whole-body paths: their defaults unless -ksp_type/-pc_type */
PETSC_INTERN PetscErrorCode SSStarNewtonSetKSPDefaults(SSStarNewton, KSPType, PCType);
/* Rows of a node that say "dv_r = y_r": S row r = 0 and T row r = e_r */
PETSC_INTERN PetscBool SSStarKnownRow(const PetscReal[9], const PetscReal[9], PetscInt);
/* x = R^T y, x += R^T y (R NULL: identity) */
PETSC_INTERN void SSStarRotateBack(const PetscReal *, const PetscScalar[3], PetscScalar[3]);

/*
   The whole body's Newton matrix formed in K's own storage for each linear solve, K's entries put back after it
   (wholebodymatrix.c; newton_wholebody.c says what M is): Create reads K's contact rows and columns, Form writes M for the
   blocks S, T (and eliminates the known rows, updating rhs), Restore puts K back.
*/
typedef struct _n_SSStarWholeBodyMatrix *SSStarWholeBodyMatrix;
PETSC_INTERN PetscErrorCode SSStarWholeBodyMatrixCreate(Mat, const SSStarContactLayout *, SSStarWholeBodyMatrix *);
PETSC_INTERN PetscErrorCode SSStarWholeBodyMatrixInPlace(SSStarWholeBodyMatrix, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarWholeBodyMatrixForm(SSStarWholeBodyMatrix, const PetscReal[], const PetscReal[], PetscReal, PetscInt, const PetscInt[], Vec, Vec, Mat *);
PETSC_INTERN PetscErrorCode SSStarWholeBodyMatrixRestore(SSStarWholeBodyMatrix);
PETSC_INTERN PetscErrorCode SSStarWholeBodyMatrixDestroy(SSStarWholeBodyMatrix *);

/*
   The LU of a dense matrix distributed by rows (denselu.c): the rows gathered on rank 0 and factored by LAPACK there,
   while the other ranks sleep (rank 0's OpenBLAS may use their cores).
*/
typedef struct {
  PetscInt      N;               /* order; -1 before the first factorization          */
  PetscMPIInt  *counts, *displs; /* rows per rank                                     */
  PetscScalar  *lu, *work;       /* rank 0: the factors (column-major), a vector      */
  size_t        capacity;        /* of lu                                             */
  PetscBLASInt *pivots;
  PetscReal     rcond;           /* LAPACK's estimate of 1/cond_1, or -1               */
  int           threads;         /* rank 0's BLAS threads during the factorization (0: leave them) */
} SSStarDenseLU;

PETSC_INTERN PetscErrorCode SSStarDenseLUSetThreads(MPI_Comm, PetscInt, SSStarDenseLU *);
PETSC_INTERN PetscErrorCode SSStarDenseLUFactor(Mat, SSStarDenseLU *, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarDenseLUSolve(MPI_Comm, SSStarDenseLU *, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarDenseLUDestroy(SSStarDenseLU *);

#endif
