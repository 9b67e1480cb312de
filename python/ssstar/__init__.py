"""ssstar from Python: the SNES type "ssstar" (semismooth* Newton for 3D contact with friction) over petsc4py.

Importing the module loads libssstar.so (ctypes) and registers the type; the functions take petsc4py objects and call
the C API of include/ssstar.h with their handles (docs/guide/python.md, docs/manual.md for each C function):

    from petsc4py import PETSc
    import ssstar

    snes = PETSc.SNES().create()
    snes.setType(ssstar.SNESSSSTAR)
    ssstar.set_linear_problem(snes, K, b)        # F(u) = K u - b, Jacobian K (SPD)
    ssstar.set_contact_nodes(snes, dofs, normals, gaps)
    ssstar.set_node_law_parameter(snes, "friction", phi)  # or set_friction(snes, 0.3), set_node_friction_laws(...)
    snes.setFromOptions()
    snes.solve(None, u)
    states, counts = ssstar.get_states(snes)     # per local contact node, codes into ssstar.STATE_NAMES
    forces = ssstar.get_contact_forces(snes)     # K u - b at each local contact node (global axes), n x 3

The friction laws are those of the library's table (FRICTION_LAWS, read from it at import: none, tresca, coulomb,
orthotropic); each has named parameters (LAW_PARAMETERS; set_law_parameter, set_node_law_parameter: "friction",
"slip_bound", "friction_1", "friction_2", "friction_direction"). The reductions (REDUCTION_TYPES) and the names of the
states, reasons, methods and remedies are read from the library too.

Arguments that are arrays per local contact node (dofs, normals, gaps, parameter values) may be given as
numpy arrays (or sequences): the module makes the IS or Vec on the SNES's communicator, and the library checks them
on every rank: input wrong on one rank raises petsc4py.PETSc.Error on every rank, with PETSc's error code (PETSc prints
the message of the rank that found it on stderr), so that no rank waits for another in a collective call.

Scenes (the scene library of examples/contact: meshes, groups, obstacles, pairs, load paths, the output file) are
ssstar.Scene: help(ssstar.Scene).

A PETSc error of the library raises ssstar.Error (a petsc4py.PETSc.Error): str() is the library's message, naming the
option, file, group or node; .ierr is PETSc's error code.

The library is found, in this order, at $SSSTAR_LIB, the one the module was installed with (_config.py: `pip install
./python` copies it beside the module, `make install` records PREFIX/lib), or in the source tree (lib/libssstar.so
beside this python/ folder); an installed module refuses a library of another version.
"""
import ctypes
import os

import numpy as np
from petsc4py import PETSc

__all__ = ["Scene", "Step", "Error", "__version__", "SNESSSSTAR", "STATE_NAMES", "FRICTION_LAWS", "LAW_PARAMETERS", "REASONS", "REDUCTION_TYPES", "METHODS", "REMEDIES", "library",
           "set_linear_problem", "set_affine", "get_affine", "get_nonlinear_counts", "set_contact_nodes", "get_contact_nodes", "set_contact_operator",
           "set_contact_offsets", "get_contact_offsets",
           "set_reduction_type", "get_reduction_type", "set_memory_limit", "set_friction_law", "get_friction_law",
           "law_parameters", "set_law_parameter", "set_friction", "get_friction", "set_node_law_parameter",
           "set_node_friction_laws", "get_node_friction_laws", "get_node_law_parameter", "set_scaling", "get_scaling", "set_state_tolerance", "set_method", "get_method",
           "set_lu_reuse", "set_globalization", "get_states", "get_reason", "get_tolerance", "get_remedy_counts",
           "get_newton_step_counts", "get_condition_estimate", "get_contact_forces", "write_node_friction"]

SNESSSSTAR = "ssstar"


try:
    from . import _config  # written by pip install ./python or make install: the library and version installed with
except ImportError:
    _config = None


def _find_library():
    if os.environ.get("SSSTAR_LIB"):
        return os.environ["SSSTAR_LIB"]
    if _config is not None:
        return _config.LIBRARY
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.join(os.path.dirname(os.path.dirname(here)), "lib", "libssstar.so")


library = _find_library()
if not os.path.exists(library):
    raise ImportError("ssstar: cannot find libssstar.so at %s (build it with make, or set SSSTAR_LIB)" % library)
