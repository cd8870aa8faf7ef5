/* memory_limit.h: how much more memory this process can have
 * (src/sys/memory_limit.c). */
#ifndef CONTACT2D_MEMORY_LIMIT_H
#define CONTACT2D_MEMORY_LIMIT_H
#include <stdint.h>

/* Bytes this process can still allocate: the address space left under
 * RLIMIT_AS and the machine's MemAvailable + SwapFree, the smaller; -1 when
 * neither is known. */
int64_t c2d_memory_available(void);

/* The address space left under RLIMIT_AS, -1 without a limit. */
int64_t c2d_address_space_left(void);
#endif /* CONTACT2D_MEMORY_LIMIT_H */
