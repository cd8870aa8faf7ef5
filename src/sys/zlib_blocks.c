/* zlib_blocks.c: zlib's compress2 block by block (see include/zlib_blocks.h).
 *
 * Why blocks: VTK's XML files store a compressed array as independent zlib
 * streams of a fixed uncompressed size (vtkZLibDataCompressor), so a reader
 * can inflate any block alone; independent blocks also compress side by
 * side on the run's threads.  Each block is compressed into a slot of its
 * own of compressBound(block) bytes, then the slots are packed in order. */
#include <string.h>

#include "zlib_blocks.h"

#ifdef C2D_HAVE_ZLIB
#include <zlib.h>

int c2d_zlib_available(void)
{
    return 1;
}

int64_t c2d_zlib_capacity(int64_t n, int64_t block)
{
    int64_t nblock = (n + block - 1) / block;
    return nblock * (int64_t) compressBound((uLong) block);
}

int c2d_zlib_blocks(const unsigned char *src, int64_t n, int64_t block, int level,
                    unsigned char *dst, int64_t *sizes, int64_t *total)
{
    int64_t nblock = (n + block - 1) / block, slot = (int64_t) compressBound((uLong) block), k;
    int failed = 0;
    *total = 0;
#pragma omp parallel for schedule(dynamic) reduction(| : failed) if (nblock > 4)
    for (k = 0; k < nblock; k++) {
        int64_t first = k * block, len = (n - first < block) ? n - first : block;
        uLongf out = (uLongf) slot;
        if (compress2(dst + k * slot, &out, src + first, (uLong) len, level) != Z_OK) failed = 1;
        sizes[k] = (int64_t) out;
    }
    if (failed) return -1;
    /* pack: block k moves down from k * slot to the sum of the sizes before it */
    for (k = 0; k < nblock; k++) {
        if (*total != k * slot) memmove(dst + *total, dst + k * slot, (size_t) sizes[k]);
        *total += sizes[k];
    }
    return 0;
}

#else /* no zlib: the callers write their data uncompressed */

int c2d_zlib_available(void)
{
    return 0;
}

int64_t c2d_zlib_capacity(int64_t n, int64_t block)
{
    (void) n;
    (void) block;
    return 0;
}

int c2d_zlib_blocks(const unsigned char *src, int64_t n, int64_t block, int level,
                    unsigned char *dst, int64_t *sizes, int64_t *total)
{
    (void) src; (void) n; (void) block; (void) level; (void) dst; (void) sizes;
    *total = 0;
    return -1;
}
#endif
