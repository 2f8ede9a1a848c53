"""Resampling: a supersampled frame averaged down to the picture's size."""

import numpy as np

from biceps.engine.jit import ngjit


@ngjit
def downsample(source, factor, target, width, columns):
    """Average each ``factor`` x ``factor`` block of pixels of source: (3 factor h factor w,)
    uint8 into one pixel of target: (3 h w,) uint8, rounding to nearest; ``width`` is w,
    ``factor`` at most 16. columns: (3 factor w,) int32, scratch (passed in, as the
    rasterizers' is).

    Each output row first sums its ``factor`` source rows column by column (a loop that
    vectorises), then adds up each block's columns. The division by the block's size is a
    multiplication by ``ceil(2^24 / size)`` and a shift, exact for sums below 2^16.
    """
    fine = 3 * width * factor  # bytes in a source row
    count = factor * factor
    reciprocal = ((1 << 24) + count - 1) // count
    for y in range(target.shape[0] // (3 * width)):
        for i in range(fine):
            columns[i] = 0
        for row in range(y * factor, (y + 1) * factor):
            start = np.uint64(row * fine)
            for i in range(fine):
                columns[i] += source[start + np.uint64(i)]
        for x in range(width):
            for c in range(3):
                total = count // 2  # rounds the mean to nearest
                for k in range(factor):
                    total += columns[3 * (factor * x + k) + c]
                target[np.uint64(3 * (y * width + x) + c)] = (total * reciprocal) >> 24
