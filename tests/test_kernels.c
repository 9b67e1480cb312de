static const char help[] = "Per-node kernels of ssstar against hand-computed cases of every contact state.\n";

/* Requirement: the approximation step, the classification and the G/H and S/T blocks of docs/derivation.md
   sections 1-5 give the hand-computed values for the states L, M1, M2, M3+, M3-, M4 and for phi = 0, for the
   Tresca law (L, LS, M1: no normal-tangential coupling) and without friction; the orthotropic law (section 9) gives
   the hand-computed step, states and blocks on and off its principal axes (a rotated and a non-unit direction with a
   normal part too), and exactly coulomb's for phi_1 = phi_2; (d, b) is always in gph Q, and T G = S H for every state
   and law; the node frame of (0, 0, 1) is the identity and every frame is a right-handed orthonormal basis with n
   last. Tolerance 1e-14 (absolute, O(1) data). */
#include <ssstar.h>

static int failures = 0;

static void Expect(PetscBool ok, const char what[], const char name[])
{
  if (!ok) {
    failures++;
    PetscPrintf(PETSC_COMM_SELF, "FAIL %s: %s\n", name, what);
  }
}

static PetscBool Close(PetscInt n, const PetscReal a[], const PetscReal b[])
{
  for (PetscInt i = 0; i < n; i++)
    if (!(PetscAbsReal(a[i] - b[i]) <= 1e-14)) return PETSC_FALSE; /* NaN fails */
  return PETSC_TRUE;
}

/* A law and its values, as the test knows them (ortho: phi_1, phi_2 and the direction (a1, a2, 0) in the node's frame) */
typedef struct {
  const char *law;
  PetscReal   phi, bound, ortho[5];
} Law;

static Law Coulomb(PetscReal phi)
{
  Law l = {"coulomb", phi, 0.0, {0}};
  return l;
}

static Law Tresca(PetscReal bound)
{
  Law l = {"tresca", 0.0, bound, {0}};
  return l;
}

static Law Frictionless(void)
{
  Law l = {"none", 0.0, 0.0, {0}};
  return l;
}

static Law Orthotropic(PetscReal phi1, PetscReal phi2, PetscReal a1, PetscReal a2)
{
  Law l = {"orthotropic", 0.0, 0.0, {phi1, phi2, a1, a2, 0}};
  return l;
}

/* The kernels' form of a law (SSStarFrictionSet()) */
static SSStarFriction Friction(Law l)
{
  SSStarFriction  fr;
  const PetscBool ortho = (PetscBool)(l.law[0] == 'o'), coulomb = (PetscBool)(l.law[0] == 'c'), tresca = (PetscBool)(l.law[0] == 't');

  PetscCallAbort(PETSC_COMM_SELF, SSStarFrictionSet(&fr, l.law, ortho ? 5 : coulomb || tresca ? 1 : 0, ortho ? l.ortho : coulomb ? &l.phi : &l.bound));
  return fr;
}

typedef struct {
  const char *name;
  Law         law;
  PetscReal   u[3], c[3];
  PetscReal   z[3], d[3], b[3]; /* expected */
  SSStarState state;
} Case;

/* |M^-1/2 b12| and the support function |M^1/2 d12| of the orthotropic law, M = phi_1^2 a a^T + phi_2^2 a' a'^T */
static PetscReal OrthoGauge(const Law *l, const PetscReal b[2])
{
  const PetscReal n = PetscSqrtReal(l->ortho[2] * l->ortho[2] + l->ortho[3] * l->ortho[3]), a[2] = {l->ortho[2] / n, l->ortho[3] / n};

  return PetscSqrtReal(PetscSqr((a[0] * b[0] + a[1] * b[1]) / l->ortho[0]) + PetscSqr((-a[1] * b[0] + a[0] * b[1]) / l->ortho[1]));
}

