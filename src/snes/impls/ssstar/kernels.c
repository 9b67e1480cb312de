/*
   Per-node contact kernels of the semismooth* Newton method: pure functions on 3-vectors
   (u_t1, u_t2, u_n) in the node's frame. Section and equation numbers refer to docs/derivation.md.

   The friction law of a node is one of
     coulomb: Q(u) = { (-phi lam d|u12|, lam) : lam in N_R+(u3) }          (section 0)
     tresca:  Q(u) = s d|u12| x N_R+(u3), s the slip bound (no normal-tangential coupling)
     none:    Q(u) = {0} x N_R+(u3)                                          (frictionless)
   Tresca is Coulomb with the threshold phi (-g3) replaced by the constant s, so its blocks are
   the Coulomb ones without the coupling terms phi om, with separate normal and tangential states.
*/
#include <ssstar.h>

const char *const SSStarStateNames[]   = {"L", "M1", "M2", "M3+", "M3-", "M4", "LS", "SSStarState", "SSSTAR_STATE_", NULL};
const char *const SSStarFrictionLaws[] = {"none", "tresca", "coulomb", "SSStarFrictionLaw", "SSSTAR_FRICTION_", NULL};

static PetscReal Norm2(const PetscReal v[2])
{
  return PetscSqrtReal(v[0] * v[0] + v[1] * v[1]);
}

/*@C
   SSStarApproximationStep - the approximation step (11)-(12) at one node (docs/derivation.md section 1, (1.1)-(1.4))

   Not Collective

   Input Parameters:
+  fr - the node's friction law (a Tresca bound in the units of c)
.  u  - the iterate in the node's frame (t1, t2, n), gap included: non-penetration is u[2] >= 0
-  c  - (scaled) c = gamma (P u - f) in the node's frame

   Output Parameters:
+  z - the step: d = u + z
.  d - the projected point, with (d, b) in gph Q
-  b - b = -z - c

   Notes:
   A pure function; d[2], b[2] and d12 come out as exact zeros where the projection is active.

   Level: developer

.seealso: `SSStarClassify()`, `SSStarTangentBlocks()`, `SSStarReducedBlocks()`
@*/
void SSStarApproximationStep(const SSStarFriction *fr, const PetscReal u[3], const PetscReal c[3], PetscReal z[3], PetscReal d[3], PetscReal b[3])
{
  const PetscReal v[2] = {u[0] - c[0], u[1] - c[1]};

  z[2] = PetscMax(-c[2], -u[2]); /* (1.1), the slides' (11) */
  d[2] = PetscMax(u[2] - c[2], 0.0);
  b[2] = -PetscMax(0.0, c[2] - u[2]);
  if (fr->law == SSSTAR_FRICTION_NONE) {
    d[0] = v[0];
    d[1] = v[1];
  } else {
    /* (1.2)-(1.3), the slides' (12): block soft-thresholding with the threshold s; the "if" keeps d12 an exact zero
       when |v| <= s */
    const PetscReal s  = fr->law == SSSTAR_FRICTION_COULOMB ? fr->phi * PetscMax(0.0, c[2] - u[2]) : fr->bound;
    const PetscReal nv = Norm2(v);

    if (nv > s) {
      d[0] = (1.0 - s / nv) * v[0];
      d[1] = (1.0 - s / nv) * v[1];
    } else {
      d[0] = 0.0;
      d[1] = 0.0;
    }
  }
  z[0] = d[0] - u[0];
  z[1] = d[1] - u[1];
  b[0] = -z[0] - c[0];
  b[1] = -z[1] - c[1];
}

/* Tresca: normal and tangential states apart, mapped onto Table 1 (LS: separated and stuck) */
static SSStarState ClassifyTresca(PetscReal bound, const PetscReal d[3], const PetscReal b[3], PetscReal tol_d, PetscReal tol_b)
{
  const PetscBool sliding = (PetscBool)(Norm2(d) > tol_d);
  const PetscBool strong  = (PetscBool)(bound - Norm2(b) > tol_b);

  if (d[2] > tol_d) return sliding ? SSSTAR_STATE_L : SSSTAR_STATE_LS;
  if (-b[2] <= tol_b) return sliding ? SSSTAR_STATE_M2 : SSSTAR_STATE_M4;
  if (sliding) return SSSTAR_STATE_M1;
  return strong ? SSSTAR_STATE_M3P : SSSTAR_STATE_M3M;
}

