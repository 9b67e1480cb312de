# ssstar: `make` builds lib/libssstar.so and the examples, `make run` solves the prism,
# `make test` runs the test suite (`make test-full` with its slow tests), `make bench` the timing table, `make docs`
# regenerates docs/options.md and docs/manual.md. configure.py runs first if needed.

# builds on every core unless make -j N says otherwise
ifeq ($(filter -j%,$(MAKEFLAGS)),)
MAKEFLAGS += -j$(shell nproc)
endif

-include config/ssstar.mk
ifneq ($(PETSC_DIR),)
include $(PETSC_DIR)/lib/petsc/conf/variables
endif

LIBNAME  := ssstar
VERSION  := 0.3.0
PREFIX   ?= /usr/local
# where make install puts the Python module ssstar (Debian's python3 searches /usr/local/lib/python3/dist-packages)
PYTHON_DIR ?= $(PREFIX)/lib/python3/dist-packages
LIB      := lib/lib$(LIBNAME).so
LIB_SRC  := src/ssstarregister.c src/options.c $(wildcard src/sys/*.c) \
            $(wildcard src/snes/impls/ssstar/*.c src/snes/impls/ssstar/*/*.c) $(wildcard src/reduction/*.c) \
            $(wildcard src/geometry/*.c) $(wildcard src/scene/*.c src/scene/*/*.c src/scene/*/*/*.c) \
            $(wildcard src/history/*.c)
LIB_OBJ  := $(patsubst src/%.c,build/%.o,$(LIB_SRC))
EXAMPLES := examples/prism examples/generic examples/fclib examples/contact
TESTS    := tests/test_kernels tests/test_newton tests/test_plain_contact tests/test_nonlinear tests/test_scenes tests/test_reduction tests/test_operator \
            tests/test_geometry tests/test_search tests/test_collective tests/test_history tests/test_offsets tests/test_stress tests/test_hyperelastic
BENCHES  := bench/yardstick bench/newton_step bench/dense_lu bench/refine_petsc
# MUMPS_LIB, MUMPS_INCLUDE: PETSc's own (petscvariables), so the direct reduction calls the MUMPS PETSc links
CFLAGS_SSSTAR := $(PCC_FLAGS) -Wall -Wextra -Wno-unused-parameter -Iinclude $(PETSC_CC_INCLUDES) $(MUMPS_INCLUDE) \
                 -DSSSTAR_MESH_DIR=\"$(abspath meshes)\" -DSSSTAR_GMSH_SONAME=\"$(GMSH_SONAME)\"
LINK_SSSTAR   := -Llib -l$(LIBNAME) -Wl,-rpath,$(abspath lib) $(PETSC_LIB)
# mpiexec as root (CI, containers) needs these; harmless otherwise
export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OPENBLAS_NUM_THREADS=1
MPIEXEC_SSSTAR := mpiexec --oversubscribe
# quiet builds: "CC file" lines; make V=1 prints the commands
ifeq ($(V),1)
  Q :=
  SAY = @true
else
  Q := @
  SAY = @echo
endif

.PHONY: all run test test-full docs bench bench-large bench-getfem-ball bench-loadpath bench-robust bench-search bench-scenes scenes accuracy accuracy-quick install print-cflags clean distclean
all: $(LIB) $(EXAMPLES) $(TESTS) $(BENCHES)

config/ssstar.mk: configure.py
	python3 configure.py

build/%.o: src/%.c $(wildcard include/*.h src/*/*.h src/*/*/*.h src/*/*/*/*.h src/snes/impls/ssstar/*.h src/snes/impls/ssstar/*/*.h) config/ssstar.mk
	@mkdir -p $(dir $@)
	$(SAY) "  CC      $<"
	$(Q)$(PCC) $(CFLAGS_SSSTAR) -c $< -o $@

$(LIB): $(LIB_OBJ)
	@mkdir -p lib
	$(SAY) "  LD      $@"
	$(Q)$(PCC) -shared -o $@ $^ $(PETSC_LIB) -ldl $(MUMPS_LIB) $(METIS_LIB)

examples/%: examples/%.c $(LIB)
	$(SAY) "  CCLD    $@"
	$(Q)$(PCC) $(CFLAGS_SSSTAR) $< -o $@ $(LINK_SSSTAR)

tests/test_kernels tests/test_newton tests/test_scenes tests/test_reduction tests/test_operator tests/test_geometry tests/test_search tests/test_collective tests/test_history tests/test_offsets tests/test_stress tests/test_hyperelastic: tests/%: tests/%.c $(LIB)
	$(SAY) "  CCLD    $@"
	$(Q)$(PCC) $(CFLAGS_SSSTAR) $< -o $@ $(LINK_SSSTAR)
tests/test_geometry tests/test_search: tests/brute_region.h

bench/%: bench/%.c $(LIB)
	$(SAY) "  CCLD    $@"
	$(Q)$(PCC) $(CFLAGS_SSSTAR) $< -o $@ $(LINK_SSSTAR)

bench/newton_step bench/dense_lu: bench/%: bench/%.c $(LIB)
	$(SAY) "  CCLD    $@"
	$(Q)$(PCC) $(CFLAGS_SSSTAR) $< -o $@ $(LINK_SSSTAR)

