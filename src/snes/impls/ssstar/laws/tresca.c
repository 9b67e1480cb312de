/*
   The law "tresca": |r_t| <= s with a given slip bound s (a force), whatever r_n; r_t = -s u_t/|u_t| where the node
   slips (docs/derivation.md section 0). It is Coulomb with the threshold phi r_n replaced by the constant s: the same
   tangential step with the threshold s, no normal-tangential coupling, and a tangential state of its own on separated
   nodes (L: slipping, LS: stuck).
*/
#include "lawimpl.h"

/* value[0] = s, in the units of the kernels' c (gamma times the force) */

static void Tangential_Tresca(const SSStarFriction *fr, PetscReal rn, const PetscReal v[2], PetscReal d[2])
{
  SSStarSoftThreshold(fr->value[0], v, d);
}

static PetscReal Margin_Tresca(const SSStarFriction *fr, const PetscReal b[3])
{
  return fr->value[0] - PetscSqrtReal(b[0] * b[0] + b[1] * b[1]);
}

static void Sliding_Tresca(const SSStarFriction *fr, const PetscReal d[3], const PetscReal b[3], PetscReal W[4], PetscReal k[2])
{
  SSStarIsotropicSliding(fr->value[0], 0.0, d, W, k);
}

static PetscBool Frictionless_Tresca(const SSStarFriction *fr)
{
  return PETSC_FALSE;
}

PetscErrorCode SSStarLawCreate_Tresca(SSStarLaw law)
{
  PetscFunctionBegin;
  law->label                 = "Tresca";
  law->effect                = "Tresca friction";
  law->nparams               = 1;
  law->params[0].name        = "slip_bound";
  law->params[0].description = "slip bound";
  law->params[0].symbol      = "s";
  law->params[0].kind        = SSSTAR_LAW_FORCE;
  law->coupled               = PETSC_FALSE;
  law->separate              = PETSC_TRUE;
  law->ops.tangential        = Tangential_Tresca;
  law->ops.margin            = Margin_Tresca;
  law->ops.sliding           = Sliding_Tresca;
  law->ops.frictionless      = Frictionless_Tresca;
  PetscFunctionReturn(0);
}