/*@C
   SSStarClassify - the state of Table 1 of a point (d, b) of gph Q (docs/derivation.md section 2)

   Not Collective

   Input Parameters:
+  fr    - the node's friction law
.  d     - the projected point of the approximation step, in the node's frame
.  b     - its partner in gph Q
.  tol_d - the tolerance of the zero tests on displacements
-  tol_b - the tolerance of the zero tests on (scaled) forces

   Notes:
   Returns the state; Tresca nodes may also be SSSTAR_STATE_LS (separated, tangentially stuck).

   Level: developer

.seealso: `SSStarApproximationStep()`, `SNESSSStarSetStateTolerance()`
@*/
SSStarState SSStarClassify(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal tol_d, PetscReal tol_b)
{
  const PetscReal phi     = fr->law == SSSTAR_FRICTION_COULOMB ? fr->phi : 0.0;
  const PetscBool sliding = (PetscBool)(Norm2(d) > tol_d);

  if (fr->law == SSSTAR_FRICTION_TRESCA) return ClassifyTresca(fr->bound, d, b, tol_d, tol_b);
  if (d[2] > tol_d) return SSSTAR_STATE_L;
  if (-b[2] <= tol_b) return sliding ? SSSTAR_STATE_M2 : SSSTAR_STATE_M4;
  if (sliding) return SSSTAR_STATE_M1;
  return (-phi * b[2] - Norm2(b) > tol_b) ? SSSTAR_STATE_M3P : SSSTAR_STATE_M3M;
}

static PetscBool IsStrongContact(SSStarState state)
{
  return (PetscBool)(state == SSSTAR_STATE_M1 || state == SSSTAR_STATE_M3P || state == SSSTAR_STATE_M3M);
}

static PetscBool IsSliding(SSStarState state)
{
  return (PetscBool)(state == SSSTAR_STATE_L || state == SSSTAR_STATE_M1 || state == SSSTAR_STATE_M2);
}

/*
   The tangential slip of a node at (d, b): om = +d12/|d12| ((3.2): the slides' omega has the other sign, which breaks
   the quadratic convergence), W = s/|d12| (I - om om^T) (3.1) with s the threshold of the approximation step at (d, b)
   (Coulomb: -phi b3), and kappa, the coefficient of the normal force in the sliding law (Coulomb: phi; section 3).
   All vanish without friction.
*/
static void SlidingDirection(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal om[2], PetscReal W[4], PetscReal *kappa)
{
  const PetscReal nd = Norm2(d);
  PetscReal       s, w;

  switch (fr->law) {
  case SSSTAR_FRICTION_COULOMB:
    s      = -fr->phi * b[2];
    *kappa = fr->phi;
    break;
  case SSSTAR_FRICTION_TRESCA:
    s      = fr->bound;
    *kappa = 0.0;
    break;
  default:
    s      = 0.0;
    *kappa = 0.0;
  }
  if (s == 0.0) {
    om[0] = om[1] = 0.0;
    W[0] = W[1] = W[2] = W[3] = 0.0;
    return;
  }
  om[0] = d[0] / nd;
  om[1] = d[1] / nd;
  w     = s / nd;
  W[0]  = w * (1.0 - om[0] * om[0]);
  W[1]  = -w * om[0] * om[1];
  W[2]  = W[1];
  W[3]  = w * (1.0 - om[1] * om[1]);
}

static void SetDiagonal(PetscReal M[9], PetscReal m0, PetscReal m1, PetscReal m2)
{
  for (int k = 0; k < 9; k++) M[k] = 0.0;
  M[0] = m0;
  M[4] = m1;
  M[8] = m2;
}

/*
   Which kind of blocks a node gets. Coulomb and none: the states of Table 1, where without friction (phi = 0 or
   none) every strong contact slides (section 3, "phi = 0"). Tresca: the normal state (closed when in strong contact)
   and the tangential one (sliding or stuck) apart.
*/
typedef struct {
  PetscBool closed;  /* normal: u3 = 0 (and g3 free)       */
  PetscBool slides;  /* tangential: the sliding law holds  */
  PetscBool tangent; /* tangential part of Q not {0}: G12/H12 from sliding or sticking */
} BlockKind;

static BlockKind GetBlockKind(SSStarState state, const SSStarFriction *fr)
{
  BlockKind k;

  k.closed = IsStrongContact(state);
  if (fr->law == SSSTAR_FRICTION_TRESCA) {
    k.tangent = PETSC_TRUE;
    k.slides  = IsSliding(state);
  } else {
    const PetscBool frictionless = (PetscBool)(fr->law == SSSTAR_FRICTION_NONE || fr->phi == 0.0);

    k.tangent = k.closed; /* Coulomb: g12 = 0 unless in strong contact */
    k.slides  = (PetscBool)(state == SSSTAR_STATE_M1 || (frictionless && k.closed));
  }
  return k;
}