static void OrthoGradient(const Law *l, const PetscReal d[2], PetscReal g[2])
{
  const PetscReal n = PetscSqrtReal(l->ortho[2] * l->ortho[2] + l->ortho[3] * l->ortho[3]), a[2] = {l->ortho[2] / n, l->ortho[3] / n};
  const PetscReal p[2] = {l->ortho[0] * l->ortho[0] * (a[0] * d[0] + a[1] * d[1]), l->ortho[1] * l->ortho[1] * (-a[1] * d[0] + a[0] * d[1])};
  const PetscReal sigma = PetscSqrtReal(p[0] * (a[0] * d[0] + a[1] * d[1]) + p[1] * (-a[1] * d[0] + a[0] * d[1]));

  g[0] = (a[0] * p[0] - a[1] * p[1]) / sigma;
  g[1] = (a[1] * p[0] + a[0] * p[1]) / sigma;
}

/*
   (d, b) in gph Q (docs/derivation.md section 0): d3 >= 0, b3 <= 0, d3 b3 = 0, and b12 in the friction set, on its
   boundary in the direction of the slip if d12 != 0: |b12| <= s, b12 = s d12/|d12| with the threshold s = -phi b3
   (Coulomb), the bound (Tresca) or 0 (none); orthotropic (section 9): |M^-1/2 b12| <= -b3 (measured as the margin of
   (9.4), min phi_i (|M^-1/2 b12| + b3), in force units), b12 = -b3 grad sigma(d12)
*/
static PetscBool InGraphQ(const Law *l, const PetscReal d[3], const PetscReal b[3])
{
  const PetscReal nd = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]), nb = PetscSqrtReal(b[0] * b[0] + b[1] * b[1]);
  const PetscReal scale = 1 + PetscAbsReal(b[2]) + l->bound;
  const PetscReal s     = l->law[0] == 'c' ? -l->phi * b[2] : (l->law[0] == 't' ? l->bound : 0.0);

  if (d[2] < 0 || b[2] > 0 || d[2] * b[2] != 0) return PETSC_FALSE;
  if (l->law[0] == 'o') {
    PetscReal g[2];

    if (PetscMin(l->ortho[0], l->ortho[1]) * (OrthoGauge(l, b) + b[2]) > 1e-14 * scale) return PETSC_FALSE; /* in force units */
    if (nd == 0) return PETSC_TRUE;
    OrthoGradient(l, d, g);
    return (PetscBool)(PetscAbsReal(b[0] + b[2] * g[0]) <= 1e-14 * scale && PetscAbsReal(b[1] + b[2] * g[1]) <= 1e-14 * scale);
  }
  if (nb > s + 1e-14 * scale) return PETSC_FALSE;
  if (nd > 0 && (PetscAbsReal(b[0] - s * d[0] / nd) > 1e-14 * scale || PetscAbsReal(b[1] - s * d[1] / nd) > 1e-14 * scale)) return PETSC_FALSE;
  return PETSC_TRUE;
}

static void CheckBlockIdentities(const char name[], SSStarState state, const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3])
{
  PetscReal G[9], H[9], S[9], T[9], TG[9], SH[9];

  SSStarTangentBlocks(state, fr, d, b, G, H);
  SSStarReducedBlocks(state, fr, d, b, S, T);
  for (PetscInt i = 0; i < 3; i++)
    for (PetscInt j = 0; j < 3; j++) {
      TG[3 * i + j] = SH[3 * i + j] = 0;
      for (PetscInt k = 0; k < 3; k++) {
        TG[3 * i + j] += T[3 * i + k] * G[3 * k + j];
        SH[3 * i + j] += S[3 * i + k] * H[3 * k + j];
      }
    }
  Expect(Close(9, TG, SH), "T G = S H (section 5)", name);
}

