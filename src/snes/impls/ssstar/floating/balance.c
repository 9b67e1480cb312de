/*
   Floating bodies at the level of the iteration (docs/derivation.md section 14): whether the friction laws can hold
   them at all, before the first iteration, and the step along their free motions to the first contact.

   The balance (14.3)-(14.4). With g_k = rho_k . b the load's work on the rigid-body motions rho_k of K's null space
   and Rc_i their values at contact point i (its frame), an equilibrium needs contact forces mu_i in the friction
   cones K_i = { (D_i t, n) : |t| <= n } (D_i from the point's law: phi I for Coulomb, M^1/2 orthotropic, 0
   frictionless; a point without a cone, Tresca's, limits only n >= 0) with

       g + sum_i Rc_i^T mu_i = 0.

   In the variables t of the unit cone, Rc_i's tangential rows become D_i^T Rc_i's (Rs below). The least squares
   problem min over mu in K of 1/2 |g + A mu|^2 (A mu = sum_i Rc_i^T mu_i) has the value 0 then.
   When it does not, its residual r = g + A mu* is a rigid motion along which the load does positive work
   (g . r = |r|^2) while every contact point moves into its dual cone (Rc_i r in K_i*: it lifts off, or slides no
   closer to its obstacle than its friction angle allows), which no admissible contact force resists: no equilibrium
   exists (Farkas' lemma), whatever the elasticity. Solved by accelerated projected gradients (FISTA with restarts)
   from the contact forces of the first iterate; a load within round-off of the limit is left to the iteration.
*/
#include "../ssstarimpl.h"
#include "../laws/lawimpl.h"

/* the balance by accelerated projected gradients: iterations, and a test of the dual motion every this many */
#define SSSTAR_BALANCE_MAX_IT   20000
#define SSSTAR_BALANCE_TEST_ITS 20
/* balanced: the unbalanced part below SSSTAR_BALANCE_TOL of the load's part on the motions; not balanced: above
   SSSTAR_BALANCE_MIN, steady to SSSTAR_BALANCE_STEADY over a test's iterations, and the dual motion in the dual cones
   to SSSTAR_BALANCE_DUAL of its largest value */
#define SSSTAR_BALANCE_TOL    1e-10
#define SSSTAR_BALANCE_MIN    1e-6
#define SSSTAR_BALANCE_STEADY 1e-9
#define SSSTAR_BALANCE_DUAL   1e-4
/* a Newton step's part on the free motions is carried on only when it is at least this fraction of the step */
#define SSSTAR_FREE_PART_MIN 1e-3

/* x projected onto the cone |x_t| <= s x_n (s = infinity: x_n >= 0 alone; s is 0, 1 or infinity here) */
static void ProjectCone(PetscReal s, PetscReal x[3])
{
  const PetscReal t = PetscSqrtReal(x[0] * x[0] + x[1] * x[1]), n = x[2];

  if (PetscIsInfReal(s)) {
    x[2] = PetscMax(n, 0.0);
  } else if (s == 0) {
    x[0] = x[1] = 0;
    x[2]        = PetscMax(n, 0.0);
  } else if (t <= s * n) {
    return;
  } else if (s * t <= -n) {
    x[0] = x[1] = x[2] = 0;
  } else {
    const PetscReal a = (s * t + n) / (1 + s * s);

    x[0] *= s * a / t;
    x[1] *= s * a / t;
    x[2] = a;
  }
}

/* How far w lies outside the dual cone of |x_t| <= s x_n, which is s |w_t| <= w_n (s = infinity: w_t = 0, w_n >= 0) */
static PetscReal DualViolation(PetscReal s, const PetscReal w[3])
{
  const PetscReal t = PetscSqrtReal(w[0] * w[0] + w[1] * w[1]);

  if (PetscIsInfReal(s)) return t + PetscMax(0.0, -w[2]);
  return PetscMax(0.0, s * t - w[2]);
}

typedef struct {
  PetscInt   m, n;     /* motions, local points                                                  */
  PetscReal *Rc;       /* the null space's values at the points in the variables of the unit cones   */
  PetscReal *Rc0;      /* and as they are (the scale of the dual motion)                          */
  PetscReal *slope;    /* per point: 1 (its cone), 0 (frictionless), infinity (no cone: n >= 0 alone) */
  PetscBool *moved;    /* per point: some motion moves it                                         */
  MPI_Comm   comm;
} Balance;

