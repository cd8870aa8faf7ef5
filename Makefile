# contact2d — top-level Makefile.  See README for the targets.
include make.inc

BUILD   := build/$(MODE)
BIN     := bin
PROGRAM := $(BIN)/contact2d

FSRC    := $(sort $(wildcard src/*.f90))
CSRC    := $(sort $(wildcard src/*.c))
FOBJ    := $(patsubst src/%.f90,$(BUILD)/%.o,$(FSRC))
COBJ    := $(patsubst src/%.c,$(BUILD)/%.o,$(CSRC))
LIBOBJ  := $(filter-out $(BUILD)/contact2d.o,$(FOBJ)) $(COBJ)
UNITSRC := $(sort $(wildcard tests/unit/test_*.f90))
UNITBIN := $(patsubst tests/unit/%.f90,$(BUILD)/tests/%,$(UNITSRC))

.PHONY: all deps demo test unit study bench clean distclean help
all: deps $(PROGRAM)

# Debian packages, installed when missing (needs root on a fresh machine).
deps:
	@scripts/install-deps

ifeq ($(MODE),release)
$(PROGRAM): $(BUILD)/contact2d.o $(LIBOBJ) | $(BIN)
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)
else
PROGRAM := $(BIN)/contact2d-$(MODE)
all: $(PROGRAM)
$(PROGRAM): $(BUILD)/contact2d.o $(LIBOBJ) | $(BIN)
	$(FC) $(FFLAGS) -o $@ $^ $(LIBS)
endif

$(BUILD)/%.o: src/%.f90 | $(BUILD)
	$(FC) $(FFLAGS) -J$(BUILD) -c $< -o $@

$(BUILD)/%.o: src/%.c include/*.h | $(BUILD)
	$(CC) $(CFLAGS) -c $< -o $@

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
	tests/run-tests $(PROGRAM) $(BUILD)/tests

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
