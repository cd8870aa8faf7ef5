/* metis_random.h: METIS orderings side by side (src/linalg/metis_random.c).
 *
 * METIS draws its random numbers from a sequence per thread, so that an
 * ordering does not depend on what runs beside it.  Every METIS call of the
 * C layer sits between c2d_metis_begin and c2d_metis_end (C2D_METIS_CALL,
 * include/metis_guard.h). */
#ifndef CONTACT2D_METIS_RANDOM_H
#define CONTACT2D_METIS_RANDOM_H

/* 1 when the per-thread sequences are in use, 0 when this METIS does not
 * call them (then METIS calls run one at a time). */
int c2d_metis_per_thread(void);
void c2d_metis_begin(void);
void c2d_metis_end(void);
#endif /* CONTACT2D_METIS_RANDOM_H */