/*
   The motions' values at the points in the variables of the unit cones, Rs_i = [D_i^T Rc_t; Rc_n] (a point whose law
   has no cone keeps Rc_i, its tangential force free), its cone, and the largest eigenvalue of Rs^T Rs (by powers of
   the m x m matrix): the Lipschitz constant of the gradient
*/
static PetscErrorCode ScaledValues(SNES snes, Balance *bl, PetscReal *lmax)
{
  SNES_SSStar        *ss = (SNES_SSStar *)snes->data;
  const SSStarFloating *fb = &ss->problem.floating;
  const PetscInt      m  = bl->m;
  PetscReal          *G, *x, *y;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < bl->n; i++) {
    const SSStarFriction *fr  = &ss->contact.nodeFriction[i];
    const PetscReal      *row = &fb->Rc[3 * i * m];
    PetscReal            *out = &bl->Rc[3 * i * m];
    PetscReal             D[4];

    PetscCall(PetscArraycpy(out, row, 3 * m));
    bl->slope[i] = fr->law->ops.cone ? 1.0 : PETSC_INFINITY;
    bl->moved[i] = PETSC_FALSE;
    for (PetscInt d = 0; d < 3 * m; d++) bl->moved[i] = (PetscBool)(bl->moved[i] || row[d] != 0.0);
    if (!fr->law->ops.cone) continue;
    fr->law->ops.cone(fr, D);
    if (D[0] == 0 && D[1] == 0 && D[2] == 0 && D[3] == 0) bl->slope[i] = 0; /* frictionless: no tangential force */
    for (PetscInt r = 0; r < 2; r++)
      for (PetscInt k = 0; k < m; k++) out[r * m + k] = D[r] * row[k] + D[2 + r] * row[m + k]; /* (D^T Rc_t)_r */
  }
  PetscCall(PetscCalloc3(m * m, &G, m, &x, m, &y));
  for (PetscInt d = 0; d < 3 * bl->n; d++)
    for (PetscInt k = 0; k < m; k++)
      for (PetscInt l = 0; l < m; l++) G[k * m + l] += bl->Rc[d * m + k] * bl->Rc[d * m + l];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, G, m * m, MPIU_REAL, MPIU_SUM, bl->comm));
  for (PetscInt k = 0; k < m; k++) x[k] = 1;
  *lmax = 0;
  for (PetscInt it = 0; it < 200; it++) {
    PetscReal norm = 0;

    for (PetscInt k = 0; k < m; k++) {
      y[k] = 0;
      for (PetscInt l = 0; l < m; l++) y[k] += G[k * m + l] * x[l];
      norm += y[k] * y[k];
    }
    norm = PetscSqrtReal(norm);
    if (norm == 0) break;
    *lmax = norm; /* |G x| with |x| = 1 after the first iteration: tends to the largest eigenvalue from below */
    for (PetscInt k = 0; k < m; k++) x[k] = y[k] / norm;
  }
  *lmax *= 1.01; /* above it: the power iteration's estimate is a lower bound */
  PetscCall(PetscFree3(G, x, y));
  PetscFunctionReturn(0);
}

/* a = sum_i Rc_i^T x_i on the local points (m values) */
static void Apply(const Balance *bl, const PetscReal x[], PetscReal a[])
{
  for (PetscInt k = 0; k < bl->m; k++) a[k] = 0;
  for (PetscInt i = 0; i < bl->n; i++) {
    if (!bl->moved[i]) continue;
    for (PetscInt r = 0; r < 3; r++) {
      const PetscReal *row = &bl->Rc[(3 * i + r) * bl->m];

      for (PetscInt k = 0; k < bl->m; k++) a[k] += row[k] * x[3 * i + r];
    }
  }
}

/* w = Rc_i r */
static void Motion(const Balance *bl, const PetscReal *Rc, PetscInt i, const PetscReal r[], PetscReal w[3])
{
  for (PetscInt d = 0; d < 3; d++) {
    const PetscReal *row = &Rc[(3 * i + d) * bl->m];

    w[d] = 0;
    for (PetscInt k = 0; k < bl->m; k++) w[d] += row[k] * r[k];
  }
}

