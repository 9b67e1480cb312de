/*
   Per-node contact kernels of the semismooth* Newton method: pure functions on 3-vectors (u_t1, u_t2, u_n) in the
   node's frame. Section and equation numbers refer to docs/derivation.md.

   What every friction law shares: the normal part of the approximation step (1.1), the states of Table 1 (2.1), the
   blocks G, H, S, T of each state (3.1), (5.2) and the node frames. What depends on the law (its tangential step, how
   far inside its friction set a force is, a sliding node's W and coupling) is in laws/, one file per law
   (laws/lawimpl.h): Q(u) = { (g_t, lam) : lam in N_R+(u3), g_t in -lam d sigma(u_t) } for the Coulomb-type laws with
   the support function sigma of their friction set (coulomb: phi |.|, orthotropic: |M^1/2 .|), g_t in -s d|u_t| with
   a given bound s for tresca, g_t = 0 for none.
*/
#include "laws/lawimpl.h"

const char *const SSStarStateNames[] = {"L", "M1", "M2", "M3+", "M3-", "M4", "LS", "SSStarState", "SSSTAR_STATE_", NULL};

static PetscReal Norm2(const PetscReal v[2])
{
  return PetscSqrtReal(v[0] * v[0] + v[1] * v[1]);
}

/* (1.2): the prox of s|.| at v, block soft-thresholding; the "if" keeps d an exact zero when |v| <= s */
void SSStarSoftThreshold(PetscReal s, const PetscReal v[2], PetscReal d[2])
{
  const PetscReal nv = Norm2(v);

  if (nv > s) {
    d[0] = (1.0 - s / nv) * v[0];
    d[1] = (1.0 - s / nv) * v[1];
  } else {
    d[0] = 0.0;
    d[1] = 0.0;
  }
}

/*
   A sliding node of an isotropic law with the friction force s om, om = +d12/|d12| ((3.2): the slides' omega has the
   other sign, which breaks the quadratic convergence): W = s/|d12| (I - om om^T) (3.1) and the coupling k = kappa om,
   kappa the coefficient of the normal force in the sliding law (Coulomb: phi). Zero where s = 0.
*/
void SSStarIsotropicSliding(PetscReal s, PetscReal kappa, const PetscReal d[3], PetscReal W[4], PetscReal k[2])
{
  const PetscReal nd = Norm2(d);
  PetscReal       om[2], w;

  if (s == 0.0) {
    W[0] = W[1] = W[2] = W[3] = 0.0;
    k[0] = k[1] = 0.0;
    return;
  }
  om[0] = d[0] / nd;
  om[1] = d[1] / nd;
  w     = s / nd;
  W[0]  = w * (1.0 - om[0] * om[0]);
  W[1]  = -w * om[0] * om[1];
  W[2]  = W[1];
  W[3]  = w * (1.0 - om[1] * om[1]);
  k[0]  = kappa * om[0];
  k[1]  = kappa * om[1];
}

/*@C
   SSStarApproximationStep - the approximation step (11)-(12) at one node (docs/derivation.md section 1, (1.1)-(1.4))

   Not Collective

   Input Parameters:
+  fr - the node's friction law and its values (SSStarFrictionSet(); a force in the units of c)
.  u  - the iterate in the node's frame (t1, t2, n), gap included: non-penetration is u[2] >= 0
-  c  - (scaled) c = gamma (P u - f) in the node's frame

   Output Parameters:
+  z - the step: d = u + z
.  d - the projected point, with (d, b) in gph Q
-  b - b = -z - c

   Notes:
   A pure function; d[2], b[2] and d12 come out as exact zeros where the projection is active. The normal part is
   the same for every law; the tangential one is the law's (the prox of the normal force times the support function
   of its friction set).

   Level: developer

.seealso: `SSStarClassify()`, `SSStarTangentBlocks()`, `SSStarReducedBlocks()`, `SSStarFrictionSet()`
@*/
void SSStarApproximationStep(const SSStarFriction *fr, const PetscReal u[3], const PetscReal c[3], PetscReal z[3], PetscReal d[3], PetscReal b[3])
{
  const PetscReal v[2] = {u[0] - c[0], u[1] - c[1]};

  z[2] = PetscMax(-c[2], -u[2]); /* (1.1), the slides' (11) */
  d[2] = PetscMax(u[2] - c[2], 0.0);
  b[2] = -PetscMax(0.0, c[2] - u[2]);
  fr->law->ops.tangential(fr, PetscMax(0.0, c[2] - u[2]), v, d); /* (1.2)-(1.3), the slides' (12) */
  z[0] = d[0] - u[0];
  z[1] = d[1] - u[1];
  b[0] = -z[0] - c[0];
  b[1] = -z[1] - c[1];
}