_lib = ctypes.CDLL(library, mode=ctypes.RTLD_GLOBAL)

# PETSc's scalar types of this build (Debian's PETSc 3.18: 32-bit PetscInt, double PetscReal)
_Int = {4: ctypes.c_int32, 8: ctypes.c_int64}[PETSc.IntType(0).itemsize]
_Real = {4: ctypes.c_float, 8: ctypes.c_double}[PETSc.RealType(0).itemsize]
_Handle = ctypes.c_void_p
_Enum = ctypes.c_int


def _enum_names(symbol):
    """The names of one of ssstar's enums, from its name table (const char *const[] in PETSc's form: the names, the
    enum's name, its prefix, NULL)"""
    table = ctypes.cast(ctypes.addressof(ctypes.c_void_p.in_dll(_lib, symbol)), ctypes.POINTER(ctypes.c_char_p))
    names = []
    while table[len(names)] is not None:
        names.append(table[len(names)].decode())
    return names[:-2]


def _declare(name, *argtypes):
    f = getattr(_lib, name)
    f.argtypes = list(argtypes)
    f.restype = ctypes.c_int
    return f


class Error(PETSc.Error):
    """An error of ssstar's C library: str() is its message (naming the option, file, group or node), ierr PETSc's error
    code and reason PETSc's words for it. A petsc4py.PETSc.Error: except PETSc.Error catches it too."""

    def __init__(self, ierr, message="", reason=""):
        PETSc.Error.__init__(self, ierr)
        self.message, self.reason = message, reason

    def __str__(self):
        return self.message or self.reason or PETSc.Error.__str__(self)


_error_message = _declare("PetscErrorMessage", ctypes.c_int, ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_char_p))
_name_bad_value = _declare("SSStarOptionsNameBadValue", ctypes.c_char_p, ctypes.c_char_p, ctypes.c_size_t)


def _error(ierr):
    """The Error of PETSc's error code ierr: the message of the error's first call, naming the option whose value PETSc's
    options parser could not read (SSStarOptionsNameBadValue(): "Option -snes_rtol abc: abc is not a number")"""
    text, specific = ctypes.c_char_p(), ctypes.c_char_p()
    _error_message(ierr, ctypes.byref(text), ctypes.byref(specific))
    message = (specific.value or b"").decode(errors="replace").strip()
    named = ctypes.create_string_buffer(1024)
    if message and not _name_bad_value(message.encode(), named, len(named)) and named.value:
        message = named.value.decode(errors="replace")
    return Error(ierr, message, (text.value or b"").decode(errors="replace"))


def _call(f, *args):
    ierr = f(*args)
    if ierr:
        raise _error(ierr)


def _petsc4py(f, *args):
    """f(*args), a petsc4py call; its PETSc error raised as an Error that names a bad option (_error())"""
    try:
        return f(*args)
    except Error:
        raise
    except PETSc.Error as e:
        raise _error(e.ierr) from None


_call(_declare("SSStarInitializePackage"))  # registers the SNES type "ssstar"


def _library_version():
    v = [_Int(), _Int(), _Int()]
    _call(_declare("SSStarGetVersionNumber", *[ctypes.POINTER(_Int)] * 3), *[ctypes.byref(x) for x in v])
    return "%d.%d.%d" % tuple(x.value for x in v)


__version__ = _library_version()
if _config is not None and getattr(_config, "VERSION", __version__) != __version__:
    raise ImportError("ssstar %s: the library %s is version %s; install the module again with the library (pip install ./python, or make install)" % (_config.VERSION, library, __version__))


def _listed(function):
    """The names a function of the library lists as (n, names): SSStarLawGetNames() and the like"""
    n, names = _Int(), ctypes.POINTER(ctypes.c_char_p)()
    _call(_declare(function, ctypes.POINTER(_Int), ctypes.POINTER(ctypes.POINTER(ctypes.c_char_p))), ctypes.byref(n), ctypes.byref(names))
    return [names[i].decode() for i in range(n.value)]


