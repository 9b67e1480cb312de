#ifndef SSSTARIMPL_H
#define SSSTARIMPL_H

#include <ssstar.h>
#include <ssstarreduction.h>
#include <petsc/private/snesimpl.h>

PETSC_EXTERN PetscLogEvent SSSTAR_ApproxStep, SSSTAR_NewtonStep, SSSTAR_LineSearch;
/* parts of the Newton step with a dense P: A_RR and its right-hand side, LU factorizations, Krylov solves on old factors */
PETSC_EXTERN PetscLogEvent SSSTAR_NewtonAssemble, SSSTAR_NewtonFactor, SSSTAR_NewtonKrylov;

/*
   The Newton step (newton.c and one file per implementation, newtonimpl.h): for the per-node blocks S, T of
   docs/derivation.md section 5 it solves the Newton system on the operator A of the solve (P, or K on the whole body)
   and returns du in the global frame. Created with the SNES (it keeps the settings); each SNESSolve gives it the
   operator, the implementation that fits it and the contact nodes' layout. Counts are of the current SNESSolve.
*/
typedef enum {
  SSSTAR_NEWTON_DENSE,  /* dense P: known dofs eliminated, LU of the rest, GMRES on an older LU        */
  SSSTAR_NEWTON_SPARSE, /* sparse P (the user's): the Newton matrix factored by the SNES's KSP         */
  SSSTAR_NEWTON_FULL    /* the whole body: K with the contact rows, Krylov + algebraic multigrid      */
} SSStarNewtonType;
PETSC_EXTERN const char *const SSStarNewtonTypes[];

/* Where the contact nodes are in the operator's vectors, and their frames */
typedef struct {
  PetscInt         nnodes; /* local contact nodes                                              */
  const PetscInt  *dofs;   /* 3 per node: the local offsets of its dofs in the operator's vectors */
  const PetscReal *frames; /* 9 per node (rows t1, t2, n), or NULL for identities                */
} SSStarContactLayout;

/* the multigrid of an earlier Newton matrix is kept while at most this fraction of the nodes changed known rows */
#define SSSTAR_PC_REUSE_DEFAULT 0.3

