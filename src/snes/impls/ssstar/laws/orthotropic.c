/*
   The law "orthotropic": Coulomb friction with the coefficient phi_1 along a given tangential direction a and phi_2
   across it (docs/derivation.md section 9). The friction set at the normal force r_n is the ellipse r_n E,
   E = { r : |M^-1/2 r| <= 1 }, M = phi_1^2 a a^T + phi_2^2 a' a'^T (a' = a turned by 90 degrees in the tangent plane),
   whose support function is sigma(v) = |M^1/2 v|; a sliding node has r_t = -r_n M u_t/|M^1/2 u_t| (maximum
   dissipation). The direction is given in global axes and projected onto each node's tangent plane.

     tangential step (9.2)  d_t = v - (the projection of v onto r_n E): a secular equation for the multiplier t,
                            solved by Newton's method from a lower bound of its root (monotone convergence)
     classification (9.4)   M3+ where b_t lies inside the ellipse -b_3 E by more than tol_b
     blocks (9.3)           W = r_n grad^2 sigma(d_t), coupling k = grad sigma(d_t)

   phi_1 = phi_2 is the law coulomb, computed by its closed forms (the same iterates).
*/
#include "lawimpl.h"

/* value[0] = phi_1, value[1] = phi_2, value[2..4] the direction in the node's frame: (cos, sin, 0) once prepared */

/* Newton iterations of the secular equation: it converges in a few from its lower bound; this many means a bug */
#define SSSTAR_ORTHOTROPIC_MAX_IT 100

/* v in the principal axes (a, a'), and back */
static void ToPrincipal(const SSStarFriction *fr, const PetscReal v[2], PetscReal p[2])
{
  const PetscReal c = fr->value[2], s = fr->value[3];

  p[0] = c * v[0] + s * v[1];
  p[1] = -s * v[0] + c * v[1];
}

static void FromPrincipal(const SSStarFriction *fr, const PetscReal p[2], PetscReal v[2])
{
  const PetscReal c = fr->value[2], s = fr->value[3];

  v[0] = c * p[0] - s * p[1];
  v[1] = s * p[0] + c * p[1];
}

/*
   The root t > 0 of g(t) = sum_i w_i^2 / (e_i^2 + t)^2 - 1 (w_i = e_i v_i, v outside the ellipse of semi-axes e_i):
   g is convex and decreasing for t > -min e_i^2, so Newton's method from a point left of the root increases
   monotonically to it. Left of it: t_lo = max(0, |w_i| - e_i^2) (each term is <= 1 at the root); right of it:
   t_hi = |w| - min e_i^2. A step that would leave [t, t_hi] is replaced by a bisection (round-off only).
*/
static PetscReal SecularRoot(const PetscReal e[2], const PetscReal w[2])
{
  const PetscReal e2[2] = {e[0] * e[0], e[1] * e[1]};
  PetscReal       t     = PetscMax(0.0, PetscMax(PetscAbsReal(w[0]) - e2[0], PetscAbsReal(w[1]) - e2[1]));
  const PetscReal hi    = PetscSqrtReal(w[0] * w[0] + w[1] * w[1]) - PetscMin(e2[0], e2[1]);

  for (PetscInt it = 0; it < SSSTAR_ORTHOTROPIC_MAX_IT; it++) {
    const PetscReal q0 = w[0] / (e2[0] + t), q1 = w[1] / (e2[1] + t);
    const PetscReal g = q0 * q0 + q1 * q1 - 1, dg = -2 * (q0 * q0 / (e2[0] + t) + q1 * q1 / (e2[1] + t));
    PetscReal       next;

    if (g <= 0 || dg == 0) break; /* at the root, to round-off */
    next = t - g / dg;
    if (!(next > t && next <= hi)) next = 0.5 * (t + hi);
    if (next - t <= 4 * PETSC_MACHINE_EPSILON * next) return next;
    t = next;
  }
  return t;
}

/* (9.2): d_t = v - proj_{rn E}(v) */
static void Tangential_Orthotropic(const SSStarFriction *fr, PetscReal rn, const PetscReal v[2], PetscReal d[2])
{
  const PetscReal e[2] = {rn * fr->value[0], rn * fr->value[1]};
  PetscReal       p[2], w[2], t, dp[2];

  if (fr->value[0] == fr->value[1]) {
    SSStarSoftThreshold(fr->value[0] * rn, v, d);
    return;
  }
  if (rn == 0.0) { /* the ellipse is a point */
    d[0] = v[0];
    d[1] = v[1];
    return;
  }
  ToPrincipal(fr, v, p);
  if (PetscSqr(p[0] / e[0]) + PetscSqr(p[1] / e[1]) <= 1) { /* inside: stuck, d_t an exact zero */
    d[0] = d[1] = 0.0;
    return;
  }
  w[0]  = e[0] * p[0];
  w[1]  = e[1] * p[1];
  t     = SecularRoot(e, w);
  dp[0] = t * p[0] / (e[0] * e[0] + t);
  dp[1] = t * p[1] / (e[1] * e[1] + t);
  FromPrincipal(fr, dp, d);
}

/* |M^-1/2 b_t| */
static PetscReal Gauge(const SSStarFriction *fr, const PetscReal b[2])
{
  PetscReal p[2];

  ToPrincipal(fr, b, p);
  return PetscSqrtReal(PetscSqr(p[0] / fr->value[0]) + PetscSqr(p[1] / fr->value[1]));
}