STATE_NAMES = _enum_names("SSStarStateNames")  # L, M1, M2, M3+, M3-, M4, LS: the codes of get_states()
FRICTION_LAWS = _listed("SSStarLawGetNames")  # the library's table: none, tresca, coulomb, orthotropic
LAW_PARAMETERS = _listed("SSStarLawGetParameterNames")  # their parameters: friction, slip_bound, friction_1, ...
REASONS = _enum_names("SSStarReasons")
REDUCTION_TYPES = _listed("SSStarReductionGetNames")  # the registered reductions, then auto
METHODS = _enum_names("SSStarMethods")
REMEDIES = _enum_names("SSStarRemedies")
_NUM_STATES, _NUM_REMEDIES = len(STATE_NAMES), len(REMEDIES)

_C = {name: _declare(name, *args) for name, args in {
    "SNESSSStarSetContactNodes": (_Handle, _Handle, _Handle, _Handle),
    "SNESSSStarGetContactNodes": (_Handle, ctypes.POINTER(_Int), ctypes.POINTER(_Handle), ctypes.POINTER(_Handle), ctypes.POINTER(_Handle)),
    "SNESSSStarSetContactOperator": (_Handle, _Handle, _Handle, _Handle),
    "SNESSSStarSetContactOffsets": (_Handle, _Handle),
    "SNESSSStarGetContactOffsets": (_Handle, ctypes.POINTER(_Handle)),
    "SNESSSStarSetLinearProblem": (_Handle, _Handle, _Handle),
    "SNESSSStarSetAffine": (_Handle, _Enum),
    "SNESSSStarGetAffine": (_Handle, ctypes.POINTER(_Enum)),
    "SNESSSStarGetNonlinearCounts": (_Handle, ctypes.POINTER(_Int), ctypes.POINTER(_Int)),
    "SNESSSStarSetReductionType": (_Handle, ctypes.c_char_p),
    "SNESSSStarGetReductionType": (_Handle, ctypes.POINTER(ctypes.c_char_p)),
    "SNESSSStarSetMemoryLimit": (_Handle, _Real),
    "SNESSSStarSetFrictionLaw": (_Handle, ctypes.c_char_p),
    "SNESSSStarGetFrictionLaw": (_Handle, ctypes.POINTER(ctypes.c_char_p)),
    "SNESSSStarSetLawParameter": (_Handle, ctypes.c_char_p, _Int, ctypes.POINTER(_Real)),
    "SNESSSStarSetFriction": (_Handle, _Real),
    "SNESSSStarGetFriction": (_Handle, ctypes.POINTER(_Real)),
    "SNESSSStarSetNodeLawParameter": (_Handle, ctypes.c_char_p, _Handle),
    "SNESSSStarSetNodeFrictionLaws": (_Handle, _Int, ctypes.POINTER(_Int)),
    "SNESSSStarGetNodeFrictionLaws": (_Handle, _Int, ctypes.POINTER(_Int)),
    "SNESSSStarGetNodeLawParameter": (_Handle, ctypes.c_char_p, _Int, ctypes.POINTER(_Real)),
    "SSStarLawGetInfo": (_Int, ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(ctypes.c_char_p), ctypes.POINTER(_Int), ctypes.POINTER(ctypes.POINTER(ctypes.c_char_p))),
    "SSStarLawGetParameterSize": (ctypes.c_char_p, ctypes.POINTER(_Int)),
    "SSStarWriteNodeFriction": (_Handle, _Handle, ctypes.c_char_p),
    "SNESSSStarSetScaling": (_Handle, _Real),
    "SNESSSStarGetScaling": (_Handle, ctypes.POINTER(_Real)),
    "SNESSSStarSetStateTolerance": (_Handle, _Real),
    "SNESSSStarSetMethod": (_Handle, _Enum),
    "SNESSSStarGetMethod": (_Handle, ctypes.POINTER(_Enum)),
    "SNESSSStarSetLUReuse": (_Handle, _Real),
    "SNESSSStarSetGlobalization": (_Handle, _Int, _Real, _Int),
    "SNESSSStarGetStates": (_Handle, ctypes.POINTER(ctypes.POINTER(_Enum)), ctypes.POINTER(_Int)),
    "SNESSSStarGetReason": (_Handle, ctypes.POINTER(_Enum)),
    "SNESSSStarGetTolerance": (_Handle, ctypes.POINTER(_Real)),
    "SNESSSStarGetRemedyCounts": (_Handle, ctypes.POINTER(_Int)),
    "SNESSSStarGetNewtonStepCounts": (_Handle, ctypes.POINTER(_Int), ctypes.POINTER(_Int), ctypes.POINTER(_Int)),
    "SNESSSStarGetConditionEstimate": (_Handle, ctypes.POINTER(_Real)),
    "SNESSSStarReleaseWork": (_Handle,),
}.items()}