/*@C
   SSStarTangentBlocks - G and H with range [G; H] the tangent space of gph Q at (d, b) for a node in the given state
   (docs/derivation.md section 3, with the corrected sign of omega, (3.2))

   Not Collective

   Input Parameters:
+  state - the node's state (SSStarClassify())
.  fr    - the node's friction law
.  d     - the projected point
-  b     - its partner in gph Q

   Output Parameters:
+  G - 3x3, row-major
-  H - 3x3, row-major

   Level: developer

.seealso: `SSStarReducedBlocks()`, `SSStarClassify()`
@*/
void SSStarTangentBlocks(SSStarState state, const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal G[9], PetscReal H[9])
{
  const BlockKind k = GetBlockKind(state, fr);
  PetscReal       om[2], W[4], kappa;

  SetDiagonal(G, 1.0, 1.0, k.closed ? 0.0 : 1.0);
  SetDiagonal(H, 0.0, 0.0, k.closed ? 1.0 : 0.0);
  if (!k.tangent) return;
  if (k.slides) {
    SlidingDirection(fr, d, b, om, W, &kappa);
    H[0] = W[0];
    H[1] = W[1];
    H[3] = W[2];
    H[4] = W[3];
    if (k.closed) {
      H[2] = -kappa * om[0];
      H[5] = -kappa * om[1];
    }
  } else {
    G[0] = G[4] = 0.0;
    H[0] = H[4] = 1.0;
  }
}

/*@C
   SSStarReducedBlocks - S and T of the node's rows of the reduced Newton system (S P + T) du = (S + T) z
   (docs/derivation.md section 5, (5.1)-(5.2)): T G = S H, [S T] of rank 3

   Not Collective

   Input Parameters:
+  state - the node's state (SSStarClassify())
.  fr    - the node's friction law
.  d     - the projected point
-  b     - its partner in gph Q

   Output Parameters:
+  S - 3x3, row-major
-  T - 3x3, row-major

   Level: developer

.seealso: `SSStarTangentBlocks()`, `SSStarClassify()`
@*/
void SSStarReducedBlocks(SSStarState state, const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal S[9], PetscReal T[9])
{
  const BlockKind k = GetBlockKind(state, fr);
  PetscReal       om[2], W[4], kappa;

  SetDiagonal(S, 1.0, 1.0, k.closed ? 0.0 : 1.0);
  SetDiagonal(T, 0.0, 0.0, k.closed ? 1.0 : 0.0);
  if (!k.tangent) return;
  if (k.slides) {
    SlidingDirection(fr, d, b, om, W, &kappa);
    T[0] = W[0];
    T[1] = W[1];
    T[3] = W[2];
    T[4] = W[3];
    if (k.closed) {
      S[2] = kappa * om[0];
      S[5] = kappa * om[1];
    }
  } else {
    S[0] = S[4] = 0.0;
    T[0] = T[4] = 1.0;
  }
}

/*@C
   SSStarNodeFrame - the frame of a contact node from the obstacle's normal

   Not Collective

   Input Parameter:
.  n - the unit normal of the node's plane, into the body

   Output Parameter:
.  R - 3x3, row-major, with the rows t1, t2, n (normalized), right-handed; the identity for n = (0, 0, 1)

   Level: developer

.seealso: `SNESSSStarSetContactNodes()`
@*/
void SSStarNodeFrame(const PetscReal n[3], PetscReal R[9])
{
  const PetscReal nn  = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const PetscReal e[3] = {n[0] / nn, n[1] / nn, n[2] / nn};
  PetscReal       a[3] = {1, 0, 0}, t1[3], dot, nt;

  if (PetscAbsReal(e[0]) > 0.9) {
    a[0] = 0;
    a[1] = 1;
  }
  dot = a[0] * e[0] + a[1] * e[1] + a[2] * e[2];
  for (int k = 0; k < 3; k++) t1[k] = a[k] - dot * e[k];
  nt = PetscSqrtReal(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (int k = 0; k < 3; k++) {
    R[k]     = t1[k] / nt;
    R[6 + k] = e[k];
  }
  /* t2 = n x t1: (t1, t2, n) is right-handed */
  R[3] = e[1] * R[2] - e[2] * R[1];
  R[4] = e[2] * R[0] - e[0] * R[2];
  R[5] = e[0] * R[1] - e[1] * R[0];
}
