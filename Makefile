# contact2d — top-level Makefile.  See README for the targets.
include make.inc

# One build folder and one program per MODE and compiler: modules and objects
# of two compilers (or two versions of one) never mix.  The default compiler,
# gfortran, keeps the short names (build/release, bin/contact2d,
# bin/contact2d-debug); another FC adds its name (FC=gfortran-11 ->
# build/release-gfortran-11, bin/contact2d-gfortran-11; FC=.../flang-new ->
# build/debug-flang-new, bin/contact2d-debug-flang-new).
FCNAME  := $(notdir $(FC))
ifeq ($(FCNAME),gfortran)
TAG     :=
else
TAG     := -$(FCNAME)
endif
BUILD   := build/$(MODE)$(TAG)
BIN     := bin
# The program's name is fixed here, before any rule names it: make expands the
# prerequisites of a rule when it reads it, so `all` and `test` must see the
# MODE's program, never the release one.
ifeq ($(MODE),release)
PROGRAM := $(BIN)/contact2d$(TAG)
else
PROGRAM := $(BIN)/contact2d-$(MODE)$(TAG)
endif

MESHER  := $(BIN)/contact2d-mesher
MESHER_CFLAGS := -O2 -std=c11 -Wall -Wextra

# The tests and studies that build a Fortran program of their own use this
# compiler (tests/robust/unchecked_alloc, studies/run-all).
export FC FC_FAMILY

# The layer folders of src/, bottom first (src/layers); the objects of all of
# them go to one folder per MODE, since a module's name is its file's.
LAYERS  := $(shell sed -n 's/^\([a-z][a-z0-9_]*\) .*/\1/p' src/layers)
FSRC    := $(foreach l,$(LAYERS),$(sort $(wildcard src/$(l)/*.f90))) src/contact2d.f90
CSRC    := $(foreach l,$(LAYERS),$(sort $(wildcard src/$(l)/*.c)))
FOBJ    := $(patsubst %.f90,$(BUILD)/%.o,$(notdir $(FSRC)))
COBJ    := $(patsubst %.c,$(BUILD)/%.o,$(notdir $(CSRC)))
LIBOBJ  := $(filter-out $(BUILD)/contact2d.o,$(FOBJ)) $(COBJ)
UNITSRC := $(sort $(wildcard tests/unit/test_*.f90))
UNITBIN := $(patsubst tests/unit/%.f90,$(BUILD)/tests/%,$(UNITSRC))

.PHONY: all deps demo test check unit unit-build study bench clean distclean help names
# Building installs nothing: `make deps` (and `make demo`, the first command
# of the README) install what is missing.
all: $(PROGRAM) $(MESHER)

# Debian packages, installed when missing (needs root on a fresh machine).
deps:
	@scripts/install-deps

$(PROGRAM): $(BUILD)/contact2d.o $(LIBOBJ) | $(BIN)
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# gmsh's batch program kept running between a run's meshes (src/mesh/gmsh_runner.f90
# says why); one for every MODE and compiler, which find it beside them.
$(MESHER): src/mesher/gmsh_mesher.c include/cpu_seconds.h | $(BIN)
	$(CC) $(MESHER_CFLAGS) -Iinclude -o $@ $< -lgmsh

# One pair of rules per folder: src/LAYER/NAME.f90 or .c -> BUILD/NAME.o.
define layer_rules
$$(BUILD)/%.o: src/$(1)/%.f90 | $$(BUILD)
	$$(FC) $$(FFLAGS) $$(FMODDIR) $$(BUILD) -c $$< -o $$@

$$(BUILD)/%.o: src/$(1)/%.c include/*.h | $$(BUILD)
	$$(CC) $$(CFLAGS) -c $$< -o $$@
endef
$(foreach l,$(LAYERS),$(eval $(call layer_rules,$(l))))

$(BUILD)/contact2d.o: src/contact2d.f90 | $(BUILD)
	$(FC) $(FFLAGS) $(FMODDIR) $(BUILD) -c $< -o $@

$(BUILD)/testing.o: tests/unit/testing.f90 | $(BUILD)
	$(FC) $(FFLAGS) $(FMODDIR) $(BUILD) -c $< -o $@

$(BUILD)/tests/%: tests/unit/%.f90 $(LIBOBJ) $(BUILD)/testing.o | $(BUILD)/tests
	$(FC) $(FFLAGS) -I$(BUILD) -o $@ $< $(BUILD)/testing.o $(LIBOBJ) $(LIBS)

$(BUILD) $(BUILD)/tests $(BIN):
	mkdir -p $@

# Module dependencies, generated from the `use` statements (module = file name).
$(BUILD)/deps.mk: $(FSRC) scripts/f90deps | $(BUILD)
	scripts/f90deps $(BUILD) $(FSRC) > $@
-include $(BUILD)/deps.mk

# `make unit` builds the unit tests and runs them; `make test` runs them and
# every other test.  Both end with `N passed, N failed`.
unit-build: $(UNITBIN)

unit: unit-build
	$(TESTENV) tests/run-tests --unit $(PROGRAM) $(BUILD)/tests

demo: deps
	$(MAKE) all
	$(PROGRAM) -o out/demo input/hertz.deck

# `make test` first installs what is missing (make deps: a look at dpkg when
# all is there), so that it works on a fresh machine as the README says;
# `make check` builds and runs every test and installs nothing.
test: deps
	@$(MAKE) --no-print-directory check

check: all unit-build
	$(TESTENV) tests/run-tests $(PROGRAM) $(BUILD)/tests

study: all
	CONTACT2D=$(CURDIR)/$(PROGRAM) C2D_BUILD=$(BUILD) studies/run-all

bench: all
	bench/run-all

clean:
	rm -rf build $(BIN)

distclean: clean
	rm -rf out

# The program and the unit tests' folder of this MODE and FC (scripts/check-modes).
names:
	@echo $(PROGRAM) $(BUILD)/tests

help:
	@echo "make [MODE=release|debug|sanitize] [FC=gfortran|gfortran-NN|flang-new] [ARCH=cpu] [all|deps|demo|test|check|unit|study|bench|clean]"
