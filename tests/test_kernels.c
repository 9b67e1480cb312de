static const char help[] = "Per-node kernels of ssstar against hand-computed cases of every contact state.\n";

/* Requirement: the approximation step, the classification and the G/H and S/T blocks of DERIVATION.md
   sections 1-5 give the hand-computed values for the states L, M1, M2, M3+, M3-, M4 and for phi = 0;
   (d, b) is always in gph Q, and T G = S H for every state. Tolerance 1e-14 (absolute, O(1) data). */
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

typedef struct {
  const char *name;
  PetscReal   phi, u[3], c[3];
  PetscReal   z[3], d[3], b[3]; /* expected */
  SSStarState state;
} Case;

/* (d, b) in gph Q (DERIVATION.md section 0): d3 >= 0, b3 <= 0, d3 b3 = 0, |b12| <= -phi b3, b12 = -phi b3 d12/|d12| if d12 != 0 */
static PetscBool InGraphQ(PetscReal phi, const PetscReal d[3], const PetscReal b[3])
{
  const PetscReal nd = PetscSqrtReal(d[0] * d[0] + d[1] * d[1]), nb = PetscSqrtReal(b[0] * b[0] + b[1] * b[1]);
  const PetscReal scale = 1 + PetscAbsReal(b[2]);

  if (d[2] < 0 || b[2] > 0 || d[2] * b[2] != 0) return PETSC_FALSE;
  if (nb > -phi * b[2] + 1e-14 * scale) return PETSC_FALSE;
  if (nd > 0 && (PetscAbsReal(b[0] + phi * b[2] * d[0] / nd) > 1e-14 * scale || PetscAbsReal(b[1] + phi * b[2] * d[1] / nd) > 1e-14 * scale)) return PETSC_FALSE;
  return PETSC_TRUE;
}

