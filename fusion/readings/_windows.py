"""Sliding-window sums along the first axis: prefix-sum differences, checked a posteriori (private).

``fusion.readings.weighting.running_average`` (``memory="window"``) takes a window's sum as the difference of two
cumulative sums. The round-off of those cumulative sums is shared by both up to the window's first sample and
cancels; what remains is the round-off of the additions inside the window, each at most ``eps`` times the prefix
sum it produced. A large value that has left the window still sits in those prefix sums, and its round-off in
every later window (fuzz 46b C1: ``[1e16] + [3.0] * 50``, window 10, gave 4.0; C2: a spike of 1e7 in
``difference_variances`` gave a window variance of 0.0, not 1.05e-4). Each window's bound is compared with the
window's own scale (its largest ``|value|``); only the windows whose bound exceeds :data:`WINDOW_RTOL` of it are
summed again from their own samples (a block's prefix plus the previous block's suffix, as the wavelet chapter's
``_window_mean``), so accurate windows keep the prefix-sum difference to the bit.
"""

from __future__ import annotations

import numpy as np

from fusion._validation import FloatArray

__all__: list[str] = []

#: Largest a-posteriori round-off bound of a prefix-sum difference accepted, relative to the window's largest
#: ``|value|`` (a lower bound of the scale its direct sum's round-off refers to); a window whose bound exceeds it is
#: summed directly. The book's window calls (notebook 02's 16 calls, 1000 x 100 x 12 stacks, 100-sample windows)
#: reach at most 2.4e-10 (measured by fix53a), 42x inside: none is recomputed. At 1e-10, 18,744 of the book's
#: windows would be, their bits changed by up to 6.6e-13.
WINDOW_RTOL = 1e-8


def _trailing_max(a: FloatArray, window: int) -> FloatArray:
    """The largest of the last ``window`` entries (fewer at the start) along axis 0 of a non-negative ``a``."""
    from scipy.ndimage import maximum_filter1d

    return maximum_filter1d(a, size=window, axis=0, mode="constant", cval=0.0, origin=(window - 1) // 2)


def block_sums(z: FloatArray, window: int) -> FloatArray:
    """The sum of the last ``window`` samples of ``z`` along its LAST axis (shorter at the start), each summed from
    the window's own samples: a block's prefix plus the previous block's suffix (``window`` at most the length)."""
    I = z.shape[-1]
    nb = -(-I // window)
    pad = np.zeros((*z.shape[:-1], nb * window - I))
    blocks = np.concatenate([z, pad], axis=-1).reshape(*z.shape[:-1], nb, window)
    pre = np.cumsum(blocks, axis=-1)                                        # sum of block j up to offset r
    suf = np.cumsum(blocks[..., ::-1], axis=-1)[..., ::-1]                  # sum of block j from offset r on
    tail = np.zeros_like(pre)
    tail[..., 1:, :-1] = suf[..., :-1, 1:]                                   # block j-1 from offset r+1 on
    return (pre + tail).reshape(*z.shape[:-1], nb * window)[..., :I]


def window_sums(A: FloatArray, window: int) -> FloatArray:
    """The sums of the last ``window`` samples along axis 0 (fewer at the start): the prefix-sum difference where
    its a-posteriori bound is within :data:`WINDOW_RTOL` of the window's scale, else the window's direct sum."""
    c = np.cumsum(A, axis=0)
    K = A.shape[0]
    if K <= window:
        return c
    prefix = np.abs(c)
    c[window:] = c[window:] - c[:-window]
    # round-off of the window's own additions (the earlier ones are in both prefix sums and cancel): at most
    # eps x (its terms) x the largest |prefix sum| among them, plus the subtraction's eps x |difference|
    terms = np.minimum(np.arange(1, K + 1), window).astype(float).reshape((K,) + (1,) * (A.ndim - 1))
    eps = np.finfo(float).eps
    bound = eps * (terms * _trailing_max(prefix, window) + np.abs(c))
    bad = bound > WINDOW_RTOL * _trailing_max(np.abs(A), window)
    if bad.any():
        direct = np.moveaxis(block_sums(np.moveaxis(A, 0, -1), window), -1, 0)
        c = np.where(bad, direct, c)
    return c