def _h(obj):
    """The C handle of a petsc4py object, or NULL for None"""
    return _Handle(obj.handle) if obj is not None else _Handle(None)


def _choice(value, names, what):
    if isinstance(value, str):
        if value.lower() not in names:
            raise ValueError("%s %r: one of %s" % (what, value, ", ".join(names)))
        return names.index(value.lower())
    if not 0 <= int(value) < len(names):
        raise ValueError("%s %r: a code 0..%d" % (what, value, len(names) - 1))
    return int(value)


def _node_vec(snes, values, per, what):
    """A Vec of per entries for each local contact node from a petsc4py Vec (kept), an array, or None"""
    if values is None or isinstance(values, PETSc.Vec):
        return values
    a = np.ascontiguousarray(np.asarray(values, dtype=PETSc.ScalarType).reshape(-1))
    # no local check of the size: the library checks it on every rank (a local error would leave the others waiting)
    v = PETSc.Vec().createMPI((a.size, PETSc.DECIDE), bsize=per if per > 1 and a.size % per == 0 else None, comm=snes.getComm())
    v.setArray(a)
    return v


def _dofs_is(snes, dofs):
    if isinstance(dofs, PETSc.IS):
        return dofs
    a = np.asarray(dofs, dtype=PETSc.IntType).reshape(-1)  # 3 per node: checked by the library on every rank
    return PETSc.IS().createGeneral(a, comm=snes.getComm())


def set_contact_nodes(snes, dofs, normals=None, gaps=None):
    """SNESSSStarSetContactNodes(): the contact nodes of a whole-body problem F(u) = K u - b. dofs: the global x, y, z
    dofs of each contact node owned by this rank (IS or array, 3 per node); normals: the unit normal of each node's
    plane into the body (Vec or array, 3 per node; None: (0, 0, 1)); gaps: the initial distance (1 per node; None: 0)"""
    is_ = _dofs_is(snes, dofs)
    _call(_C["SNESSSStarSetContactNodes"], _h(snes), _h(is_), _h(_node_vec(snes, normals, 3, "normals")), _h(_node_vec(snes, gaps, 1, "gaps")))


def get_contact_nodes(snes):
    """SNESSSStarGetContactNodes(): (n, dofs, normals, gaps): the number of contact nodes of this rank and what
    set_contact_nodes() declared as numpy arrays (None where not declared; n = -1 for a reduced problem whose function
    vector does not exist yet)"""
    n, handles = _Int(), [_Handle() for _ in range(3)]
    _call(_C["SNESSSStarGetContactNodes"], _h(snes), ctypes.byref(n), *(ctypes.byref(h) for h in handles))
    out = []
    for h, kind in zip(handles, (PETSc.IS, PETSc.Vec, PETSc.Vec)):
        out.append(None if not h.value else _borrowed_array(h.value, kind))
    return (n.value, *out)


def _borrowed_array(handle, kind):
    """The local entries of a C IS or Vec the SNES owns (copied)"""
    if kind is PETSc.IS:
        get = _declare("ISGetLocalSize", _Handle, ctypes.POINTER(_Int))
        idx = _declare("ISGetIndices", _Handle, ctypes.POINTER(ctypes.POINTER(_Int)))
        restore = _declare("ISRestoreIndices", _Handle, ctypes.POINTER(ctypes.POINTER(_Int)))
        ctype, dtype = _Int, PETSc.IntType
    else:
        get = _declare("VecGetLocalSize", _Handle, ctypes.POINTER(_Int))
        idx = _declare("VecGetArrayRead", _Handle, ctypes.POINTER(ctypes.POINTER(_Real)))
        restore = _declare("VecRestoreArrayRead", _Handle, ctypes.POINTER(ctypes.POINTER(_Real)))
        ctype, dtype = _Real, PETSc.RealType
    n, p = _Int(), ctypes.POINTER(ctype)()
    _call(get, _Handle(handle), ctypes.byref(n))
    _call(idx, _Handle(handle), ctypes.byref(p))
    a = np.array(np.ctypeslib.as_array(p, shape=(n.value,)) if n.value else [], dtype=dtype)
    _call(restore, _Handle(handle), ctypes.byref(p))
    return a