/* The relative distance of the dual motion from the dual cones: max_i violation / max_i |Rc_i r| */
static PetscErrorCode DualDistance(const Balance *bl, const PetscReal r[], PetscReal *dist)
{
  PetscReal v[2] = {0, 0};

  PetscFunctionBegin;
  for (PetscInt i = 0; i < bl->n; i++) {
    PetscReal w[3];

    if (!bl->moved[i]) continue;
    Motion(bl, bl->Rc, i, r, w);
    v[0] = PetscMax(v[0], DualViolation(bl->slope[i], w));
    Motion(bl, bl->Rc0, i, r, w);
    v[1] = PetscMax(v[1], PetscSqrtReal(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 2, MPIU_REAL, MPIU_MAX, bl->comm));
  *dist = v[1] > 0 ? v[0] / v[1] : 0;
  PetscFunctionReturn(0);
}

/*
   min over mu in K of 1/2 |g + A mu|^2 from mu (projected first); r = g + A mu at the end. balanced: PETSC_TRUE when
   r vanishes (to SSSTAR_BALANCE_TOL |g|), PETSC_FALSE when r is the certificate of (14.4), undecided (iterations
   spent) otherwise: then decided is PETSC_FALSE.
*/
static PetscErrorCode Solve(const Balance *bl, PetscReal lmax, const PetscReal g[], PetscReal mu[], PetscReal r[], PetscBool *balanced, PetscBool *decided, PetscInt *its)
{
  const PetscInt m = bl->m, n3 = 3 * bl->n;
  PetscReal     *y, *xn, *red, *amu, *ay, gnorm = 0, t = 1, last = -1;

  PetscFunctionBegin;
  *decided  = PETSC_FALSE;
  *balanced = PETSC_FALSE;
  for (PetscInt k = 0; k < m; k++) gnorm += g[k] * g[k];
  gnorm = PetscSqrtReal(gnorm);
  PetscCall(PetscMalloc5(n3 + 1, &y, n3 + 1, &xn, m + 1, &red, m, &amu, m, &ay));
  for (PetscInt i = 0; i < bl->n; i++) {
    if (bl->moved[i]) ProjectCone(bl->slope[i], &mu[3 * i]);
    else mu[3 * i] = mu[3 * i + 1] = mu[3 * i + 2] = 0;
  }
  Apply(bl, mu, amu);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, amu, m, MPIU_REAL, MPIU_SUM, bl->comm));
  PetscCall(PetscArraycpy(y, mu, n3));
  PetscCall(PetscArraycpy(ay, amu, m));
  for (*its = 0; *its < SSSTAR_BALANCE_MAX_IT; (*its)++) {
    PetscReal rnorm = 0, tn, beta;

    for (PetscInt k = 0; k < m; k++) r[k] = g[k] + amu[k];
    for (PetscInt k = 0; k < m; k++) rnorm += r[k] * r[k];
    rnorm = PetscSqrtReal(rnorm);
    if (rnorm <= SSSTAR_BALANCE_TOL * gnorm) {
      *decided = *balanced = PETSC_TRUE;
      break;
    }
    if (*its % SSSTAR_BALANCE_TEST_ITS == 0) {
      if (last > 0 && rnorm > SSSTAR_BALANCE_MIN * gnorm && PetscAbsReal(rnorm - last) <= SSSTAR_BALANCE_STEADY * rnorm) {
        PetscReal dist = 0;

        PetscCall(DualDistance(bl, r, &dist));
        if (dist <= SSSTAR_BALANCE_DUAL) {
          *decided = PETSC_TRUE;
          break;
        }
      }
      last = rnorm;
    }
    /* the projected gradient step from y, with r at y */
    for (PetscInt k = 0; k < m; k++) red[k] = g[k] + ay[k];
    for (PetscInt i = 0; i < bl->n; i++) {
      PetscReal w[3];

      if (!bl->moved[i]) {
        xn[3 * i] = xn[3 * i + 1] = xn[3 * i + 2] = 0;
        continue;
      }
      Motion(bl, bl->Rc, i, red, w);
      for (PetscInt d = 0; d < 3; d++) xn[3 * i + d] = y[3 * i + d] - w[d] / lmax;
      ProjectCone(bl->slope[i], &xn[3 * i]);
    }
    Apply(bl, xn, red);
    red[m] = 0; /* restart when the step turns against the momentum: (y - xn) . (xn - mu) > 0 */
    for (PetscInt d = 0; d < n3; d++) red[m] += (y[d] - xn[d]) * (xn[d] - mu[d]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, red, m + 1, MPIU_REAL, MPIU_SUM, bl->comm));
    tn   = red[m] > 0 ? 1 : 0.5 * (1 + PetscSqrtReal(1 + 4 * t * t));
    beta = red[m] > 0 ? 0 : (t - 1) / tn;
    for (PetscInt d = 0; d < n3; d++) y[d] = xn[d] + beta * (xn[d] - mu[d]);
    for (PetscInt k = 0; k < m; k++) ay[k] = red[k] + beta * (red[k] - amu[k]);
    PetscCall(PetscArraycpy(mu, xn, n3));
    PetscCall(PetscArraycpy(amu, red, m));
    t = tn;
  }
  PetscCall(PetscFree5(y, xn, red, amu, ay));
  PetscFunctionReturn(0);
}

