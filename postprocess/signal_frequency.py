"""Dominant frequency of a vibration signal along a run, from zero crossings:
an estimate independent of the eigen-analysis (it uses only the simulated
motion), for comparing with the tracked first frequency."""
import numpy as np


def moving_average(t, y, window):
    """Centred moving average of y over `window` seconds (edge values repeated at the ends):
    the slow part of a vibrating signal. t must be (about) evenly spaced."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    dt = np.median(np.diff(t))
    half = max(1, int(round(0.5 * window / dt)))
    kernel = np.ones(2 * half + 1) / (2 * half + 1)
    padded = np.pad(y, half, mode="edge")
    return np.convolve(padded, kernel, mode="valid")


def zero_crossing_frequency(t, y, trend_window):
    """Instantaneous frequency from successive upward zero crossings.

    The slow part of the signal (static deflection growing with the
    extension) is removed by a centred moving average over `trend_window`
    seconds; each pair of successive upward crossings of the remainder gives
    one period, reported at its midpoint. Returns (times, frequencies in Hz).
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    r = y - moving_average(t, y, trend_window)
    # Upward crossings, located by linear interpolation.
    idx = np.nonzero((r[:-1] < 0) & (r[1:] >= 0))[0]
    tc = t[idx] - r[idx] * (t[idx + 1] - t[idx]) / (r[idx + 1] - r[idx])
    if len(tc) < 2:
        return np.array([]), np.array([])
    return 0.5 * (tc[1:] + tc[:-1]), 1.0 / np.diff(tc)
