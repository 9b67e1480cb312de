static const char help[] = "Per-node kernels of ssstar against hand-computed cases of every contact state.\n";

/* Requirement: the approximation step, the classification and the G/H and S/T blocks of docs/derivation.md
   sections 1-5 give the hand-computed values for the states L, M1, M2, M3+, M3-, M4 and for phi = 0, for the
   Tresca law (L, LS, M1: no normal-tangential coupling) and without friction; (d, b) is always in gph Q, and
   T G = S H for every state and law; the node frame of (0, 0, 1) is the identity and every frame is a right-handed
   orthonormal basis with n last. Tolerance 1e-14 (absolute, O(1) data). */
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

static SSStarFriction Coulomb(PetscReal phi)
{
  SSStarFriction fr = {SSSTAR_FRICTION_COULOMB, phi, 0.0};
  return fr;
}

static SSStarFriction Tresca(PetscReal bound)
{
  SSStarFriction fr = {SSSTAR_FRICTION_TRESCA, 0.0, bound};
  return fr;
}

static const SSStarFriction Frictionless = {SSSTAR_FRICTION_NONE, 0.0, 0.0};

typedef struct {
  const char    *name;
  SSStarFriction fr;
  PetscReal      u[3], c[3];
  PetscReal   z[3], d[3], b[3]; /* expected */
  SSStarState state;
} Case;

/*
   (d, b) in gph Q (docs/derivation.md section 0): d3 >= 0, b3 <= 0, d3 b3 = 0, |b12| <= s, b12 = s d12/|d12| if d12 != 0,
   with the threshold s = -phi b3 (Coulomb), the bound (Tresca) or 0 (none)
*/
static PetscBool InGraphQ(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3])
{
  const PetscReal nd = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]), nb = PetscSqrtReal(b[0] * b[0] + b[1] * b[1]);
  const PetscReal scale = 1 + PetscAbsReal(b[2]) + fr->bound;
  const PetscReal s     = fr->law == SSSTAR_FRICTION_COULOMB ? -fr->phi * b[2] : (fr->law == SSSTAR_FRICTION_TRESCA ? fr->bound : 0.0);

  if (d[2] < 0 || b[2] > 0 || d[2] * b[2] != 0) return PETSC_FALSE;
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
  /* M1: |v| = 5 > s = 0.6, d12 = 0.88 (3, 4), b12 = (0.36, 0.48) with |b12| = phi |b3| */
  /* M3+: |v| = 0.1 < s; M3-: |v| = s = 0.6 exactly; M2, M4: u3 = c3 (weak contact) */
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
    {"none",        Frictionless, {3, 4, 0},       {0.5, 0, 2},     {-0.5, 0, 0},     {2.5, 4, 0},       {0, 0, -2},        SSSTAR_STATE_M1 },
  };
  PetscRandom rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(cases); k++) {
    const Case *cs = &cases[k];
    PetscReal   z[3], d[3], b[3];
    SSStarState state;

    SSStarApproximationStep(&cs->fr, cs->u, cs->c, z, d, b);
    Expect(Close(3, z, cs->z), "z of the approximation step", cs->name);
    Expect(Close(3, d, cs->d), "d = u + z", cs->name);
    Expect(Close(3, b, cs->b), "b = -z - c", cs->name);
    Expect(InGraphQ(&cs->fr, d, b), "(d, b) in gph Q", cs->name);
    state = SSStarClassify(&cs->fr, d, b, 0.0, 0.0);
    Expect((PetscBool)(state == cs->state), "state of Table 1", cs->name);
    CheckBlockIdentities(cs->name, state, &cs->fr, d, b);
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
    const SSStarFriction c03 = Coulomb(0.3), c0 = Coulomb(0.0), t06 = Tresca(0.6);
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
      SSStarTangentBlocks(st, &Frictionless, dz, bs, G, H);
      SSStarReducedBlocks(st, &Frictionless, dz, bs, S, T);
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

  /* Random data: the approximation step always lands in gph Q and the identities hold */
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  for (PetscInt k = 0; k < 10000; k++) {
    PetscReal      u[3], c[3], z[3], d[3], b[3], phi;
    SSStarFriction fr;

    for (PetscInt i = 0; i < 3; i++) {
      PetscCall(PetscRandomGetValueReal(rnd, &u[i]));
      PetscCall(PetscRandomGetValueReal(rnd, &c[i]));
    }
    if (k % 3 == 0) u[2] = 0; /* on the plane */
    PetscCall(PetscRandomGetValueReal(rnd, &phi));
    phi = PetscAbsReal(phi);
    fr  = k % 5 == 1 ? Tresca(phi) : (k % 5 == 2 ? Frictionless : Coulomb(phi));
    SSStarApproximationStep(&fr, u, c, z, d, b);
    if (!InGraphQ(&fr, d, b)) {
      Expect(PETSC_FALSE, "(d, b) in gph Q for random data", SSStarFrictionLaws[fr.law]);
      break;
    }
    CheckBlockIdentities(SSStarFrictionLaws[fr.law], SSStarClassify(&fr, d, b, 0.0, 0.0), &fr, d, b);
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s: %d failures\n", failures ? "FAILED" : "OK", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