/*
   The direction the body slides in: the mean tangential part, in global axes, of the motion at its contact points
   (r restricted to its motions); its translation where it only lifts off
*/
static PetscErrorCode SlidingDirection(SSStarFloating *fb, const PetscReal r[])
{
  PetscReal *rb, sums[4] = {0, 0, 0, 0}, len;

  PetscFunctionBegin;
  PetscCall(PetscMalloc1(fb->m, &rb));
  for (PetscInt k = 0; k < fb->m; k++) rb[k] = fb->body[k] == fb->movingBody ? r[k] : 0;
  for (PetscInt i = 0; i < fb->nnodes; i++) {
    const PetscReal *R = fb->frames ? &fb->frames[9 * i] : NULL;
    PetscReal        w[3] = {0, 0, 0};

    for (PetscInt d = 0; d < 3; d++)
      for (PetscInt k = 0; k < fb->m; k++) w[d] += fb->Rc[(3 * i + d) * fb->m + k] * rb[k];
    for (PetscInt k = 0; k < 3; k++) sums[k] += R ? R[k] * w[0] + R[3 + k] * w[1] : w[k] * (k < 2);
    sums[3] += PetscSqrtReal(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 4, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)fb->modes[0])));
  len = PetscSqrtReal(sums[0] * sums[0] + sums[1] * sums[1] + sums[2] * sums[2]);
  for (PetscInt k = 0; k < 3; k++) fb->direction[k] = len > 1e-3 * sums[3] ? sums[k] / len : fb->translation[k];
  PetscCall(PetscFree(rb));
  PetscFunctionReturn(0);
}