static void CheckBlockIdentities(const char name[], SSStarState state, PetscReal phi, const PetscReal d[3], const PetscReal b[3])
{
  PetscReal G[9], H[9], S[9], T[9], TG[9], SH[9];

  SSStarTangentBlocks(state, phi, d, b, G, H);
  SSStarReducedBlocks(state, phi, d, b, S, T);
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
    {"L",          0.3, {0.1, 0, 1},     {0.02, 0, 0.5},  {-0.02, 0, -0.5}, {0.08, 0, 0.5},    {0, 0, 0},         SSSTAR_STATE_L  },
    {"M1",         0.3, {3, 4, 0},       {0, 0, 2},       {-0.36, -0.48, 0}, {2.64, 3.52, 0},  {0.36, 0.48, -2},  SSSTAR_STATE_M1 },
    {"M2",         0.3, {0.1, 0.2, 0.5}, {0.05, 0, 0.5},  {-0.05, 0, -0.5}, {0.05, 0.2, 0},    {0, 0, 0},         SSSTAR_STATE_M2 },
    {"M3+",        0.3, {0.1, 0, 0},     {0, 0, 2},       {-0.1, 0, 0},     {0, 0, 0},         {0.1, 0, -2},      SSSTAR_STATE_M3P},
    {"M3-",        0.3, {0.6, 0, 0},     {0, 0, 2},       {-0.6, 0, 0},     {0, 0, 0},         {0.6, 0, -2},      SSSTAR_STATE_M3M},
    {"M4",         0.3, {0.1, 0.2, 0.5}, {0.1, 0.2, 0.5}, {-0.1, -0.2, -0.5}, {0, 0, 0},       {0, 0, 0},         SSSTAR_STATE_M4 },
    {"phi=0 stick", 0.0, {0.1, 0, 0},    {0.1, 0, 2},     {-0.1, 0, 0},     {0, 0, 0},         {0, 0, -2},        SSSTAR_STATE_M3M},
  };
  PetscRandom rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  for (size_t k = 0; k < PETSC_STATIC_ARRAY_LENGTH(cases); k++) {
    const Case *cs = &cases[k];
    PetscReal   z[3], d[3], b[3];
    SSStarState state;

    SSStarApproximationStep(cs->phi, cs->u, cs->c, z, d, b);
    Expect(Close(3, z, cs->z), "z of the approximation step", cs->name);
    Expect(Close(3, d, cs->d), "d = u + z", cs->name);
    Expect(Close(3, b, cs->b), "b = -z - c", cs->name);
    Expect(InGraphQ(cs->phi, d, b), "(d, b) in gph Q", cs->name);
    state = SSStarClassify(cs->phi, d, b, 0.0, 0.0);
    Expect((PetscBool)(state == cs->state), "state of Table 1", cs->name);
    CheckBlockIdentities(cs->name, state, cs->phi, d, b);
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
    PetscReal G[9], H[9], S[9], T[9];

    SSStarTangentBlocks(SSSTAR_STATE_M1, 0.3, d, b, G, H);
    SSStarReducedBlocks(SSSTAR_STATE_M1, 0.3, d, b, S, T);
    Expect((PetscBool)(Close(9, G, Gm1) && Close(9, H, Hm1)), "G, H with om = +d12/|d12| (section 3, corrected sign)", "M1 blocks");
    Expect((PetscBool)(Close(9, S, Sm1) && Close(9, T, Tm1)), "S, T of section 5", "M1 blocks");
    for (SSStarState st = SSSTAR_STATE_M3P; st <= SSSTAR_STATE_M3M; st++) {
      SSStarTangentBlocks(st, 0.3, dz, bs, G, H);
      SSStarReducedBlocks(st, 0.3, dz, bs, S, T);
      Expect((PetscBool)(Close(9, G, Z3) && Close(9, H, I3) && Close(9, S, Z3) && Close(9, T, I3)), "sticking blocks G = 0, H = I, S = 0, T = I", SSStarStateNames[st]);
    }
    for (SSStarState st = SSSTAR_STATE_L; st <= SSSTAR_STATE_M4; st++) {
      if (st != SSSTAR_STATE_L && st != SSSTAR_STATE_M2 && st != SSSTAR_STATE_M4) continue;
      SSStarTangentBlocks(st, 0.3, du, bz, G, H);
      SSStarReducedBlocks(st, 0.3, du, bz, S, T);
      Expect((PetscBool)(Close(9, G, I3) && Close(9, H, Z3) && Close(9, S, I3) && Close(9, T, Z3)), "free blocks G = I, H = 0, S = I, T = 0", SSStarStateNames[st]);
    }
    /* phi = 0: a sticking node in strong contact gets the frictionless sliding blocks, not the sticking ones */
    for (SSStarState st = SSSTAR_STATE_M1; st <= SSSTAR_STATE_M3M; st++) {
      if (st == SSSTAR_STATE_M2) continue;
      SSStarTangentBlocks(st, 0.0, dz, bs, G, H);
      SSStarReducedBlocks(st, 0.0, dz, bs, S, T);
      Expect((PetscBool)(Close(9, G, D110) && Close(9, H, D001) && Close(9, S, D110) && Close(9, T, D001)), "phi = 0 blocks G = S = diag(1,1,0), H = T = diag(0,0,1)", SSStarStateNames[st]);
    }
  }

  /* Random data: the approximation step always lands in gph Q and the identities hold */
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  for (PetscInt k = 0; k < 10000; k++) {
    PetscReal u[3], c[3], z[3], d[3], b[3], phi;

    for (PetscInt i = 0; i < 3; i++) {
      PetscCall(PetscRandomGetValueReal(rnd, &u[i]));
      PetscCall(PetscRandomGetValueReal(rnd, &c[i]));
    }
    if (k % 3 == 0) u[2] = 0; /* on the plane */
    PetscCall(PetscRandomGetValueReal(rnd, &phi));
    phi = PetscAbsReal(phi);
    SSStarApproximationStep(phi, u, c, z, d, b);
    if (!InGraphQ(phi, d, b)) {
      Expect(PETSC_FALSE, "(d, b) in gph Q for random data", "random");
      break;
    }
    CheckBlockIdentities("random", SSStarClassify(phi, d, b, 0.0, 0.0), phi, d, b);
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s: %d failures\n", failures ? "FAILED" : "OK", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