/*@C
   SSStarClassify - the state of Table 1 of a point (d, b) of gph Q (docs/derivation.md section 2)

   Not Collective

   Input Parameters:
+  fr    - the node's friction law and its values
.  d     - the projected point of the approximation step, in the node's frame
.  b     - its partner in gph Q
.  tol_d - the tolerance of the zero tests on displacements
-  tol_b - the tolerance of the zero tests on (scaled) forces

   Notes:
   Returns the state. A sticking node is M3+ when its force lies inside the law's friction set by more than tol_b;
   the nodes of a law whose tangential law holds without contact (Tresca) may also be SSSTAR_STATE_LS (separated,
   tangentially stuck).

   Level: developer

.seealso: `SSStarApproximationStep()`, `SNESSSStarSetStateTolerance()`
@*/
SSStarState SSStarClassify(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal tol_d, PetscReal tol_b)
{
  const PetscBool sliding = (PetscBool)(Norm2(d) > tol_d);

  if (d[2] > tol_d) return sliding || !fr->law->separate ? SSSTAR_STATE_L : SSSTAR_STATE_LS;
  if (-b[2] <= tol_b) return sliding ? SSSTAR_STATE_M2 : SSSTAR_STATE_M4;
  if (sliding) return SSSTAR_STATE_M1;
  return fr->law->ops.margin(fr, b) > tol_b ? SSSTAR_STATE_M3P : SSSTAR_STATE_M3M;
}

static PetscBool IsStrongContact(SSStarState state)
{
  return (PetscBool)(state == SSSTAR_STATE_M1 || state == SSSTAR_STATE_M3P || state == SSSTAR_STATE_M3M);
}

static PetscBool IsSliding(SSStarState state)
{
  return (PetscBool)(state == SSSTAR_STATE_L || state == SSSTAR_STATE_M1 || state == SSSTAR_STATE_M2);
}

static void SetDiagonal(PetscReal M[9], PetscReal m0, PetscReal m1, PetscReal m2)
{
  for (int k = 0; k < 9; k++) M[k] = 0.0;
  M[0] = m0;
  M[4] = m1;
  M[8] = m2;
}

/*
   Which kind of blocks a node gets. The states of Table 1, where without friction (no tangential force at the node)
   every strong contact slides (section 3, "phi = 0"). A law whose tangential law holds without contact (Tresca): the
   normal state (closed when in strong contact) and the tangential one (sliding or stuck) apart.
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
  if (fr->law->separate) {
    k.tangent = PETSC_TRUE;
    k.slides  = IsSliding(state);
  } else {
    k.tangent = k.closed; /* g12 = 0 unless in strong contact */
    k.slides  = (PetscBool)(state == SSSTAR_STATE_M1 || (fr->law->ops.frictionless(fr) && k.closed));
  }
  return k;
}

/*
   The blocks (G, H) of (3.2) and (S, T) of (5.1)-(5.2) share their pattern: per tangential direction the identity of
   a free or a stuck one, W of a sliding node, and the normal row of a node in contact or not; they differ in where
   the normal-tangential coupling k of a sliding node in contact goes: -k into H's normal column, +k into S's.
*/
static void Blocks(SSStarState state, const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscBool reduced, PetscReal A[9], PetscReal B[9])
{
  const BlockKind k = GetBlockKind(state, fr);
  PetscReal       W[4], kk[2];

  SetDiagonal(A, 1.0, 1.0, k.closed ? 0.0 : 1.0);
  SetDiagonal(B, 0.0, 0.0, k.closed ? 1.0 : 0.0);
  if (!k.tangent) return;
  if (k.slides) {
    fr->law->ops.sliding(fr, d, b, W, kk);
    B[0] = W[0];
    B[1] = W[1];
    B[3] = W[2];
    B[4] = W[3];
    if (k.closed) {
      PetscReal *coupled = reduced ? A : B;

      coupled[2] = reduced ? kk[0] : -kk[0];
      coupled[5] = reduced ? kk[1] : -kk[1];
    }
  } else {
    A[0] = A[4] = 0.0;
    B[0] = B[4] = 1.0;
  }
}

/*@C
   SSStarTangentBlocks - G and H with range [G; H] the tangent space of gph Q at (d, b) for a node in the given state
   (docs/derivation.md section 3, with the corrected sign of omega, (3.2))

   Not Collective

   Input Parameters:
+  state - the node's state (SSStarClassify())
.  fr    - the node's friction law and its values
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
  Blocks(state, fr, d, b, PETSC_FALSE, G, H);
}

/*@C
   SSStarReducedBlocks - S and T of the node's rows of the reduced Newton system (S P + T) du = (S + T) z
   (docs/derivation.md section 5, (5.1)-(5.2)): T G = S H, [S T] of rank 3

   Not Collective

   Input Parameters:
+  state - the node's state (SSStarClassify())
.  fr    - the node's friction law and its values
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
  Blocks(state, fr, d, b, PETSC_TRUE, S, T);
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