/*
   The rigid motion of the certificate r: sum_k r_k rho_k; the body it moves most (the largest |r| over its motions),
   that body's mean translation along it (the mean over its nodes, 3 dofs each, of the motion: its translation at
   their centroid) and the direction it slides in, unit
*/
static PetscErrorCode DescribeMotion(SSStarFloating *fb, Mat K, const PetscReal r[])
{
  const PetscInt     m = fb->m;
  PetscReal          share = -1, sums[6] = {0, 0, 0, 0, 0, 0}, len = 0;
  PetscScalar       *coef;
  const PetscScalar *ma, *mk;
  PetscInt           bs, n, rstart;
  PetscBool         *onBody;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&fb->motion));
  PetscCall(VecDuplicate(fb->modes[0], &fb->motion));
  PetscCall(VecZeroEntries(fb->motion));
  PetscCall(PetscMalloc1(m, &coef));
  for (PetscInt k = 0; k < m; k++) coef[k] = r[k];
  PetscCall(VecMAXPY(fb->motion, m, coef, fb->modes));
  PetscCall(PetscFree(coef));
  for (PetscInt b = 0; b < fb->nbodies; b++) {
    PetscReal s = 0;

    for (PetscInt k = 0; k < m; k++)
      if (fb->body[k] == b) s += r[k] * r[k];
    if (s > share) {
      share          = s;
      fb->movingBody = b;
    }
  }
  PetscCall(PetscArrayzero(fb->translation, 3));
  PetscCall(MatGetBlockSize(K, &bs));
  if (bs != 3) {
    PetscCall(SlidingDirection(fb, r));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetLocalSize(fb->motion, &n));
  PetscCall(VecGetOwnershipRange(fb->motion, &rstart, NULL));
  PetscCall(PetscCalloc1(n + 1, &onBody));
  for (PetscInt k = 0; k < m; k++) { /* the dofs of the body: those its motions move */
    if (fb->body[k] != fb->movingBody) continue;
    PetscCall(VecGetArrayRead(fb->modes[k], &mk));
    for (PetscInt j = 0; j < n; j++)
      if (mk[j] != 0.0) onBody[j] = PETSC_TRUE;
    PetscCall(VecRestoreArrayRead(fb->modes[k], &mk));
  }
  PetscCall(VecGetArrayRead(fb->motion, &ma));
  for (PetscInt j = 0; j < n; j++) {
    if (!onBody[j]) continue;
    sums[(rstart + j) % 3] += PetscRealPart(ma[j]);
    sums[3 + (rstart + j) % 3] += 1;
  }
  PetscCall(VecRestoreArrayRead(fb->motion, &ma));
  PetscCall(PetscFree(onBody));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums, 6, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)K)));
  for (PetscInt d = 0; d < 3; d++) {
    fb->translation[d] = sums[3 + d] > 0 ? sums[d] / sums[3 + d] : 0;
    len += fb->translation[d] * fb->translation[d];
  }
  len = PetscSqrtReal(len);
  for (PetscInt d = 0; d < 3 && len > 0; d++) fb->translation[d] /= len;
  PetscCall(SlidingDirection(fb, r));
  PetscFunctionReturn(0);
}

/*
   Before the first iteration of a solve with floating bodies: whether contact forces the laws allow can balance the
   load on their rigid-body motions. Where they cannot, the solve ends here: reason NO_EQUILIBRIUM
   (SNES_DIVERGED_DTOL), the motion along which the body goes in the null space (SNESSSStarGetUnbalancedMotion()), the
   first iterate's approximation step and states for the record.
*/
PetscErrorCode SNESSSStarCheckEquilibrium(SNES snes)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  SSStarFloating      *fb = &pb->floating;
  const PetscInt     m  = fb->m;
  Balance            bl;
  PetscScalar       *gs;
  PetscReal         *g, *r, *mu, gnorm = 0, rnorm = 0, lmax = 0;
  const PetscScalar *ca;
  PetscBool          balanced, decided;
  PetscInt           its;

  PetscFunctionBegin;
  if (!m) PetscFunctionReturn(0);
  bl.m    = m;
  bl.n    = fb->nnodes;
  bl.comm = PetscObjectComm((PetscObject)snes);
  bl.Rc0  = fb->Rc;
  PetscCall(PetscMalloc6(m, &gs, m, &g, m, &r, 3 * bl.n + 1, &mu, bl.n + 1, &bl.slope, bl.n + 1, &bl.moved));
  PetscCall(PetscMalloc1(3 * bl.n * m + 1, &bl.Rc));
  PetscCall(ScaledValues(snes, &bl, &lmax));
  PetscCall(VecMDot(pb->b, m, fb->modes, gs));
  for (PetscInt k = 0; k < m; k++) {
    g[k] = PetscRealPart(gs[k]);
    gnorm += g[k] * g[k];
  }
  PetscCall(VecGetArrayRead(ss->c, &ca));
  for (PetscInt i = 0; i < bl.n; i++) { /* the contact forces of the first iterate, in the unit cone's variables */
    const SSStarFriction *fr = &ct->nodeFriction[i];
    PetscReal             D[4], det, t0, t1;

    SNESSSStarNodeRotate(ct, pb, i, ca, &mu[3 * i]);
    if (!fr->law->ops.cone) continue;
    fr->law->ops.cone(fr, D);
    det = D[0] * D[3] - D[1] * D[2];
    t0  = mu[3 * i];
    t1  = mu[3 * i + 1];
    mu[3 * i]     = det != 0 ? (D[3] * t0 - D[1] * t1) / det : 0;
    mu[3 * i + 1] = det != 0 ? (-D[2] * t0 + D[0] * t1) / det : 0;
  }
  PetscCall(VecRestoreArrayRead(ss->c, &ca));
  balanced = decided = PETSC_TRUE;
  its      = 0;
  if (gnorm > 0) PetscCall(Solve(&bl, lmax, g, mu, r, &balanced, &decided, &its));
  fb->unbalanced = 0;
  if (decided && !balanced) {
    PetscReal gbody = 0;

    PetscCall(DescribeMotion(fb, pb->K, r));
    /* relative to the load on the moving body's motions, not on every floating body's: a lid sliding off a stack on a
       slope left sin(alpha - arctan phi) = 0.0576 unbalanced, of its own load, and was said to leave 0.0442 of both
       blocks' loads */
    for (PetscInt k = 0; k < m; k++)
      if (fb->body[k] == fb->movingBody) {
        rnorm += r[k] * r[k];
        gbody += g[k] * g[k];
      }
    fb->unbalanced = gbody > 0 ? PetscSqrtReal(rnorm / gbody) : 0;
  }
  PetscCall(PetscInfo(snes, "Balance of the load on %" PetscInt_FMT " rigid-body motions: %s after %" PetscInt_FMT " iterations, unbalanced part %g of the moving body's load\n", m, !decided ? "undecided" : balanced ? "balanced" : "not balanced", its, (double)fb->unbalanced));
  if (decided && !balanced) {
    ss->reason   = SSSTAR_REASON_NO_EQUILIBRIUM;
    snes->reason = SNES_DIVERGED_DTOL;
    PetscCall(SNESSSStarApproximationStep(snes, ss->u, ss->c, &snes->norm));
    PetscCall(SNESSSStarClassify(snes));
  }
  PetscCall(PetscFree6(gs, g, r, mu, bl.slope, bl.moved));
  PetscCall(PetscFree(bl.Rc));
  PetscFunctionReturn(0);
}