# deliberately not linked with libssstar: they get the type through -dll_append
tests/test_plain_contact tests/test_nonlinear: tests/%: tests/%.c
	$(SAY) "  CCLD    $@"
	$(Q)$(PCC) $(PCC_FLAGS) -Wall $(PETSC_CC_INCLUDES) $< -o $@ $(PETSC_LIB)

# make install PREFIX=/some/where: the library, the headers and lib/pkgconfig/ssstar.pc (which carries PETSc's flags),
# so that a program builds with  mpicc prog.c $$(pkg-config --cflags --libs ssstar); and the Python module ssstar in
# $(PYTHON_DIR), told where the library is (_config.py)
install: $(LIB)
	install -d $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PYTHON_DIR)/ssstar
	install -m 644 include/*.h $(DESTDIR)$(PREFIX)/include/
	install -m 755 $(LIB) $(DESTDIR)$(PREFIX)/lib/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' -e 's|@PETSC_CFLAGS@|$(PETSC_CC_INCLUDES)|' \
	    -e 's|@PETSC_LIBS@|$(PETSC_LIB)|' ssstar.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/ssstar.pc
	install -m 644 python/ssstar/__init__.py python/ssstar/scene.py $(DESTDIR)$(PYTHON_DIR)/ssstar/
	printf 'LIBRARY = "%s"\nVERSION = "%s"\n' '$(PREFIX)/lib/lib$(LIBNAME).so' '$(VERSION)' > $(DESTDIR)$(PYTHON_DIR)/ssstar/_config.py
	@echo "The Python module ssstar is in $(PYTHON_DIR): put it on PYTHONPATH unless python3 searches it already"

# the compiler and flags the sources are built with (tests/suite_package.py compiles the manual's synopses with them)
print-cflags:
	@echo $(PCC) $(CFLAGS_SSSTAR)

run: all
	$(MPIEXEC_SSSTAR) -n 2 examples/prism -level 6 -snes_converged_reason -o prism_L6.h5

# the default suite, several tests at a time (tests/run.py -j, default the number of cores); test-full adds the slow ones
test: all
	$(PYTHON) tests/run.py

test-full: all
	$(PYTHON) tests/run.py --full

# the generated documentation: docs/options.md from the examples' -help, docs/manual.md from the sources (make test
# fails when either is stale)
docs: all
	$(PYTHON) docs/mkoptions.py
	$(PYTHON) docs/mkmanual.py

bench: all
	$(PYTHON) bench/table2.py
	$(PYTHON) bench/newton.py
	$(PYTHON) bench/schur.py

# the scale table (docs/guide/scale.md): levels 16, 24, 32, 40, 48 on the whole body on 2 ranks, medians of 3, each
# beside the AMG yardstick of the same run, level 48 also as level 24 refined once in parallel, level 10 against GetFEM
# (bench/output/scale.md): about an hour and a half on a quiet machine
bench-large: all
	$(PYTHON) bench/table2.py --large

# the neo-Hookean half ball pressed to 0.3 R against GetFEM 5.4 on the same mesh, frictionless and phi = 0.3, medians of
# 3 beside the AMG yardstick (bench/output/getfem_ball.csv, _times.csv, .png; docs/guide/large-deformation.md): about
# 10 minutes on a loaded 2-core machine; Debian's python3-getfem
bench-getfem-ball: all
	/usr/bin/python3 bench/getfem_ball.py --level 1 --repeat 3

# the contact search on large inputs (a ball of 59 356 triangles on a 250 000-node block; a 310 000-dof pair): its
# share of the whole run, 2 ranks, the whole body (bench/output/search.csv)
bench-search: all
	$(PYTHON) bench/search.py

# the work-precision study: docs/accuracy.md, docs/accuracy/*.csv, *.json and *.png (both paths on 1 rank to level 10 and
# on 2 ranks at levels 12 and 16 against level 24; Hertz, its von Mises maximum, Cattaneo-Mindlin, the slider, the load
# path; about an hour on a loaded 2-core machine); accuracy-quick: the small version into bench/output/accuracy_quick
# (under a minute on a quiet machine)
accuracy: all
	$(PYTHON) bench/accuracy.py

accuracy-quick: all
	$(PYTHON) bench/accuracy.py --quick

# the robustness families at the default settings, both paths, 1-4 ranks: converged, the law on every step, within 1e-6
# of the exact discrete solution (bench/output/robust.csv)
bench-robust: all
	$(PYTHON) bench/robust.py

# what an effect costs: the prism scene with effects switched on and off (bench/output/scenes.csv)
bench-scenes: all
	$(PYTHON) bench/scenes.py

# the Mindlin-Deresiewicz loop of a load path against its closed forms, levels 1 and 2 (bench/output/loadpath.csv)
bench-loadpath: all
	$(PYTHON) bench/loadpath.py --levels 1,2

# every scene of scenes/ at its level: scenes/output/NAME.h5, .xmf and .png
SCENES := $(basename $(notdir $(wildcard scenes/*.opts)))
scenes: all
	@mkdir -p scenes/output
	for s in $(SCENES); do examples/contact -options_file scenes/$$s.opts -o scenes/output/$$s.h5 && $(PYTHON) examples/plot_contact.py scenes/output/$$s.h5 || exit 1; done

clean:
	rm -rf build lib $(EXAMPLES) $(TESTS) $(BENCHES) tests/output scenes/output meshes/*.msh *.h5 *.xmf

distclean: clean
	rm -f config/ssstar.mk
