static const char help[] = "A plain PETSc elasticity program: a block on a structured grid (DMDA, trilinear elements) whose top face is\n\
pushed down and sideways; its bottom face rests above a rigid plane. It assembles K and b, solves F(u) = K u - b with\n\
a SNES and declares the bottom nodes as contact nodes. It has no contact code of its own:\n\
  -snes_type ksponly   one linear solve (add -pc_type lu), the body goes through the plane\n\
  -snes_type ssstar    frictional contact (-snes_ssstar_* options)\n\
Options:\n\
  -da_grid_x <9> -da_grid_y <9> -da_grid_z <5>  nodes per direction (and any -da_* option)\n\
  -size <1,1,0.5>                 the block [0,a]x[0,b]x[0,c]\n\
  -E <2.1e5> -nu <0.3>            material\n\
  -push <0.005,0,-0.01>           displacement imposed on the top face\n\
  -obstacle_point <0,0,-0.002>    a point of the rigid plane\n\
  -obstacle_normal <0,0,1>        its normal, pointing into the body (normalized here)\n\
  -o <file.h5>                    write the contact nodes' coordinates, displacement, reaction (K u - b), normal, gap\n\
                                  and, for ssstar, the friction law of each and the values of its parameters\n\
An option nothing reads is refused before any work. Exit status 0 when the solve converged, 2 when it did not (the -o\n\
file says so: attributes converged_reason, residual_norm, iterations of \"/\"), PETSc's error code for bad input (one\n\
line naming the option or file; -ssstar_traceback adds PETSc's report). -help lists the options and does nothing else.\n";

#include <petscdmda.h>
#include <petscsnes.h>
#include <petscviewerhdf5.h>
#include <ssstar.h>
#include <ssstarscene.h> /* SSStarWriteNodeFriction() */

/* Stiffness of a trilinear brick h[0] x h[1] x h[2] (2x2x2 Gauss points); node a = di + 2 dj + 4 dk */
static void BrickStiffness(const PetscReal h[3], PetscReal lambda, PetscReal mu, PetscScalar Ke[24 * 24])
{
  const PetscReal g = 1.0 / PetscSqrtReal(3.0), detJ = h[0] * h[1] * h[2] / 8.0;

  for (PetscInt k = 0; k < 24 * 24; k++) Ke[k] = 0;
  for (PetscInt q = 0; q < 8; q++) {
    const PetscReal xi[3] = {q & 1 ? g : -g, q & 2 ? g : -g, q & 4 ? g : -g};
    PetscReal       dN[8][3];

    for (PetscInt a = 0; a < 8; a++) {
      const PetscReal s[3] = {a & 1 ? 1.0 : -1.0, a & 2 ? 1.0 : -1.0, a & 4 ? 1.0 : -1.0};
      const PetscReal f[3] = {1 + s[0] * xi[0], 1 + s[1] * xi[1], 1 + s[2] * xi[2]};

      dN[a][0] = s[0] * f[1] * f[2] / 8.0 * 2.0 / h[0];
      dN[a][1] = f[0] * s[1] * f[2] / 8.0 * 2.0 / h[1];
      dN[a][2] = f[0] * f[1] * s[2] / 8.0 * 2.0 / h[2];
    }
    for (PetscInt a = 0; a < 8; a++)
      for (PetscInt b = 0; b < 8; b++) {
        const PetscReal dot = dN[a][0] * dN[b][0] + dN[a][1] * dN[b][1] + dN[a][2] * dN[b][2];

        for (PetscInt i = 0; i < 3; i++)
          for (PetscInt j = 0; j < 3; j++) Ke[(3 * a + i) * 24 + 3 * b + j] += detJ * (lambda * dN[a][i] * dN[b][j] + mu * dN[a][j] * dN[b][i] + (i == j ? mu * dot : 0.0));
      }
  }
}