def set_contact_operator(snes, dofs, B, gaps=None):
    """SNESSSStarSetContactOperator(): contact points by an operator B (a petsc4py Mat, 3 rows per point)"""
    is_ = _dofs_is(snes, dofs)
    _call(_C["SNESSSStarSetContactOperator"], _h(snes), _h(is_), _h(B), _h(_node_vec(snes, gaps, 1, "gaps")))


def set_contact_offsets(snes, offsets):
    """SNESSSStarSetContactOffsets(): the offsets of a load path's step, w = R u + o instead of R u + g e3
    (docs/derivation.md (10.4)); 3 per local contact point in its frame (Vec or array), or None: back to the gaps. Read
    at every solve: the reduction is kept"""
    _call(_C["SNESSSStarSetContactOffsets"], _h(snes), _h(_node_vec(snes, offsets, 3, "offsets")))


def get_contact_offsets(snes):
    """SNESSSStarGetContactOffsets(): the offsets in use as a numpy array (3 per local contact point), or None"""
    h = _Handle()
    _call(_C["SNESSSStarGetContactOffsets"], _h(snes), ctypes.byref(h))
    return None if not h.value else _borrowed_array(h.value, PETSc.Vec)


def set_linear_problem(snes, K, b):
    """SNESSSStarSetLinearProblem(): F(u) = K u - b with Jacobian K (a whole body), or the reduced c(u) = P u - f; the
    SNES keeps K and b (change b's values to change the load)"""
    _call(_C["SNESSSStarSetLinearProblem"], _h(snes), _h(K), _h(b))


def set_affine(snes, affine):
    """SNESSSStarSetAffine(): whether F is affine (K u - b: the Jacobian once per solve, the fast route) or nonlinear (F at
    the iterates, the Jacobian again as -snes_lag_jacobian says, on the whole body); docs/guide/nonlinear-residuals.md"""
    _call(_C["SNESSSStarSetAffine"], _h(snes), 1 if affine else 0)


def get_affine(snes):
    """SNESSSStarGetAffine(): whether the next solve treats F as affine (set_linear_problem's F is, others are not)"""
    v = _Enum()
    _call(_C["SNESSSStarGetAffine"], _h(snes), ctypes.byref(v))
    return bool(v.value)


def get_nonlinear_counts(snes):
    """SNESSSStarGetNonlinearCounts(): (Jacobian evaluations, contact updates) of the last solve"""
    a, b = _Int(), _Int()
    _call(_C["SNESSSStarGetNonlinearCounts"], _h(snes), ctypes.byref(a), ctypes.byref(b))
    return a.value, b.value


def set_reduction_type(snes, kind):
    """SNESSSStarSetReductionType(): 'direct', 'mumps', 'explicit', 'none' or 'auto' (or their codes in REDUCTION_TYPES)"""
    _call(_C["SNESSSStarSetReductionType"], _h(snes), REDUCTION_TYPES[_choice(kind, REDUCTION_TYPES, "reduction")].encode())


def get_reduction_type(snes):
    v = ctypes.c_char_p()
    _call(_C["SNESSSStarGetReductionType"], _h(snes), ctypes.byref(v))
    return v.value.decode()


def set_memory_limit(snes, gigabytes):
    """SNESSSStarSetMemoryLimit(): GB per rank the reduction may plan for (0: MemAvailable)"""
    _call(_C["SNESSSStarSetMemoryLimit"], _h(snes), float(gigabytes))


def set_friction_law(snes, law):
    """SNESSSStarSetFrictionLaw(): a law of FRICTION_LAWS ('none', 'tresca', 'coulomb', 'orthotropic', or its code) for
    the nodes without a law of their own"""
    _call(_C["SNESSSStarSetFrictionLaw"], _h(snes), FRICTION_LAWS[_choice(law, FRICTION_LAWS, "friction law")].encode())


def get_friction_law(snes):
    v = ctypes.c_char_p()
    _call(_C["SNESSSStarGetFrictionLaw"], _h(snes), ctypes.byref(v))
    return v.value.decode()


def law_parameters(law):
    """The names of the parameters of a law of FRICTION_LAWS (name or code), from the library's table"""
    n, names = _Int(), ctypes.POINTER(ctypes.c_char_p)()
    _call(_C["SSStarLawGetInfo"], _choice(law, FRICTION_LAWS, "friction law"), None, None, ctypes.byref(n), ctypes.byref(names))
    return [names[i].decode() for i in range(n.value)]