/*
   How far a sliding point stays sliding along a motion w of its tangential iterate: the first t > 0 at which
   a + t w (a = v_t - gamma c_t) enters its stick zone, where its law's tangential step (1.2) is zero; found by
   bisection up to the line's closest approach to the zone's centre, PETSC_MAX_REAL when the line misses the zone there
*/
static PetscReal StickEntry(const SSStarFriction *fr, PetscReal rn, const PetscReal a[2], const PetscReal w[2])
{
  const PetscReal ww = w[0] * w[0] + w[1] * w[1];
  PetscReal       lo = 0, hi, p[2], d[2];

  if (ww == 0) return PETSC_MAX_REAL;
  hi   = -(a[0] * w[0] + a[1] * w[1]) / ww;
  p[0] = a[0] + hi * w[0];
  p[1] = a[1] + hi * w[1];
  if (hi <= 0) return PETSC_MAX_REAL;
  fr->law->ops.tangential(fr, rn, p, d);
  if (d[0] != 0 || d[1] != 0) return PETSC_MAX_REAL;
  for (PetscInt k = 0; k < 60; k++) {
    const PetscReal mid = 0.5 * (lo + hi);

    p[0] = a[0] + mid * w[0];
    p[1] = a[1] + mid * w[1];
    fr->law->ops.tangential(fr, rn, p, d);
    if (d[0] == 0 && d[1] == 0) hi = mid;
    else lo = mid;
  }
  return hi;
}

