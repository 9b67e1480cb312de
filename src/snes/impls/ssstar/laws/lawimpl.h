#ifndef SSSTARLAWIMPL_H
#define SSSTARLAWIMPL_H

/*
   A friction law of ssstar (docs/derivation.md sections 1-5): one file per law in this folder, registered by name
   (lawregall.c). The law-independent parts of the per-node kernels (the normal part of the approximation step, the
   states, the assembly of G, H, S, T, the frames) are in ../kernels.c; a law gives what depends on it:

     its named parameters                   (SSStarLawParameter: what SNESSSStarSetLawParameter() names)
     the tangential approximation step      d_t = prox of r_n sigma at v = u_t - c_t, r_n = -b_3 (section 1)
     its classification                     how far b_t lies inside the friction set (M3+ or M3-, section 2)
     its blocks                             a sliding node's W = d b_t / d d_t and coupling k = -d b_t / d b_3 (3.1)

   Table 1's states apply to every law; a law whose tangential law holds whatever the normal contact (Tresca: its
   bound does not depend on r_n) has a tangential state of its own on separated nodes (LS).

   A new law is a file here whose SSStarLawCreate_<Name>() fills a _n_SSStarLaw and its registration in lawregall.c;
   the options, checks, views and output of the solver and the scenes read the table (docs/guide/own-program.md, "Adding a friction law").
*/
#include <ssstar.h>

#define SSSTAR_LAW_MAX_PARAMETERS 3

/* A named parameter of a law; its kind (ssstar.h: a coefficient, a force or a direction) says how many values it has
   and how they are checked. The kernels see a force times gamma, a direction in the node's frame. */
typedef struct {
  const char            *name;        /* SNESSSStarSetLawParameter()'s name, the options -snes_ssstar_<name>, -<name>_<G> */
  const char            *description; /* for messages, -help and -snes_view: "friction coefficient"                      */
  const char            *symbol;      /* for -snes_view and the scene's view: "phi"                                     */
  SSStarLawParameterKind kind;
  PetscBool              hasDefault;  /* the solver's value for every node until one is set (a coefficient or force)    */
  PetscReal              defaultValue;
} SSStarLawParameter;

typedef struct {
  /* d_t of the approximation step (1.2) at v = u_t - c_t, with the normal force rn = max(0, c_3 - u_3) */
  void (*tangential)(const SSStarFriction *, PetscReal rn, const PetscReal v[2], PetscReal d[2]);
  /* how far b_t lies inside the friction set at the normal force -b_3, in force units: > tol_b is M3+ (2.1) */
  PetscReal (*margin)(const SSStarFriction *, const PetscReal b[3]);
  /* a sliding node at (d, b): W (2x2, row-major) and the coupling k of (3.1); zero where there is no friction force */
  void (*sliding)(const SSStarFriction *, const PetscReal d[3], const PetscReal b[3], PetscReal W[4], PetscReal k[2]);
  /* the node has no tangential force at all: every node in strong contact slides (section 3, "phi = 0") */
  PetscBool (*frictionless)(const SSStarFriction *);
  /* its friction set at the normal force 1 as the image D (unit disk) of a 2 x 2 matrix D (row-major, the node's
     frame): phi I for Coulomb, M^1/2 for the orthotropic law, 0 frictionless; so its friction cone is
     { (D t', r_n) : |t'| <= r_n }. Floating bodies: a load these cones cannot balance has no equilibrium
     (docs/derivation.md section 14). NULL: no such cone (a bound that does not grow with r_n, as Tresca's): no load is
     refused for such a node */
  void (*cone)(const SSStarFriction *, PetscReal D[4]);
  /* checks the values and puts them in the form the kernels use (a direction projected onto the tangent plane);
     NULL, or what is wrong ("the friction direction is normal to the contact plane"). Optional. */
  const char *(*prepare)(SSStarFriction *);
} SSStarLawOps;

struct _n_SSStarLaw {
  char              *name;
  PetscInt           index;     /* its place in the table: the code of /contact/friction_law        */
  const char        *label;     /* "Coulomb" in -snes_view's "contact nodes: 3 frictionless, 5 Coulomb" */
  const char        *effect;    /* "Coulomb friction" in the active effects; NULL: frictionless      */
  PetscInt           nparams;
  SSStarLawParameter params[SSSTAR_LAW_MAX_PARAMETERS];
  const char        *paramNames[SSSTAR_LAW_MAX_PARAMETERS]; /* their names, for SSStarLawGetInfo()      */
  PetscBool          coupled;   /* the friction force depends on the normal force: the regularized Newton step
                                   (ssstar.c) drops that coupling when the Newton matrix is singular       */
  PetscBool          separate;  /* the tangential law holds on separated nodes too (Tresca): states L, LS */
  SSStarLawOps       ops;
};

/* The number of values of a parameter in SSStarFriction.value (3 for a direction), and where a law's parameter starts */
PETSC_INTERN PetscInt SSStarLawParameterSize(SSStarLawParameterKind);
PETSC_INTERN PetscInt SSStarLawParameterOffset(SSStarLaw, PetscInt);

/* The table (law.c): a law by index, where a parameter name is in a law (-1: not its), what a parameter name is */
PETSC_INTERN PetscErrorCode SSStarLawGet(PetscInt, SSStarLaw *);
PETSC_INTERN PetscErrorCode SSStarLawFind(const char[], SSStarLaw *);
PETSC_INTERN PetscInt       SSStarLawFindParameter(SSStarLaw, const char[]);
PETSC_INTERN PetscErrorCode SSStarLawGetParameter(const char[], const SSStarLawParameter **);
PETSC_INTERN PetscErrorCode SSStarLawCheckValues(const SSStarLawParameter *, const PetscReal[], char[], size_t);
PETSC_INTERN PetscErrorCode SSStarLawDestroyAll(void);
PETSC_EXTERN PetscBool      SSStarLawRegisterAllCalled;

/* Shared by the isotropic laws (kernels.c): the block soft-thresholding d = max(0, 1 - s/|v|) v (1.2), and W, k of a
   sliding node with the friction force s om (s = the threshold at the node) and coupling kappa om, om = d_t/|d_t| */
PETSC_INTERN void SSStarSoftThreshold(PetscReal s, const PetscReal v[2], PetscReal d[2]);
PETSC_INTERN void SSStarIsotropicSliding(PetscReal s, PetscReal kappa, const PetscReal d[3], PetscReal W[4], PetscReal k[2]);

#endif