def _parameter_size(name):
    size = _Int()
    _call(_C["SSStarLawGetParameterSize"], name.encode(), ctypes.byref(size))
    return size.value


def set_law_parameter(snes, name, value):
    """SNESSSStarSetLawParameter(): a parameter of the laws ('friction', 'slip_bound', 'friction_1', 'friction_2', or
    'friction_direction' as x, y, z in global axes) for every node without a value of its own"""
    values = np.atleast_1d(np.asarray(value, dtype=float))
    _call(_C["SNESSSStarSetLawParameter"], _h(snes), name.encode(), len(values), (_Real * len(values))(*values))


def set_friction(snes, friction):
    """SNESSSStarSetFriction(): the Coulomb coefficient of the nodes without one of their own"""
    _call(_C["SNESSSStarSetFriction"], _h(snes), float(friction))


def get_friction(snes):
    v = _Real()
    _call(_C["SNESSSStarGetFriction"], _h(snes), ctypes.byref(v))
    return v.value


def set_node_law_parameter(snes, name, values):
    """SNESSSStarSetNodeLawParameter(): one value of a law parameter per local contact node (Vec or array; three per
    node for a direction; None: back to set_law_parameter()'s)"""
    _call(_C["SNESSSStarSetNodeLawParameter"], _h(snes), name.encode(), _h(_node_vec(snes, values, _parameter_size(name), name)))


def set_node_friction_laws(snes, laws):
    """SNESSSStarSetNodeFrictionLaws(): one law per local contact node (names of FRICTION_LAWS or their codes; None:
    every node has set_friction_law()'s)"""
    if laws is None:
        _call(_C["SNESSSStarSetNodeFrictionLaws"], _h(snes), 0, None)
        return
    codes = (_Int * len(laws))(*[_choice(law, FRICTION_LAWS, "friction law") for law in laws])
    _call(_C["SNESSSStarSetNodeFrictionLaws"], _h(snes), len(laws), codes)


def _local_nodes(snes, what):
    n = get_contact_nodes(snes)[0]
    if n < 0:
        raise RuntimeError("%s: the contact nodes are not known before SNESSetUp()" % what)
    return n


def get_node_friction_laws(snes):
    """SNESSSStarGetNodeFrictionLaws() after the set-up or the solve: the law of each local contact node in the
    declared order, as codes into FRICTION_LAWS"""
    n = _local_nodes(snes, "get_node_friction_laws")
    laws = (_Int * max(n, 1))()
    _call(_C["SNESSSStarGetNodeFrictionLaws"], _h(snes), n, laws)
    return np.array(laws[:n], dtype=np.int32)


def get_node_law_parameter(snes, name):
    """SNESSSStarGetNodeLawParameter() after the set-up or the solve: the value of a law parameter at each local
    contact node (n x 3 for a direction), 0 where the node's law has no such parameter"""
    n, size = _local_nodes(snes, "get_node_law_parameter"), _parameter_size(name)
    values = (_Real * max(size * n, 1))()
    _call(_C["SNESSSStarGetNodeLawParameter"], _h(snes), name.encode(), n, values)
    a = np.array(values[:size * n], dtype=PETSc.RealType)
    return a.reshape(n, 3) if size == 3 else a


def set_scaling(snes, gamma):
    """SNESSSStarSetScaling(): gamma of the approximation step (0: 1/mean diag)"""
    _call(_C["SNESSSStarSetScaling"], _h(snes), float(gamma))


def get_scaling(snes):
    v = _Real()
    _call(_C["SNESSSStarGetScaling"], _h(snes), ctypes.byref(v))
    return v.value


def set_state_tolerance(snes, tau):
    """SNESSSStarSetStateTolerance(): the relative tolerance of the state classification"""
    _call(_C["SNESSSStarSetStateTolerance"], _h(snes), float(tau))


def set_method(snes, method):
    """SNESSSStarSetMethod(): 'newton' or 'fixedpoint'"""
    _call(_C["SNESSSStarSetMethod"], _h(snes), _choice(method, METHODS, "method"))


def get_method(snes):
    v = _Enum()
    _call(_C["SNESSSStarGetMethod"], _h(snes), ctypes.byref(v))
    return METHODS[v.value]


