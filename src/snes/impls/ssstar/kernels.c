/*
   Per-node contact kernels of the semismooth* Newton method: pure functions on 3-vectors
   (u_t1, u_t2, u_n). Section numbers refer to DERIVATION.md.
*/
#include <ssstar.h>

const char *const SSStarStateNames[] = {"L", "M1", "M2", "M3+", "M3-", "M4", "SSStarState", "SSSTAR_STATE_", NULL};

static PetscReal Norm2(const PetscReal v[2])
{
  return PetscSqrtReal(v[0] * v[0] + v[1] * v[1]);
}

void SSStarApproximationStep(PetscReal phi, const PetscReal u[3], const PetscReal c[3], PetscReal z[3], PetscReal d[3], PetscReal b[3])
{
  const PetscReal s    = phi * PetscMax(0.0, c[2] - u[2]); /* threshold of the prox (12) */
  const PetscReal v[2] = {u[0] - c[0], u[1] - c[1]};
  const PetscReal nv   = Norm2(v);

  z[2] = PetscMax(-c[2], -u[2]); /* (11) */
  d[2] = PetscMax(u[2] - c[2], 0.0);
  b[2] = -PetscMax(0.0, c[2] - u[2]);
  /* (12): block soft-thresholding; the "if" keeps d12 an exact zero when |v| <= s */
  if (nv > s) {
    d[0] = (1.0 - s / nv) * v[0];
    d[1] = (1.0 - s / nv) * v[1];
  } else {
    d[0] = 0.0;
    d[1] = 0.0;
  }
  z[0] = d[0] - u[0];
  z[1] = d[1] - u[1];
  b[0] = -z[0] - c[0];
  b[1] = -z[1] - c[1];
}

SSStarState SSStarClassify(PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal tol_d, PetscReal tol_b)
{
  const PetscBool sliding = (PetscBool)(Norm2(d) > tol_d);

  if (d[2] > tol_d) return SSSTAR_STATE_L;
  if (-b[2] <= tol_b) return sliding ? SSSTAR_STATE_M2 : SSSTAR_STATE_M4;
  if (sliding) return SSSTAR_STATE_M1;
  return (-phi * b[2] - Norm2(b) > tol_b) ? SSSTAR_STATE_M3P : SSSTAR_STATE_M3M;
}

static PetscBool IsStrongContact(SSStarState state)
{
  return (PetscBool)(state == SSSTAR_STATE_M1 || state == SSSTAR_STATE_M3P || state == SSSTAR_STATE_M3M);
}

/* Sliding blocks: do the M1 formulas apply? Also for every strong contact when phi = 0 (section 3). */
static PetscBool UsesSlidingBlocks(SSStarState state, PetscReal phi)
{
  return (PetscBool)(state == SSSTAR_STATE_M1 || (phi == 0.0 && IsStrongContact(state)));
}

/* om = d12/|d12| and W = -phi b3/|d12| (I - om om^T) of section 3; both vanish when phi = 0. */
static void SlidingDirection(PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal om[2], PetscReal W[4])
{
  const PetscReal nd = Norm2(d);
  PetscReal       w;

  if (phi == 0.0) {
    om[0] = om[1] = 0.0;
    W[0] = W[1] = W[2] = W[3] = 0.0;
    return;
  }
  om[0] = d[0] / nd;
  om[1] = d[1] / nd;
  w     = -phi * b[2] / nd;
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

void SSStarTangentBlocks(SSStarState state, PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal G[9], PetscReal H[9])
{
  PetscReal om[2], W[4];

  if (UsesSlidingBlocks(state, phi)) {
    SlidingDirection(phi, d, b, om, W);
    SetDiagonal(G, 1.0, 1.0, 0.0);
    SetDiagonal(H, W[0], W[3], 1.0);
    H[1] = W[1];
    H[3] = W[2];
    H[2] = -phi * om[0];
    H[5] = -phi * om[1];
  } else if (IsStrongContact(state)) {
    SetDiagonal(G, 0.0, 0.0, 0.0);
    SetDiagonal(H, 1.0, 1.0, 1.0);
  } else {
    SetDiagonal(G, 1.0, 1.0, 1.0);
    SetDiagonal(H, 0.0, 0.0, 0.0);
  }
}

void SSStarReducedBlocks(SSStarState state, PetscReal phi, const PetscReal d[3], const PetscReal b[3], PetscReal S[9], PetscReal T[9])
{
  PetscReal om[2], W[4];

  if (UsesSlidingBlocks(state, phi)) {
    SlidingDirection(phi, d, b, om, W);
    SetDiagonal(S, 1.0, 1.0, 0.0);
    S[2] = phi * om[0];
    S[5] = phi * om[1];
    SetDiagonal(T, W[0], W[3], 1.0);
    T[1] = W[1];
    T[3] = W[2];
  } else if (IsStrongContact(state)) {
    SetDiagonal(S, 0.0, 0.0, 0.0);
    SetDiagonal(T, 1.0, 1.0, 1.0);
  } else {
    SetDiagonal(S, 1.0, 1.0, 1.0);
    SetDiagonal(T, 0.0, 0.0, 0.0);
  }
}