/*
   (14.5), the free motions' part of a Newton step carried on as far as its model holds: the model has no stiffness
   along a free motion, and it stays the model while no point changes its state; so the step's part on the free
   motions, U U^T du, is extended to the first point it would change: a separated point whose gap it closes, a sliding
   point it brings into its stick zone (the contact force does not change along a rigid motion). A floating body off
   its obstacles reaches them in one step, one that slid too far comes back in one, not in many proximal ones. ss->dv
   in place; ss->ut, ss->ct are its scratch.
*/
PetscErrorCode SNESSSStarExtendFreeStep(SNES snes)
{
  SNES_SSStar       *ss = (SNES_SSStar *)snes->data;
  SSStarContact     *ct = &ss->contact;
  SSStarProblem     *pb = &ss->problem;
  SSStarFloating      *fb = &pb->floating;
  const PetscInt     n3 = 3 * fb->nnodes;
  PetscReal         *t, first = PETSC_MAX_REAL;
  const PetscScalar *ua, *ca, *da;
  PetscScalar       *xa;

  PetscFunctionBegin;
  if (!fb->m || !fb->nfree) PetscFunctionReturn(0);
  PetscCall(PetscCalloc1(fb->nfree + 1, &t));
  PetscCall(VecGetArrayRead(ss->dv, &da));
  for (PetscInt i = 0; i < fb->nnodes; i++) { /* t = U^T du (frames), and |du|^2 at the contact dofs */
    PetscReal dv[3];

    SNESSSStarNodeRotate(ct, pb, i, da, dv);
    for (PetscInt f = 0; f < fb->nfree; f++)
      for (PetscInt k = 0; k < 3; k++) t[f] += fb->free[f * n3 + 3 * i + k] * dv[k];
    for (PetscInt k = 0; k < 3; k++) t[fb->nfree] += dv[k] * dv[k];
  }
  PetscCall(VecRestoreArrayRead(ss->dv, &da));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, t, fb->nfree + 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)snes)));
  { /* a free part at the level of the solve's error has no direction to follow (|U t| = |t|: U orthonormal) */
    PetscReal tt = 0;

    for (PetscInt f = 0; f < fb->nfree; f++) tt += t[f] * t[f];
    if (tt <= SSSTAR_FREE_PART_MIN * SSSTAR_FREE_PART_MIN * t[fb->nfree]) {
      PetscCall(PetscFree(t));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(VecWAXPY(ss->ut, 1.0, ss->dv, ss->u)); /* after the step: v+, c+ */
  PetscCall(SNESSSStarResidual(snes, ss->ut, ss->ct));
  PetscCall(VecGetArrayRead(ss->ut, &ua));
  PetscCall(VecGetArrayRead(ss->ct, &ca));
  for (PetscInt i = 0; i < fb->nnodes; i++) { /* the first point whose state it changes */
    const SSStarState    s  = ss->states[i];
    const SSStarFriction fr = SNESSSStarScaledFriction(ss, i, ss->scaling);
    PetscReal            v[3], c[3], w[3] = {0, 0, 0};

    if (s != SSSTAR_STATE_L && s != SSSTAR_STATE_LS && s != SSSTAR_STATE_M1) continue;
    for (PetscInt f = 0; f < fb->nfree; f++)
      for (PetscInt k = 0; k < 3; k++) w[k] += fb->free[f * n3 + 3 * i + k] * t[f];
    SNESSSStarNodeIterate(ct, pb, i, ua, v);
    if (s != SSSTAR_STATE_M1) {
      if (w[2] < 0 && v[2] > 0) first = PetscMin(first, v[2] / -w[2]);
      continue;
    }
    SNESSSStarNodeRotate(ct, pb, i, ca, c);
    {
      const PetscReal a[2] = {v[0] - ss->scaling * c[0], v[1] - ss->scaling * c[1]};

      first = PetscMin(first, StickEntry(&fr, PetscMax(0.0, ss->scaling * c[2] - v[2]), a, w));
    }
  }
  PetscCall(VecRestoreArrayRead(ss->ct, &ca));
  PetscCall(VecRestoreArrayRead(ss->ut, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &first, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)snes)));
  if (first < PETSC_MAX_REAL) {
    PetscCall(PetscInfo(snes, "Free motions of a floating body carried %g times further, to the first change of state\n", (double)first));
    if (pb->wholeBody) { /* the rigid motion sum_k (Y t)_k T^-1 rho_k on every dof */
      PetscScalar *coef;

      PetscCall(PetscCalloc1(fb->m, &coef));
      for (PetscInt k = 0; k < fb->m; k++)
        for (PetscInt f = 0; f < fb->nfree; f++) coef[k] += first * fb->Y[f * fb->m + k] * t[f];
      PetscCall(VecMAXPY(ss->dv, fb->m, coef, fb->pmodes));
      PetscCall(PetscFree(coef));
    } else { /* its contact dofs, in global axes */
      PetscCall(VecGetArray(ss->dv, &xa));
      for (PetscInt d = 0; d < n3; d++)
        for (PetscInt f = 0; f < fb->nfree; f++) xa[pb->layoutDofs[d]] += first * fb->freeGlobal[f * n3 + d] * t[f];
      PetscCall(VecRestoreArray(ss->dv, &xa));
    }
  }
  PetscCall(PetscFree(t));
  PetscFunctionReturn(0);
}