def set_lu_reuse(snes, fraction):
    """SNESSSStarSetLUReuse()"""
    _call(_C["SNESSSStarSetLUReuse"], _h(snes), float(fraction))


def set_globalization(snes, on=True, damping_min=None, stagnation_its=None):
    """SNESSSStarSetGlobalization(): on/off, the smallest damping factor, the iterations without progress before
    the solve stops (None: keep the default)"""
    _call(_C["SNESSSStarSetGlobalization"], _h(snes), 1 if on else 0, PETSc.DEFAULT if damping_min is None else float(damping_min),
          PETSc.DEFAULT if stagnation_its is None else int(stagnation_its))


def get_states(snes):
    """SNESSSStarGetStates() after the solve: (states, counts): the state code of each local contact node (declared
    order; names in STATE_NAMES) and the global count of each state"""
    n = get_contact_nodes(snes)[0]
    p, counts = ctypes.POINTER(_Enum)(), (_Int * _NUM_STATES)()
    _call(_C["SNESSSStarGetStates"], _h(snes), ctypes.byref(p), counts)
    states = np.array(np.ctypeslib.as_array(p, shape=(n,)) if n > 0 and p else [], dtype=np.int32)
    return states, np.array(counts[:], dtype=np.int64)


def get_reason(snes):
    """SNESSSStarGetReason(): why the last solve stopped, finer than snes.getConvergedReason() (a name of REASONS)"""
    v = _Enum()
    _call(_C["SNESSSStarGetReason"], _h(snes), ctypes.byref(v))
    return REASONS[v.value]


def get_tolerance(snes):
    """SNESSSStarGetTolerance(): the threshold the last stopping test compared ||z|| with"""
    v = _Real()
    _call(_C["SNESSSStarGetTolerance"], _h(snes), ctypes.byref(v))
    return v.value


def get_remedy_counts(snes):
    """SNESSSStarGetRemedyCounts(): {remedy name: count} of the last solve"""
    counts = (_Int * _NUM_REMEDIES)()
    _call(_C["SNESSSStarGetRemedyCounts"], _h(snes), counts)
    return dict(zip(REMEDIES, counts[:]))


def get_newton_step_counts(snes):
    """SNESSSStarGetNewtonStepCounts(): (LU factorizations, steps on an older LU, Krylov iterations)"""
    a, b, c = _Int(), _Int(), _Int()
    _call(_C["SNESSSStarGetNewtonStepCounts"], _h(snes), ctypes.byref(a), ctypes.byref(b), ctypes.byref(c))
    return a.value, b.value, c.value


def get_condition_estimate(snes):
    """SNESSSStarGetConditionEstimate(): 1/cond of the last LU-factored Newton matrix, or -1"""
    v = _Real()
    _call(_C["SNESSSStarGetConditionEstimate"], _h(snes), ctypes.byref(v))
    return v.value


def release_work(snes):
    """SNESSSStarReleaseWork(): frees the Newton steps' preconditioner (multigrid or factorization) and work vectors
    after the last solve, before writing or other post-processing; the solution's data stay, a later solve builds them
    again"""
    _call(_C["SNESSSStarReleaseWork"], _h(snes))


def get_contact_forces(snes):
    """The contact force on the body at each local contact node after the solve, n x 3 in global axes: the entries
    of snes.getFunction() (K u - b; P u - f in the reduced use) at the declared dofs"""
    r = snes.getFunction()[0]
    n, dofs = get_contact_nodes(snes)[:2]
    a = r.getArray(readonly=True)
    if dofs is None:
        return np.array(a, dtype=PETSc.RealType).reshape(-1, 3)
    start = r.getOwnershipRange()[0]
    return np.array(a[dofs - start], dtype=PETSc.RealType).reshape(n, 3)


def write_node_friction(snes, viewer, group="/contact"):
    """SSStarWriteNodeFriction(): the law of each contact node (group/friction_law, codes into FRICTION_LAWS, with their
    names as an attribute) and one dataset per parameter of the laws in use (group/friction, ...), as the scenes' files
    have them, into an open petsc4py HDF5 viewer"""
    _call(_C["SSStarWriteNodeFriction"], _h(snes), _h(viewer), group.encode())


from .scene import Scene, Step  # noqa: E402  (the scene library: meshes, groups, load paths, output)