static PetscErrorCode AssembleStiffness(DM da, const PetscReal size[3], PetscReal E, PetscReal nu, Mat *K)
{
  const PetscReal lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  PetscInt        M, N, P, xs, ys, zs, xm, ym, zm;
  PetscReal       h[3];
  PetscScalar     Ke[24 * 24];

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(da, NULL, &M, &N, &P, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(da, &xs, &ys, &zs, &xm, &ym, &zm));
  h[0] = size[0] / (M - 1);
  h[1] = size[1] / (N - 1);
  h[2] = size[2] / (P - 1);
  BrickStiffness(h, lambda, mu, Ke);
  PetscCall(DMCreateMatrix(da, K));
  /* each element is added by the rank that owns its lowest corner */
  for (PetscInt k = zs; k < PetscMin(zs + zm, P - 1); k++)
    for (PetscInt j = ys; j < PetscMin(ys + ym, N - 1); j++)
      for (PetscInt i = xs; i < PetscMin(xs + xm, M - 1); i++) {
        MatStencil idx[24];

        for (PetscInt a = 0; a < 8; a++)
          for (PetscInt c = 0; c < 3; c++) {
            idx[3 * a + c].i = i + (a & 1 ? 1 : 0);
            idx[3 * a + c].j = j + (a & 2 ? 1 : 0);
            idx[3 * a + c].k = k + (a & 4 ? 1 : 0);
            idx[3 * a + c].c = c;
          }
        PetscCall(MatSetValuesStencil(*K, 24, idx, 24, idx, Ke, ADD_VALUES));
      }
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The top face moves by push: identity rows and columns (K stays SPD), the load b carries the imposed values */
static PetscErrorCode ImposeTopDisplacement(DM da, const PetscReal push[3], Mat K, Vec b)
{
  PetscInt    P, xs, ys, zs, xm, ym, zm, n = 0;
  MatStencil *rows;
  Vec         x;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(da, NULL, NULL, NULL, &P, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(da, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMGetGlobalVector(da, &x));
  PetscCall(VecZeroEntries(x));
  PetscCall(PetscMalloc1(3 * xm * ym, &rows));
  if (zs + zm == P) {
    PetscScalar ****xa;

    PetscCall(DMDAVecGetArrayDOF(da, x, &xa));
    for (PetscInt j = ys; j < ys + ym; j++)
      for (PetscInt i = xs; i < xs + xm; i++)
        for (PetscInt c = 0; c < 3; c++) {
          rows[n].i   = i;
          rows[n].j   = j;
          rows[n].k   = P - 1;
          rows[n++].c = c;
          xa[P - 1][j][i][c] = push[c];
        }
    PetscCall(DMDAVecRestoreArrayDOF(da, x, &xa));
  }
  PetscCall(VecZeroEntries(b));
  PetscCall(MatZeroRowsColumnsStencil(K, n, rows, 1.0, x, b));
  PetscCall(PetscFree(rows));
  PetscCall(DMRestoreGlobalVector(da, &x));
  PetscFunctionReturn(0);
}

/* The bottom nodes: their global dofs (3 per node), the plane's normal at each, and their distance to the plane */
static PetscErrorCode DeclareBottom(DM da, const PetscReal size[3], const PetscReal point[3], const PetscReal normal[3], IS *dofs, Vec *normals, Vec *gaps, Vec *coords)
{
  PetscInt     M, N, P, xs, ys, zs, xm, ym, zm, rstart, n = 0, *idx;
  PetscScalar *na, *ga, *ca;
  Vec          x;

  PetscFunctionBeginUser;
  PetscCall(DMDAGetInfo(da, NULL, &M, &N, &P, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL));
  PetscCall(DMDAGetCorners(da, &xs, &ys, &zs, &xm, &ym, &zm));
  PetscCall(DMGetGlobalVector(da, &x));
  PetscCall(VecGetOwnershipRange(x, &rstart, NULL));
  PetscCall(DMRestoreGlobalVector(da, &x));
  n = zs == 0 ? xm * ym : 0;
  PetscCall(PetscMalloc1(3 * n, &idx));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)da), 3 * n, PETSC_DETERMINE, normals));
  PetscCall(VecSetBlockSize(*normals, 3));
  PetscCall(VecDuplicate(*normals, coords));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)da), n, PETSC_DETERMINE, gaps));
  PetscCall(VecGetArray(*normals, &na));
  PetscCall(VecGetArray(*coords, &ca));
  PetscCall(VecGetArray(*gaps, &ga));
  /* the nodes are declared j fastest: the order of the contact nodes need not follow the order of their dofs */
  for (PetscInt q = 0; q < n; q++) {
    const PetscInt  i = xs + q / ym, j = ys + q % ym;
    const PetscReal X[3] = {size[0] * i / (M - 1), size[1] * j / (N - 1), 0.0};

    /* owned nodes are numbered i fastest, then j, then k, 3 dofs each */
    for (PetscInt c = 0; c < 3; c++) {
      idx[3 * q + c] = rstart + 3 * ((j - ys) * xm + (i - xs)) + c;
      na[3 * q + c]  = normal[c];
      ca[3 * q + c]  = X[c];
    }
    ga[q] = (X[0] - point[0]) * normal[0] + (X[1] - point[1]) * normal[1] + (X[2] - point[2]) * normal[2];
    PetscCheck(ga[q] >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Bottom node (%g, %g, 0) starts %g inside the obstacle: move -obstacle_point", (double)X[0], (double)X[1], (double)-ga[q]);
  }
  PetscCall(VecRestoreArray(*gaps, &ga));
  PetscCall(VecRestoreArray(*coords, &ca));
  PetscCall(VecRestoreArray(*normals, &na));
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)da), 3 * n, idx, PETSC_OWN_POINTER, dofs));
  PetscFunctionReturn(0);
}