typedef struct _n_SSStarNewton *SSStarNewton;
PETSC_INTERN PetscErrorCode SSStarNewtonCreate(SNES, SSStarNewton *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetReuse(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode SSStarNewtonGetReuse(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetPCReuse(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode SSStarNewtonGetPCReuse(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetLUThreads(SSStarNewton, PetscInt);
PETSC_INTERN PetscErrorCode SSStarNewtonGetLUThreads(SSStarNewton, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetOperator(SSStarNewton, SSStarNewtonType, Mat, PetscReal, const SSStarContactLayout *);
PETSC_INTERN PetscErrorCode SSStarNewtonGetType(SSStarNewton, SSStarNewtonType *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetScaling(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode SSStarNewtonSetTolerances(SSStarNewton, PetscReal, PetscReal);
PETSC_INTERN PetscErrorCode SSStarNewtonSolve(SSStarNewton, const PetscReal[], const PetscReal[], Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarNewtonSolveKnown(SSStarNewton, Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarNewtonRefine(SSStarNewton, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarNewtonGetConditionEstimate(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarNewtonGetCounts(SSStarNewton, PetscInt *, PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarNewtonGetSteps(SSStarNewton, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarNewtonView(SSStarNewton, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarNewtonReset(SSStarNewton);
PETSC_INTERN PetscErrorCode SSStarNewtonDestroy(SSStarNewton *);

/*
   The contact declaration and the problem the iteration runs on (contact.c). The solver's unknown u lives in the
   vectors of an operator A: the contact dofs in the global frame (3 per node; in node i's frame v_i = R_i u_i + g_i e_3,
   with v_i3 >= 0) and, on the whole body, the other dofs too (free dofs).

     reduced use:          A = the user's P (every dof a contact dof), u = u_C
     whole body, a Schur reduction of K:  A = P = K_CC - K_CI K_II^-1 K_IC, load f, u = u_C
     whole body, reduction none:          A = K, load b, u = the whole displacement (P never formed)
*/
typedef struct {
  /* as declared by the user */
  IS                  dofs;         /* contact dofs of the SNES vector, 3 per owned node; NULL: every dof     */
  Vec                 normals;      /* 3 per node, or NULL for (0, 0, 1)                                    */
  Mat                 B;            /* the contact operator (operator.c), or NULL: the nodes against planes */
  Vec                 gaps;         /* 1 per node, or NULL for 0                                            */
  SSStarFrictionLaw   law;          /* of the nodes without a law of their own                              */
  PetscReal           friction;     /* phi of the nodes without a coefficient of their own                  */
  Vec                 coefficients; /* phi per node, or NULL                                                */
  Vec                 bounds;       /* Tresca slip bound per node, or NULL                                  */
  SSStarFrictionLaw  *nodeLaws;     /* per owned node, or NULL                                              */
  PetscInt            nNodeLaws;
  SSStarReductionType reductionType;
  PetscReal           memoryLimit;  /* GB per rank for the reduction; 0: MemAvailable of the node per rank  */
  PetscObjectState    declared;     /* bumped by every setter: the per-node data are rebuilt when it moved  */

  /* derived, in the solver's node order (nodes sorted by their first dof) */
  PetscObjectState built;           /* value of declared the per-node data were built for                  */
  PetscInt         nnodes;          /* owned contact nodes                                                  */
  IS               isC, isI;        /* contact dofs in the solver's order, and the other owned dofs         */
  PetscInt        *order;           /* solver's node i is the user's node order[i]                          */
  PetscReal       *frames;          /* 9 per node (rows t1, t2, n), or NULL when every normal is (0, 0, 1)  */
  PetscReal       *gap;             /* per node, or NULL                                                    */
  PetscReal       *pointScale;      /* with B: d_i of each point (its block at its own dofs is d_i R_i)     */
  Mat              T;               /* with B and masters: u = T v, the change to the points' variables      */
  SSStarFriction  *nodeFriction;    /* per node; Tresca bounds as forces                                    */
  PetscBool        hasFriction;     /* some node has friction (global)                                     */
  PetscInt         lawCounts[3];    /* nodes per law (global)                                               */

  /* the problem c(u) = A u - f, kept while K and the declaration are unchanged */
  SSStarReduction  reduction;       /* NULL in the reduced use                                              */
  Mat              K;               /* the Jacobian the problem was set up from                             */
  Mat              Kw;              /* K in the points' variables, T^T K T (K itself without masters)       */
  PetscObjectState Kstate;
  PetscReal        meanDiag;        /* mean of the diagonal of K_CC (P in the reduced use)                  */
  PetscReal        maxRowSum;       /* largest sum |K_ij| of a contact row: a bound of lambda_max(P)        */
  Mat              A;               /* the operator: P, or K (reduction none)                               */
  Vec              b, bw, f;        /* the whole load b = -F(0), T^T b, and A's load f (reduced, or bw)     */
  SSStarNewtonType newtonType;      /* the Newton step that fits A                                          */
  PetscInt        *layoutDofs;      /* 3 per node: its dofs' local offsets in A's vectors                   */
  PetscInt         nfree, *free;    /* the other local offsets of A's vectors (free dofs; none when reduced) */
} SSStarContact;

PETSC_INTERN PetscErrorCode SSStarContactSetUp(SNES, SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactSetUpProblem(SNES, SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactGetLayout(SSStarContact *, SSStarContactLayout *);
PETSC_INTERN PetscErrorCode SSStarContactGetInitialGuess(SSStarContact *, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarContactSetSolution(SSStarContact *, Vec, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarContactReset(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactDestroy(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactView(SSStarContact *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarContactSetLaw(SSStarContact *, SSStarFrictionLaw, PetscReal);
PETSC_INTERN PetscErrorCode SNESSSStarSetContactNodes_SSStar(SNES, IS, Vec, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarSetContactOperator_SSStar(SNES, IS, Mat, Vec);
/* operator.c: the contact operator B and the change of variables T */
PETSC_INTERN PetscErrorCode SSStarContactBuildOperator(MPI_Comm, SSStarContact *, Vec);
PETSC_INTERN PetscErrorCode SSStarContactTransformStiffness(SSStarContact *, Mat, Mat *);
PETSC_INTERN PetscErrorCode SSStarContactToPointVariables(SSStarContact *, Vec, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarSetFrictionCoefficients_SSStar(SNES, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarSetSlipBounds_SSStar(SNES, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarSetNodeFrictionLaws_SSStar(SNES, PetscInt, const SSStarFrictionLaw[]);

/*
   The globalization (globalization.c): damped steps on the merit function ||z||, detection of cycles and
   stagnation, and the remedies of SSStarRemedy. README, "When it does not converge".
*/
typedef enum {
  SSSTAR_DETECTED_NONE,
  SSSTAR_DETECTED_CYCLE,      /* states as two iterations ago and ||z|| back to its value then, twice in a row */
  SSSTAR_DETECTED_STAGNATION  /* no new smallest ||z|| for stagnationIts iterations                            */
} SSStarDetection;

typedef struct {
  /* settings */
  PetscBool on;            /* damped steps and remedies; off: the plain iteration of docs/derivation.md section 7   */
  PetscReal dampingMin;    /* smallest damping factor alpha of the line search                                 */
  PetscInt  stagnationIts; /* iterations without a new smallest ||z|| before the solve stops                   */

  /* per solve */
  PetscReal       zbest;                      /* smallest ||z|| since the start or the last rescaling         */
  PetscInt        kbest;                      /* its iteration                                                  */
  PetscReal       zhist[4];                   /* ||z|| at k, k-1, k-2, k-3                                      */
  PetscInt        nhist;                      /* iterations recorded since the start or the last rescaling      */
  PetscBool       recurred;                   /* the previous iteration recurred to the one two before it      */
  SSStarState    *older[2];                   /* local states at k-1 and k-2                                     */
  PetscInt        nnodes;                     /* local nodes of older[]                                          */
  PetscInt        lsFailures;                 /* failed line searches: odd ones take the full step, even rescale */
  PetscInt        counts[SSSTAR_NUM_REMEDIES];
  PetscInt        cycles;                     /* cycles detected                                                 */
  PetscReal       gamma0;                     /* the scaling the solve started with                              */

  /* the remedies on the way to the next iterate, and those that led to the current one with what was detected at
     it (printed by -snes_ssstar_monitor_states) */
  PetscBool       pending[SSSTAR_NUM_REMEDIES], shown[SSSTAR_NUM_REMEDIES];
  PetscReal       alpha, shownAlpha;          /* damping of the step (1: full, 0: no step)                      */
  SSStarDetection detected;
  PetscInt        flipping;                   /* nodes whose state has period 2                                 */
  PetscInt        changed;                    /* nodes whose state is not that of the previous iterate (-1: none) */
} SSStarGlobalization;

typedef struct {
  SSStarContact contact;

  /* the method */
  SSStarMethod method;       /* Newton (default) or the fixed-point baseline                          */
  PetscReal    scaling_user; /* gamma as set by the user; 0 means 1/mean(diag K_CC)                  */
  PetscReal    scaling;      /* gamma in use for the current solve                                    */
  PetscReal    state_tol;    /* tau of the classification (section 2)                                 */
  PetscReal    scale;        /* ||gamma f||: the problem's displacement scale in the stopping rule    */
  PetscReal    fnorm_inf;    /* ||f||_inf, f the load reduced to the contact dofs                     */
  PetscReal    etaMax;       /* whole body: the loosest relative tolerance of a Newton step's solve   */
  SSStarReason reason;
  PetscReal    tolerance;    /* the threshold of the last convergence test: max(atol, rtol max(||u||, ||gamma f||)) */

  /* the iteration, per local node in the solver's order */
  SSStarState *states;                     /* at the last iterate                                   */
  SSStarState *userStates;                 /* the same in the user's node order                     */
  PetscInt     counts[SSSTAR_NUM_STATES];  /* global counts per state                               */
  PetscReal   *S, *T;                      /* blocks of the Newton system, 9 per node               */
  /* in the layout of the operator's vectors (the contact nodes' entries in the global frame, unless said) */
  Vec          u, c, z, y, dv;             /* u, c = A u - f, dv; z, y: the nodes' frames at the contact dofs */
  Vec          ut, ct, ua, ca;             /* trial iterates and their A u - f: the full step, a damped one  */
  Vec          d, b;                       /* 3 per node, the nodes' frames                                 */
  SSStarNewton newton;
  SSStarGlobalization glob;
} SNES_SSStar;

/* ssstar.c: the per-node work of an iteration on any iterate (u, c) */
PETSC_INTERN PetscErrorCode SNESSSStarApproximationStep(SNES, Vec, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode SNESSSStarFixedPointStep(SNES, Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SNESSSStarResidual(SNES, Vec, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarRefineNewtonStep(SNES, PetscReal, PetscBool *);

/* globalization.c */
PETSC_INTERN PetscErrorCode SSStarGlobalizationBegin(SNES);
PETSC_INTERN PetscErrorCode SSStarGlobalizationDetect(SNES, PetscInt, PetscReal);
PETSC_INTERN PetscErrorCode SSStarGlobalizationRecord(SSStarGlobalization *, SSStarRemedy);
PETSC_INTERN PetscErrorCode SSStarGlobalizationStep(SNES, PetscInt, PetscReal, SSStarReason *);
PETSC_INTERN PetscErrorCode SSStarGlobalizationBreakCycle(SNES, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarGlobalizationFixedPoint(SNES, PetscReal, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarGlobalizationView(SSStarGlobalization *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarGlobalizationViewCounts(SSStarGlobalization *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarGlobalizationFormatEvents(SSStarGlobalization *, char[], size_t);
PETSC_INTERN PetscErrorCode SSStarGlobalizationDestroy(SSStarGlobalization *);

#endif