int main(int argc, char **argv)
{
  PetscRandom rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage()); /* the table of laws */
  /* M1: |v| = 5 > s = 0.6, d12 = 0.88 (3, 4), b12 = (0.36, 0.48) with |b12| = phi |b3| */
  /* M3+: |v| = 0.1 < s; M3-: |v| = s = 0.6 exactly; M2, M4: u3 = c3 (weak contact) */
  /* orthotropic, phi_1 = 0.2 along t1, phi_2 = 0.4 along t2, r_n = 2: the ellipse of semi-axes 0.4, 0.8. Inside it,
     stuck; along a principal axis, v minus the vertex; (1, 1): the secular equation's root t = 0.437269218660699...
     (bisection to 50 digits), d12 = t v_i/(e_i^2 + t) */
  const Case cases[] = {
    {"L",           Coulomb(0.3), {0.1, 0, 1},     {0.02, 0, 0.5},  {-0.02, 0, -0.5}, {0.08, 0, 0.5},    {0, 0, 0},         SSSTAR_STATE_L  },
    {"M1",          Coulomb(0.3), {3, 4, 0},       {0, 0, 2},       {-0.36, -0.48, 0}, {2.64, 3.52, 0},  {0.36, 0.48, -2},  SSSTAR_STATE_M1 },
    {"M2",          Coulomb(0.3), {0.1, 0.2, 0.5}, {0.05, 0, 0.5},  {-0.05, 0, -0.5}, {0.05, 0.2, 0},    {0, 0, 0},         SSSTAR_STATE_M2 },
    {"M3+",         Coulomb(0.3), {0.1, 0, 0},     {0, 0, 2},       {-0.1, 0, 0},     {0, 0, 0},         {0.1, 0, -2},      SSSTAR_STATE_M3P},
    {"M3-",         Coulomb(0.3), {0.6, 0, 0},     {0, 0, 2},       {-0.6, 0, 0},     {0, 0, 0},         {0.6, 0, -2},      SSSTAR_STATE_M3M},
    {"M4",          Coulomb(0.3), {0.1, 0.2, 0.5}, {0.1, 0.2, 0.5}, {-0.1, -0.2, -0.5}, {0, 0, 0},       {0, 0, 0},         SSSTAR_STATE_M4 },
    {"phi=0 stick", Coulomb(0.0), {0.1, 0, 0},     {0.1, 0, 2},     {-0.1, 0, 0},     {0, 0, 0},         {0, 0, -2},        SSSTAR_STATE_M3M},
    /* Tresca with s = 0.6: the M1 node of Coulomb (0.3 x 2), a separated node that slips, one held by friction */
    {"Tresca M1",   Tresca(0.6),  {3, 4, 0},       {0, 0, 2},       {-0.36, -0.48, 0}, {2.64, 3.52, 0},  {0.36, 0.48, -2},  SSSTAR_STATE_M1 },
    {"Tresca L",    Tresca(0.6),  {1, 0, 1},       {0.02, 0, 0.5},  {-0.62, 0, -0.5}, {0.38, 0, 0.5},    {0.6, 0, 0},       SSSTAR_STATE_L  },
    {"Tresca LS",   Tresca(0.6),  {0.1, 0, 1},     {0.02, 0, 0.5},  {-0.1, 0, -0.5},  {0, 0, 0.5},       {0.08, 0, 0},      SSSTAR_STATE_LS },
    /* frictionless: no projection of the tangential part, d12 = u12 - c12 */
    {"none",        Frictionless(), {3, 4, 0},     {0.5, 0, 2},     {-0.5, 0, 0},     {2.5, 4, 0},       {0, 0, -2},        SSSTAR_STATE_M1 },
    {"ortho M3+",   Orthotropic(0.2, 0.4, 1, 0), {0.3, 0, 0}, {0, 0, 2}, {-0.3, 0, 0},   {0, 0, 0},         {0.3, 0, -2},      SSSTAR_STATE_M3P},
    {"ortho M3-",   Orthotropic(0.2, 0.4, 1, 0), {0, 0.8, 0}, {0, 0, 2}, {0, -0.8, 0},   {0, 0, 0},         {0, 0.8, -2},      SSSTAR_STATE_M3M},
    {"ortho M1 t1", Orthotropic(0.2, 0.4, 1, 0), {1, 0, 0},   {0, 0, 2}, {-0.4, 0, 0},   {0.6, 0, 0},       {0.4, 0, -2},      SSSTAR_STATE_M1 },
    {"ortho M1 t2", Orthotropic(0.2, 0.4, 1, 0), {0, 1, 0},   {0, 0, 2}, {0, -0.8, 0},   {0, 0.2, 0},       {0, 0.8, -2},      SSSTAR_STATE_M1 },
    {"ortho turned", Orthotropic(0.2, 0.4, 0, 3), {1, 0, 0},  {0, 0, 2}, {-0.8, 0, 0},   {0.2, 0, 0},       {0.8, 0, -2},      SSSTAR_STATE_M1 },
    {"ortho M1",    Orthotropic(0.2, 0.4, 1, 0), {1, 1, 0},   {0, 0, 2}, {-0.26788589634466625, -0.59409476193487762, 0}, {0.73211410365533375, 0.40590523806512238, 0}, {0.26788589634466625, 0.59409476193487762, -2}, SSSTAR_STATE_M1},
    {"ortho L",     Orthotropic(0.2, 0.4, 1, 0), {0.1, 0, 1}, {0.02, 0, 0.5}, {-0.02, 0, -0.5}, {0.08, 0, 0.5}, {0, 0, 0},        SSSTAR_STATE_L  },
  };

  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(cases); k++) {
    const Case          *cs = &cases[k];
    const SSStarFriction fr = Friction(cs->law);
    PetscReal            z[3], d[3], b[3];
    SSStarState          state;

    SSStarApproximationStep(&fr, cs->u, cs->c, z, d, b);
    Expect(Close(3, z, cs->z), "z of the approximation step", cs->name);
    Expect(Close(3, d, cs->d), "d = u + z", cs->name);
    Expect(Close(3, b, cs->b), "b = -z - c", cs->name);
    Expect(InGraphQ(&cs->law, d, b), "(d, b) in gph Q", cs->name);
    state = SSStarClassify(&fr, d, b, 0.0, 0.0);
    Expect((PetscBool)(state == cs->state), "state of Table 1", cs->name);
    CheckBlockIdentities(cs->name, state, &fr, d, b);
  }

  /* Blocks by hand (section 3 and 5 tables) */
  {
    const PetscReal d[3] = {2.64, 3.52, 0}, b[3] = {0.36, 0.48, -2};
    const PetscReal w = 0.3 * 2 / 4.4; /* -phi b3 / |d12|, om = (0.6, 0.8) */
    const PetscReal Gm1[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0};
    const PetscReal Hm1[9] = {w * 0.64, -w * 0.48, -0.18, -w * 0.48, w * 0.36, -0.24, 0, 0, 1};
    const PetscReal Sm1[9] = {1, 0, 0.18, 0, 1, 0.24, 0, 0, 0};
    const PetscReal Tm1[9] = {w * 0.64, -w * 0.48, 0, -w * 0.48, w * 0.36, 0, 0, 0, 1};
    const PetscReal I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, Z3[9] = {0}, D110[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0}, D001[9] = {0, 0, 0, 0, 0, 0, 0, 0, 1};
    const PetscReal dz[3] = {0, 0, 0}, bs[3] = {0.1, 0, -2}, du[3] = {0.08, 0, 0.5}, bz[3] = {0, 0, 0};
    const SSStarFriction c03 = Friction(Coulomb(0.3)), c0 = Friction(Coulomb(0.0)), t06 = Friction(Tresca(0.6)), none = Friction(Frictionless());
    PetscReal            G[9], H[9], S[9], T[9];

    SSStarTangentBlocks(SSSTAR_STATE_M1, &c03, d, b, G, H);
    SSStarReducedBlocks(SSSTAR_STATE_M1, &c03, d, b, S, T);
    Expect((PetscBool)(Close(9, G, Gm1) && Close(9, H, Hm1)), "G, H with om = +d12/|d12| (section 3, corrected sign)", "M1 blocks");
    Expect((PetscBool)(Close(9, S, Sm1) && Close(9, T, Tm1)), "S, T of section 5", "M1 blocks");
    for (SSStarState st = SSSTAR_STATE_M3P; st <= SSSTAR_STATE_M3M; st++) {
      SSStarTangentBlocks(st, &c03, dz, bs, G, H);
      SSStarReducedBlocks(st, &c03, dz, bs, S, T);
      Expect((PetscBool)(Close(9, G, Z3) && Close(9, H, I3) && Close(9, S, Z3) && Close(9, T, I3)), "sticking blocks G = 0, H = I, S = 0, T = I", SSStarStateNames[st]);
    }
    for (SSStarState st = SSSTAR_STATE_L; st <= SSSTAR_STATE_M4; st++) {
      if (st != SSSTAR_STATE_L && st != SSSTAR_STATE_M2 && st != SSSTAR_STATE_M4) continue;
      SSStarTangentBlocks(st, &c03, du, bz, G, H);
      SSStarReducedBlocks(st, &c03, du, bz, S, T);
      Expect((PetscBool)(Close(9, G, I3) && Close(9, H, Z3) && Close(9, S, I3) && Close(9, T, Z3)), "free blocks G = I, H = 0, S = I, T = 0", SSStarStateNames[st]);
    }
    /* phi = 0: a sticking node in strong contact gets the frictionless sliding blocks, not the sticking ones */
    for (SSStarState st = SSSTAR_STATE_M1; st <= SSSTAR_STATE_M3M; st++) {
      if (st == SSSTAR_STATE_M2) continue;
      SSStarTangentBlocks(st, &c0, dz, bs, G, H);
      SSStarReducedBlocks(st, &c0, dz, bs, S, T);
      Expect((PetscBool)(Close(9, G, D110) && Close(9, H, D001) && Close(9, S, D110) && Close(9, T, D001)), "phi = 0 blocks G = S = diag(1,1,0), H = T = diag(0,0,1)", SSStarStateNames[st]);
      SSStarTangentBlocks(st, &none, dz, bs, G, H);
      SSStarReducedBlocks(st, &none, dz, bs, S, T);
      Expect((PetscBool)(Close(9, G, D110) && Close(9, H, D001) && Close(9, S, D110) && Close(9, T, D001)), "frictionless blocks G = S = diag(1,1,0), H = T = diag(0,0,1)", SSStarStateNames[st]);
    }
    /* Tresca: the sliding blocks without the coupling phi om, and the stuck separated node */
    {
      const PetscReal wt       = 0.6 / 4.4;
      const PetscReal Ht[9]    = {wt * 0.64, -wt * 0.48, 0, -wt * 0.48, wt * 0.36, 0, 0, 0, 1};
      const PetscReal St[9]    = {1, 0, 0, 0, 1, 0, 0, 0, 0};
      const PetscReal dl[3]    = {0.38, 0, 0.5}, bl[3] = {0.6, 0, 0};
      const PetscReal Tl[9]    = {0, 0, 0, 0, 0.6 / 0.38, 0, 0, 0, 0};
      const PetscReal dls[3]   = {0, 0, 0.5}, bls[3] = {0.08, 0, 0};

      SSStarTangentBlocks(SSSTAR_STATE_M1, &t06, d, b, G, H);
      SSStarReducedBlocks(SSSTAR_STATE_M1, &t06, d, b, S, T);
      Expect((PetscBool)(Close(9, G, Gm1) && Close(9, H, Ht) && Close(9, S, St) && Close(9, T, Ht)), "Tresca sliding: G = S = diag(1,1,0), H = T = [W 0; 0 1], W = s/|d12| (I - om om^T)", "Tresca M1 blocks");
      SSStarTangentBlocks(SSSTAR_STATE_L, &t06, dl, bl, G, H);
      SSStarReducedBlocks(SSSTAR_STATE_L, &t06, dl, bl, S, T);
      Expect((PetscBool)(Close(9, G, I3) && Close(9, H, Tl) && Close(9, S, I3) && Close(9, T, Tl)), "Tresca separated and slipping: G = S = I, H = T = [W 0; 0 0]", "Tresca L blocks");
      SSStarTangentBlocks(SSSTAR_STATE_LS, &t06, dls, bls, G, H);
      SSStarReducedBlocks(SSSTAR_STATE_LS, &t06, dls, bls, S, T);
      Expect((PetscBool)(Close(9, G, D001) && Close(9, H, D110) && Close(9, S, D001) && Close(9, T, D110)), "Tresca separated and stuck: G = S = diag(0,0,1), H = T = diag(1,1,0)", "Tresca LS blocks");
    }
    /* orthotropic, sliding along t1 (phi_1 = 0.2, phi_2 = 0.4, r_n = 2, d12 = (0.6, 0)): sigma = 0.12, the coupling
       k = grad sigma = (phi_1, 0), W = r_n (M - k k^T)/sigma = diag(0, 2 phi_2^2/(phi_1 0.6)) = diag(0, 8/3): the
       curvature of the ellipse at its vertex, where Coulomb (phi = 0.2) has 2/3; the same with the direction turned
       into t2 and given with a normal part, (0, 3, 5) in the node's frame, for a slip along t2 */
    {
      const PetscReal      dO[3] = {0.6, 0, 0}, bO[3] = {0.4, 0, -2}, dT[3] = {0, 0.6, 0}, bT[3] = {0, 0.4, -2};
      const PetscReal      So[9] = {1, 0, 0.2, 0, 1, 0, 0, 0, 0}, To[9] = {0, 0, 0, 0, 8.0 / 3, 0, 0, 0, 1};
      const PetscReal      Ho[9] = {0, 0, -0.2, 0, 8.0 / 3, 0, 0, 0, 1};
      const PetscReal      St[9] = {1, 0, 0, 0, 1, 0.2, 0, 0, 0}, Tt[9] = {8.0 / 3, 0, 0, 0, 0, 0, 0, 0, 1};
      const PetscReal      turned[5] = {0.2, 0.4, 0, 3, 5};
      const SSStarFriction o = Friction(Orthotropic(0.2, 0.4, 1, 0));
      SSStarFriction       ot, bad;
      PetscErrorCode       ierr;

      SSStarTangentBlocks(SSSTAR_STATE_M1, &o, dO, bO, G, H);
      SSStarReducedBlocks(SSSTAR_STATE_M1, &o, dO, bO, S, T);
      Expect((PetscBool)(Close(9, G, Gm1) && Close(9, H, Ho) && Close(9, S, So) && Close(9, T, To)), "orthotropic sliding along t1: k = (phi_1, 0), W = diag(0, 8/3)", "ortho M1 blocks");
      PetscCall(SSStarFrictionSet(&ot, "orthotropic", 5, turned));
      SSStarReducedBlocks(SSSTAR_STATE_M1, &ot, dT, bT, S, T);
      Expect((PetscBool)(Close(9, S, St) && Close(9, T, Tt)), "orthotropic, the direction (0, 3, 5) projected: sliding along t2 with phi_1", "ortho turned blocks");
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      ierr = SSStarFrictionSet(&bad, "orthotropic", 5, (PetscReal[]){0.2, 0.4, 0, 0, 1});
      PetscCall(PetscPopErrorHandler());
      Expect((PetscBool)(ierr != 0), "a direction normal to the plane is refused", "ortho direction");
    }
    /* frames: (0, 0, 1) gives the identity; any normal an orthonormal right-handed (t1, t2, n) */
    {
      const PetscReal ez[3] = {0, 0, 1}, normals[3][3] = {{1, 0, 0}, {0, -0.6, 0.8}, {0.48, 0.6, 0.64}};
      PetscReal       R[9];

      SSStarNodeFrame(ez, R);
      Expect(Close(9, R, I3), "the frame of (0, 0, 1) is the identity", "frames");
      for (PetscInt k = 0; k < 3; k++) {
        PetscReal RRt[9], det;

        SSStarNodeFrame(normals[k], R);
        for (PetscInt i = 0; i < 3; i++)
          for (PetscInt j = 0; j < 3; j++) RRt[3 * i + j] = R[3 * i] * R[3 * j] + R[3 * i + 1] * R[3 * j + 1] + R[3 * i + 2] * R[3 * j + 2];
        det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) + R[2] * (R[3] * R[7] - R[4] * R[6]);
        Expect((PetscBool)(Close(9, RRt, I3) && Close(3, &R[6], normals[k]) && PetscAbsReal(det - 1) < 1e-14), "R R^T = I, det R = 1, last row n", "frames");
      }
    }
  }

  /* Random data: the approximation step always lands in gph Q and the identities hold; the orthotropic law with
     phi_1 = phi_2 is coulomb exactly (the same z, d, b, state, S and T, bit for bit) */
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  for (PetscInt k = 0; k < 10000; k++) {
    PetscReal      u[3], c[3], z[3], d[3], b[3], phi, phi2, a[2];
    Law            law;
    SSStarFriction fr;

    for (PetscInt i = 0; i < 3; i++) {
      PetscCall(PetscRandomGetValueReal(rnd, &u[i]));
      PetscCall(PetscRandomGetValueReal(rnd, &c[i]));
    }
    if (k % 3 == 0) u[2] = 0; /* on the plane */
    PetscCall(PetscRandomGetValueReal(rnd, &phi));
    PetscCall(PetscRandomGetValueReal(rnd, &phi2));
    PetscCall(PetscRandomGetValueReal(rnd, &a[0]));
    PetscCall(PetscRandomGetValueReal(rnd, &a[1]));
    phi  = PetscAbsReal(phi);
    phi2 = 0.01 + PetscAbsReal(phi2);
    law  = k % 5 == 1 ? Tresca(phi) : (k % 5 == 2 ? Frictionless() : (k % 5 == 3 ? Orthotropic(0.01 + phi, phi2, a[0], a[1]) : Coulomb(phi)));
    fr   = Friction(law);
    SSStarApproximationStep(&fr, u, c, z, d, b);
    if (!InGraphQ(&law, d, b)) {
      Expect(PETSC_FALSE, "(d, b) in gph Q for random data", law.law);
      break;
    }
    CheckBlockIdentities(law.law, SSStarClassify(&fr, d, b, 0.0, 0.0), &fr, d, b);
    if (k % 5 == 4) { /* coulomb: the orthotropic law with phi_1 = phi_2 = phi gives the same */
      const SSStarFriction iso = Friction(Orthotropic(phi > 0 ? phi : 0.5, phi > 0 ? phi : 0.5, a[0], a[1]));
      const SSStarFriction cou = Friction(Coulomb(phi > 0 ? phi : 0.5));
      PetscReal            zo[3], dd[3], bo[3], S[9], T[9], So[9], To[9];
      SSStarState          st, sto;

      SSStarApproximationStep(&cou, u, c, z, d, b);
      SSStarApproximationStep(&iso, u, c, zo, dd, bo);
      st  = SSStarClassify(&cou, d, b, 1e-13, 1e-13);
      sto = SSStarClassify(&iso, dd, bo, 1e-13, 1e-13);
      SSStarReducedBlocks(st, &cou, d, b, S, T);
      SSStarReducedBlocks(sto, &iso, dd, bo, So, To);
      for (PetscInt i = 0; i < 9; i++)
        if (S[i] != So[i] || T[i] != To[i] || (i < 3 && (z[i] != zo[i] || d[i] != dd[i] || b[i] != bo[i])) || st != sto) {
          Expect(PETSC_FALSE, "phi_1 = phi_2 gives coulomb's step, state and blocks exactly", "orthotropic");
          break;
        }
    }
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s: %d failures\n", failures ? "FAILED" : "OK", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