static PetscErrorCode GetVector3(const char name[], PetscReal v[3])
{
  PetscInt  n = 3;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, name, v, &n, &set));
  PetscCheck(!set || n == 3, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "Option %s needs three comma-separated values x,y,z (got %" PetscInt_FMT ")", name, n);
  for (PetscInt k = 0; k < 3; k++) PetscCheck(!PetscIsInfOrNanReal(v[k]), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "Option %s: %g is not a number", name, (double)v[k]);
  PetscFunctionReturn(0);
}

/* The worst penetration min(gap + u.n) over the bottom nodes, and the total force K u - b on them along n */
static PetscErrorCode Report(Vec u, Vec r, IS dofs, Vec normals, Vec gaps)
{
  Vec                uC, rC;
  const PetscScalar *ua, *ra, *na, *ga;
  PetscInt           n;
  PetscReal          local[2] = {PETSC_MAX_REAL, 0}, worst, force;

  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(u, dofs, &uC));
  PetscCall(VecGetSubVector(r, dofs, &rC));
  PetscCall(VecGetLocalSize(gaps, &n));
  PetscCall(VecGetArrayRead(uC, &ua));
  PetscCall(VecGetArrayRead(rC, &ra));
  PetscCall(VecGetArrayRead(normals, &na));
  PetscCall(VecGetArrayRead(gaps, &ga));
  for (PetscInt q = 0; q < n; q++) {
    local[0] = PetscMin(local[0], PetscRealPart(ga[q] + ua[3 * q] * na[3 * q] + ua[3 * q + 1] * na[3 * q + 1] + ua[3 * q + 2] * na[3 * q + 2]));
    local[1] += PetscRealPart(ra[3 * q] * na[3 * q] + ra[3 * q + 1] * na[3 * q + 1] + ra[3 * q + 2] * na[3 * q + 2]);
  }
  PetscCall(VecRestoreArrayRead(gaps, &ga));
  PetscCall(VecRestoreArrayRead(normals, &na));
  PetscCall(VecRestoreArrayRead(rC, &ra));
  PetscCall(VecRestoreArrayRead(uC, &ua));
  PetscCall(VecRestoreSubVector(r, dofs, &rC));
  PetscCall(VecRestoreSubVector(u, dofs, &uC));
  PetscCall(MPIU_Allreduce(&local[0], &worst, 1, MPIU_REAL, MPIU_MIN, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(&local[1], &force, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "smallest distance to the plane %.6e (negative: penetration); force on the bottom along n %.6e\n", (double)worst, (double)force));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteContactNodes(const char file[], SNES snes, Vec u, Vec r, IS dofs, Vec normals, Vec gaps, Vec coords)
{
  PetscViewer viewer;
  Vec         uC, rC;
  PetscBool   isssstar;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/contact"));
  PetscCall(VecGetSubVector(u, dofs, &uC));
  PetscCall(VecGetSubVector(r, dofs, &rC));
  PetscCall(PetscObjectSetName((PetscObject)uC, "displacement"));
  PetscCall(PetscObjectSetName((PetscObject)rC, "reaction"));
  PetscCall(PetscObjectSetName((PetscObject)normals, "normal"));
  PetscCall(PetscObjectSetName((PetscObject)gaps, "gap"));
  PetscCall(PetscObjectSetName((PetscObject)coords, "coordinates"));
  PetscCall(VecSetBlockSize(uC, 3));
  PetscCall(VecSetBlockSize(rC, 3));
  PetscCall(VecView(uC, viewer));
  PetscCall(VecView(rC, viewer));
  PetscCall(VecView(normals, viewer));
  PetscCall(VecView(gaps, viewer));
  PetscCall(VecView(coords, viewer));
  PetscCall(VecRestoreSubVector(r, dofs, &rC));
  PetscCall(VecRestoreSubVector(u, dofs, &uC));
  PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESSSSTAR, &isssstar));
  if (isssstar) PetscCall(SSStarWriteNodeFriction(snes, viewer, "/contact")); /* friction_law and the laws' parameters, as the scenes write them */
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(SSStarWriteOutcome(snes, viewer)); /* how the solve ended */
  PetscCall(PetscViewerDestroy(&viewer));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscReal           size[3] = {1, 1, 0.5}, push[3] = {0.005, 0, -0.01}, point[3] = {0, 0, -0.002}, normal[3] = {0, 0, 1}, E = 2.1e5, nu = 0.3, len;
  char                out[PETSC_MAX_PATH_LEN] = "";
  PetscBool           hasOut, hasHelp, hasType;
  DM                  da;
  Mat                 K;
  Vec                 b;
  SNES                snes;
  Vec                 u, r, normals, gaps, coords;
  IS                  dofs;
  PetscInt            its;
  SNESConvergedReason reason;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SSStarInitializePackage());
  PetscCall(SSStarPushErrorHandler());
  /* every option, before any work */
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "A block pushed onto a plane", NULL);
  PetscCall(PetscOptionsReal("-E", "Young's modulus", NULL, E, &E, NULL));
  PetscCall(PetscOptionsReal("-nu", "Poisson ratio", NULL, nu, &nu, NULL));
  PetscCall(PetscOptionsString("-o", "Output file (HDF5) for the contact nodes", NULL, out, out, sizeof(out), &hasOut));
  PetscOptionsEnd();
  PetscCall(GetVector3("-size", size));
  PetscCall(GetVector3("-push", push));
  PetscCall(GetVector3("-obstacle_point", point));
  PetscCall(GetVector3("-obstacle_normal", normal));
  PetscCheck(E > 0 && nu > -1 && nu < 0.5, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-E %g -nu %g: need E > 0 and -1 < nu < 0.5", (double)E, (double)nu);
  len = PetscSqrtReal(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  PetscCheck(len > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-obstacle_normal is zero");
  for (PetscInt k = 0; k < 3; k++) normal[k] /= len;
  PetscCall(DMDACreate3d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX, 9, 9, 5, PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, 3, 1, NULL, NULL, NULL, &da));
  PetscCall(DMSetFromOptions(da));
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(PetscOptionsHasHelp(NULL, &hasHelp));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-snes_type", &hasType));
  if (hasHelp && !hasType) PetscCall(SNESSetType(snes, SNESSSSTAR)); /* -help lists the options of ssstar */
  PetscCall(SNESSetFromOptions(snes));
  if (hasHelp) { /* the options are listed: no assembly, no solve, no file */
    PetscCall(SNESDestroy(&snes));
    PetscCall(DMDestroy(&da));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(SSStarCheckOptionsUsed(PETSC_COMM_WORLD, (const char *const[]){help, NULL}, snes));

  PetscCall(DMSetUp(da));
  PetscCall(AssembleStiffness(da, size, E, nu, &K));
  PetscCall(DMCreateGlobalVector(da, &b));
  PetscCall(ImposeTopDisplacement(da, push, K, b));
  PetscCall(DeclareBottom(da, size, point, normal, &dofs, &normals, &gaps, &coords));

  PetscCall(SNESSSStarSetLinearProblem(snes, K, b)); /* F(u) = K u - b, with any SNES type */
  PetscCall(SNESSSStarSetContactNodes(snes, dofs, normals, gaps)); /* ignored by other SNES types */
  PetscCall(DMCreateGlobalVector(da, &u));
  PetscCall(VecZeroEntries(u));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(VecDuplicate(u, &r));
  PetscCall(SNESComputeFunction(snes, u, r));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s after %" PetscInt_FMT " iterations\n", SNESConvergedReasons[reason], its));
  PetscCall(Report(u, r, dofs, normals, gaps));
  if (hasOut) PetscCall(WriteContactNodes(out, snes, u, r, dofs, normals, gaps, coords));
  if (reason <= 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "The solve did not converge (%s): exit status %d\n", SNESConvergedReasons[reason], SSSTAR_EXIT_NOT_CONVERGED));

  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&u));
  PetscCall(SNESDestroy(&snes));
  PetscCall(ISDestroy(&dofs));
  PetscCall(VecDestroy(&normals));
  PetscCall(VecDestroy(&gaps));
  PetscCall(VecDestroy(&coords));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&b));
  PetscCall(DMDestroy(&da));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : SSSTAR_EXIT_NOT_CONVERGED;
}