/* (9.4): min(phi_i) (r_n - |M^-1/2 b_t|), a lower bound of the distance of b_t to the boundary of r_n E */
static PetscReal Margin_Orthotropic(const SSStarFriction *fr, const PetscReal b[3])
{
  if (fr->value[0] == fr->value[1]) return -fr->value[0] * b[2] - PetscSqrtReal(b[0] * b[0] + b[1] * b[1]);
  return PetscMin(fr->value[0], fr->value[1]) * (-b[2] - Gauge(fr, b));
}

/* (9.3): sigma = |M^1/2 d|, k = grad sigma = M d/sigma, W = r_n grad^2 sigma = r_n (M - k k^T)/sigma */
static void Sliding_Orthotropic(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal W[4], PetscReal k[2])
{
  const PetscReal m[2] = {fr->value[0] * fr->value[0], fr->value[1] * fr->value[1]}, rn = -b[2];
  PetscReal       p[2], sigma, kp[2], Wp[3], c = fr->value[2], s = fr->value[3];

  if (fr->value[0] == fr->value[1]) {
    SSStarIsotropicSliding(-fr->value[0] * b[2], fr->value[0], d, W, k);
    return;
  }
  ToPrincipal(fr, d, p);
  sigma = PetscSqrtReal(m[0] * p[0] * p[0] + m[1] * p[1] * p[1]);
  if (rn == 0.0 || sigma == 0.0) {
    W[0] = W[1] = W[2] = W[3] = 0.0;
    k[0] = k[1] = 0.0;
    return;
  }
  kp[0] = m[0] * p[0] / sigma;
  kp[1] = m[1] * p[1] / sigma;
  Wp[0] = rn * (m[0] - kp[0] * kp[0]) / sigma; /* principal axes: [[Wp0, Wp1], [Wp1, Wp2]] */
  Wp[1] = -rn * kp[0] * kp[1] / sigma;
  Wp[2] = rn * (m[1] - kp[1] * kp[1]) / sigma;
  FromPrincipal(fr, kp, k);
  /* W = R Wp R^T with R = [[c, -s], [s, c]] */
  W[0] = c * c * Wp[0] - 2 * c * s * Wp[1] + s * s * Wp[2];
  W[1] = c * s * (Wp[0] - Wp[2]) + (c * c - s * s) * Wp[1];
  W[2] = W[1];
  W[3] = s * s * Wp[0] + 2 * c * s * Wp[1] + c * c * Wp[2];
}

static PetscBool Frictionless_Orthotropic(const SSStarFriction *fr)
{
  return PETSC_FALSE; /* both coefficients > 0 (Prepare) */
}

/* Coefficients > 0, and the direction projected onto the tangent plane (t1, t2) and normalized */
static const char *Prepare_Orthotropic(SSStarFriction *fr)
{
  PetscReal *a = &fr->value[2];
  PetscReal  len3 = PetscSqrtReal(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), len2 = PetscSqrtReal(a[0] * a[0] + a[1] * a[1]);

  if (!(fr->value[0] > 0 && fr->value[1] > 0)) return "the orthotropic law needs friction_1 > 0 and friction_2 > 0 (frictionless contact is the law none)";
  if (!(len2 > 1e-8 * len3)) return "the friction direction is normal to the contact plane (or zero): it has no tangential part there";
  a[0] /= len2;
  a[1] /= len2;
  a[2] = 0.0;
  return NULL;
}

/* M^1/2 = phi_1 a a^T + phi_2 a' a'^T: the friction set at r_n = 1 is M^1/2 (unit disk) */
static void Cone_Orthotropic(const SSStarFriction *fr, PetscReal D[4])
{
  const PetscReal c = fr->value[2], s = fr->value[3], p1 = fr->value[0], p2 = fr->value[1];

  D[0] = p1 * c * c + p2 * s * s;
  D[1] = D[2] = (p1 - p2) * c * s;
  D[3] = p1 * s * s + p2 * c * c;
}

PetscErrorCode SSStarLawCreate_Orthotropic(SSStarLaw law)
{
  PetscFunctionBegin;
  law->label                 = "orthotropic";
  law->effect                = "orthotropic Coulomb friction";
  law->nparams               = 3;
  law->params[0].name        = "friction_1";
  law->params[0].description = "friction coefficient along the friction direction";
  law->params[0].symbol      = "phi_1";
  law->params[0].kind        = SSSTAR_LAW_COEFFICIENT;
  law->params[1].name        = "friction_2";
  law->params[1].description = "friction coefficient across the friction direction";
  law->params[1].symbol      = "phi_2";
  law->params[1].kind        = SSSTAR_LAW_COEFFICIENT;
  law->params[2].name        = "friction_direction";
  law->params[2].description = "friction direction";
  law->params[2].symbol      = "a";
  law->params[2].kind        = SSSTAR_LAW_DIRECTION;
  law->coupled               = PETSC_TRUE;
  law->separate              = PETSC_FALSE;
  law->ops.tangential        = Tangential_Orthotropic;
  law->ops.margin            = Margin_Orthotropic;
  law->ops.sliding           = Sliding_Orthotropic;
  law->ops.frictionless      = Frictionless_Orthotropic;
  law->ops.cone              = Cone_Orthotropic;
  law->ops.prepare           = Prepare_Orthotropic;
  PetscFunctionReturn(0);
}
