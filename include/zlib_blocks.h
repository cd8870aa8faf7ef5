/* zlib_blocks.h: zlib's compress2 over a buffer cut in blocks, each block
 * compressed on its own (src/sys/zlib_blocks.c): the layout of VTK's
 * vtkZLibDataCompressor, which the XML VTK files use.
 *
 * Built with zlib when its header is there at build time (make.inc defines
 * C2D_HAVE_ZLIB and links -lz); without it c2d_zlib_available() is 0 and
 * c2d_zlib_blocks fails, and the callers write their data uncompressed. */
#ifndef CONTACT2D_ZLIB_BLOCKS_H
#define CONTACT2D_ZLIB_BLOCKS_H

#include <stddef.h>
#include <stdint.h>

/* 1 when the program was built with zlib, else 0. */
int c2d_zlib_available(void);

/* The most bytes c2d_zlib_blocks can write for n bytes in blocks of block
 * bytes (block >= 1): what dst must hold. */
int64_t c2d_zlib_capacity(int64_t n, int64_t block);

/* Compress src[0, n) in ceil(n / block) blocks of block bytes (the last one
 * shorter), each by compress2 at level (0..9, -1 zlib's default) on its own,
 * side by side on the OpenMP threads.  On return dst[0, *total) holds the
 * compressed blocks one after the other and sizes[k] the size of block k.
 *   dst:   c2d_zlib_capacity(n, block) bytes
 *   sizes: ceil(n / block) entries
 * Returns 0, or -1 when zlib is missing or failed (out of memory). */
int c2d_zlib_blocks(const unsigned char *src, int64_t n, int64_t block, int level,
                    unsigned char *dst, int64_t *sizes, int64_t *total);
#endif /* CONTACT2D_ZLIB_BLOCKS_H */
