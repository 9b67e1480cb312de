#ifndef SSSTARIMPL_H
#define SSSTARIMPL_H

#include <ssstar.h>
#include <ssstarreduction.h>
#include <petsc/private/snesimpl.h>

PETSC_EXTERN PetscLogEvent SSSTAR_ApproxStep, SSSTAR_NewtonStep, SSSTAR_LineSearch;
/* parts of the Newton step with a dense P: A_RR and its right-hand side, LU factorizations, Krylov solves on old factors */
PETSC_EXTERN PetscLogEvent SSSTAR_NewtonAssemble, SSSTAR_NewtonFactor, SSSTAR_NewtonKrylov;

/*
   The Newton step (newton.c): solves (gamma S R P R^T + T) dv = y (DERIVATION.md section 5 in the nodes' frames R)
   and returns du = R^T dv (global frame), given P (global frame) and, per local node, R, S and T (9 values each,
   row-major). Created with the SNES (it keeps
   the settings); Reset drops what was built for a P. Counts and the condition estimate are of the current SNESSolve.
*/
typedef struct _n_SSStarNewton *SSStarNewton;
PETSC_INTERN PetscErrorCode SSStarNewtonCreate(SNES, SSStarNewton *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetReuse(SSStarNewton, PetscReal);
PETSC_INTERN PetscErrorCode SSStarNewtonGetReuse(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetLUThreads(SSStarNewton, PetscInt);
PETSC_INTERN PetscErrorCode SSStarNewtonGetLUThreads(SSStarNewton, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarNewtonSetOperator(SSStarNewton, Mat, PetscReal);
PETSC_INTERN PetscErrorCode SSStarNewtonSolve(SSStarNewton, const PetscReal[], const PetscReal[], const PetscReal[], Vec, Vec, PetscBool *);
PETSC_INTERN PetscErrorCode SSStarNewtonGetConditionEstimate(SSStarNewton, PetscReal *);
PETSC_INTERN PetscErrorCode SSStarNewtonGetCounts(SSStarNewton, PetscInt *, PetscInt *, PetscInt *);
PETSC_INTERN PetscErrorCode SSStarNewtonView(SSStarNewton, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarNewtonReset(SSStarNewton);
PETSC_INTERN PetscErrorCode SSStarNewtonDestroy(SSStarNewton *);

/*
   The contact declaration and the reduced problem (contact.c). The solver's unknown is u, the displacement of the
   contact dofs in the global frame (3 per node); in node i's frame it is v_i = R_i u_i + g_i e_3, with v_i3 >= 0.
*/
typedef struct {
  /* as declared by the user */
  IS                  dofs;         /* contact dofs of the SNES vector, 3 per owned node; NULL: every dof     */
  Vec                 normals;      /* 3 per node, or NULL for (0, 0, 1)                                    */
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
  SSStarFriction  *nodeFriction;    /* per node; Tresca bounds as forces                                    */
  PetscBool        hasFriction;     /* some node has friction (global)                                     */
  PetscInt         lawCounts[3];    /* nodes per law (global)                                               */

  /* the reduced problem c(u) = P u - f, kept while K and the declaration are unchanged */
  SSStarReduction  reduction;       /* NULL in the reduced use                                              */
  Mat              K;               /* the Jacobian the reduction was computed from                          */
  PetscObjectState Kstate;
  Mat              P;
  Vec              b, f;            /* the whole load b = -F(0) and its reduction f                          */
} SSStarContact;

PETSC_INTERN PetscErrorCode SSStarContactSetUp(SNES, SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactSetUpProblem(SNES, SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactGetInitialGuess(SSStarContact *, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarContactSetSolution(SSStarContact *, Vec, Vec, Vec);
PETSC_INTERN PetscErrorCode SSStarContactReset(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactDestroy(SSStarContact *);
PETSC_INTERN PetscErrorCode SSStarContactView(SSStarContact *, PetscViewer);
PETSC_INTERN PetscErrorCode SSStarContactSetLaw(SSStarContact *, SSStarFrictionLaw, PetscReal);
PETSC_INTERN PetscErrorCode SNESSSStarSetContactNodes_SSStar(SNES, IS, Vec, Vec);
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
  PetscBool on;            /* damped steps and remedies; off: the plain iteration of DERIVATION.md section 7   */
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
} SSStarGlobalization;

typedef struct {
  SSStarContact contact;

  /* the method */
  SSStarMethod method;       /* Newton (default) or the fixed-point baseline                          */
  PetscReal    scaling_user; /* gamma as set by the user; 0 means 1/mean(diag P)                     */
  PetscReal    scaling;      /* gamma in use for the current solve                                    */
  PetscReal    state_tol;    /* tau of the classification (section 2)                                 */
  PetscReal    scale;        /* ||gamma f||: the problem's displacement scale in the stopping rule    */
  SSStarReason reason;

  /* the iteration, per local node in the solver's order */
  SSStarState *states;                     /* at the last iterate                                   */
  SSStarState *userStates;                 /* the same in the user's node order                     */
  PetscInt     counts[SSSTAR_NUM_STATES];  /* global counts per state                               */
  PetscReal   *S, *T;                      /* blocks of the Newton system, 9 per node               */
  Vec          u, c, z, d, b, y, dv;       /* u, c = P u - f, dv (global frame); z, d, b, y (nodes' frames) */
  Vec          ut, ct, ua, ca;             /* trial iterates and their P u - f: the full step, a damped one  */
  SSStarNewton newton;
  SSStarGlobalization glob;
} SNES_SSStar;

/* ssstar.c: the per-node work of an iteration on any iterate (u, c) */
PETSC_INTERN PetscErrorCode SNESSSStarApproximationStep(SNES, Vec, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode SNESSSStarAddStep(SNES, Vec, PetscReal, Vec);
PETSC_INTERN PetscErrorCode SNESSSStarResidual(SNES, Vec, Vec);

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
