# contact2d — top-level Makefile.  See README for the targets.
include make.inc

BUILD   := build/$(MODE)
BIN     := bin
# The program's name is fixed here, before any rule names it: make expands the
# prerequisites of a rule when it reads it, so `all` and `test` must see the
# MODE's program, never the release one.
ifeq ($(MODE),release)
PROGRAM := $(BIN)/contact2d
else
PROGRAM := $(BIN)/contact2d-$(MODE)
endif

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

.PHONY: all deps demo test unit study bench clean distclean help
all: deps $(PROGRAM)

# Debian packages, installed when missing (needs root on a fresh machine).
deps:
	@scripts/install-deps

$(PROGRAM): $(BUILD)/contact2d.o $(LIBOBJ) | $(BIN)
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)

# One pair of rules per folder: src/LAYER/NAME.f90 or .c -> BUILD/NAME.o.
define layer_rules
$$(BUILD)/%.o: src/$(1)/%.f90 | $$(BUILD)
	$$(FC) $$(FFLAGS) -J$$(BUILD) -c $$< -o $$@

$$(BUILD)/%.o: src/$(1)/%.c include/*.h | $$(BUILD)
	$$(CC) $$(CFLAGS) -c $$< -o $$@
endef
$(foreach l,$(LAYERS),$(eval $(call layer_rules,$(l))))

$(BUILD)/contact2d.o: src/contact2d.f90 | $(BUILD)
	$(FC) $(FFLAGS) -J$(BUILD) -c $< -o $@

$(BUILD)/testing.o: tests/unit/testing.f90 | $(BUILD)
	$(FC) $(FFLAGS) -J$(BUILD) -c $< -o $@

$(BUILD)/tests/%: tests/unit/%.f90 $(LIBOBJ) $(BUILD)/testing.o | $(BUILD)/tests
	$(FC) $(FFLAGS) -I$(BUILD) -o $@ $< $(BUILD)/testing.o $(LIBOBJ) $(LIBS)

$(BUILD) $(BUILD)/tests $(BIN):
	mkdir -p $@

# Module dependencies, generated from the `use` statements (module = file name).
$(BUILD)/deps.mk: $(FSRC) scripts/f90deps | $(BUILD)
	scripts/f90deps $(BUILD) $(FSRC) > $@
-include $(BUILD)/deps.mk

unit: deps $(UNITBIN)

demo: all
	$(PROGRAM) -o out/demo input/hertz.deck

test: all unit
	$(TESTENV) tests/run-tests $(PROGRAM) $(BUILD)/tests

study: all
	studies/run-all

bench: all
	bench/run-all

clean:
	rm -rf build $(BIN)

distclean: clean
	rm -rf out

help:
	@echo "make [MODE=release|debug|sanitize] [all|demo|test|unit|study|bench|clean]"
