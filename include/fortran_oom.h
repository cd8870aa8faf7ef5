/* fortran_oom.h: the phase an out-of-memory diagnosis names
 * (src/sys/fortran_oom.c; Fortran: src/sys/run_phase.f90). */
#ifndef CONTACT2D_FORTRAN_OOM_H
#define CONTACT2D_FORTRAN_OOM_H
#include <stddef.h>

/* The run enters a step: phase[0..length-1] (not NUL-terminated; at most 95
 * characters kept), e.g. "factorizing K", is what a failed allocation that
 * the code does not check is said to have run out of memory while doing:
 * `contact2d: error: out of memory while factorizing K (...)`. */
void c2d_set_phase(const char *phase, size_t length);
#endif /* CONTACT2D_FORTRAN_OOM_H */