/*@
   SNESSSStarGetUnbalancedMotion - after a solve that found no equilibrium (SSSTAR_REASON_NO_EQUILIBRIUM): the rigid
   motion of a floating body along which the load does work that no contact force the friction laws allow resists

   Not Collective

   Input Parameter:
.  snes - the SNES

   Output Parameters:
+  motion     - the motion, a combination of the vectors of K's null space in the layout of the SNES vector (owned by
                the SNES), or NULL when the last solve did not stop for this reason; pass NULL if not wanted
.  body       - the floating body it moves most: the vectors of K's null space that move common dofs make one body,
                numbered in the order of their first vector (-1 when there is no motion); or NULL
.  direction  - the direction the body slides in (unit, global axes): the mean tangential part of the motion at its
                contact points, or where it only lifts off its mean translation; or NULL
-  unbalanced - the part of the load on the body's rigid-body motions that no admissible contact force balances,
                relative to the load on that body's motions (a block on a slope of angle alpha with friction phi < tan
                alpha, alone or on other floating bodies: sin(alpha - arctan phi)); or NULL

   Notes:
   A floating body is one held by contact alone: its rigid-body motions are declared as K's null space
   (MatSetNullSpace()). Before its first iteration every solve checks that contact forces inside the friction cones
   can balance the load on those motions (docs/derivation.md section 14); where they cannot, no equilibrium exists,
   and the solve stops with SNES_DIVERGED_DTOL and this motion (down a slope steeper than its friction angle allows,
   lifting off the slope at that angle; along a push on a frictionless plane).

   Level: intermediate

.seealso: `SNESSSStarGetReason()`, `MatSetNullSpace()`
@*/
PetscErrorCode SNESSSStarGetUnbalancedMotion(SNES snes, Vec *motion, PetscInt *body, PetscReal direction[3], PetscReal *unbalanced)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(snes, SNES_CLASSID, 1);
  PetscUseMethod(snes, "SNESSSStarGetUnbalancedMotion_C", (SNES, Vec *, PetscInt *, PetscReal[3], PetscReal *), (snes, motion, body, direction, unbalanced));
  PetscFunctionReturn(0);
}

static PetscErrorCode SNESSSStarGetUnbalancedMotion_SSStar(SNES snes, Vec *motion, PetscInt *body, PetscReal direction[3], PetscReal *unbalanced)
{
  SNES_SSStar  *ss = (SNES_SSStar *)snes->data;
  SSStarFloating *fb = &ss->problem.floating;
  const PetscBool none = (PetscBool)(ss->reason != SSSTAR_REASON_NO_EQUILIBRIUM);

  PetscFunctionBegin;
  if (motion) *motion = none ? NULL : fb->motion;
  if (body) *body = none ? -1 : fb->movingBody;
  for (PetscInt d = 0; d < 3 && direction; d++) direction[d] = none ? 0 : fb->direction[d];
  if (unbalanced) *unbalanced = none ? 0 : fb->unbalanced;
  PetscFunctionReturn(0);
}

/* The implementations of the public functions above, composed on the SNES (SNESSSStarComposeFunctions()) */
static const SSStarComposed Composed[] = {
    {"SNESSSStarGetUnbalancedMotion_C", (PetscVoidFunction)SNESSSStarGetUnbalancedMotion_SSStar},
};

PetscErrorCode SNESSSStarComposeFloating(SNES snes, PetscBool on)
{
  PetscFunctionBegin;
  PetscCall(SNESSSStarComposeTable(snes, Composed, PETSC_STATIC_ARRAY_LENGTH(Composed), on));
  PetscFunctionReturn(0);
}
