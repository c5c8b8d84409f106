"""Readers of the Quiroz (2022) UTFSM data set: an MR damper at five coil currents (docs/case_studies/quiroz.md).

The data set is not part of the repository: :func:`quiroz_folder` finds it in ``../shared/data/quiroz2022_utfsm_mr``
beside the repository.  Six preprocessed sinusoids per current (:data:`QUIROZ_TESTS`, :func:`read_quiroz_file`) and
an earthquake-type validation record (:func:`read_quiroz_mat`); the study that identifies models on them is
:mod:`erdesign.case_studies.quiroz`.
"""

from __future__ import annotations

import numpy as np

from ..errors import ErdesignError
from .measurement import Measurement

__all__ = [
    "QUIROZ_CURRENTS",
    "QUIROZ_VALIDATION_CURRENTS",
    "QUIROZ_TESTS",
    "QUIROZ_FILE_NAME",
    "quiroz_folder",
    "read_quiroz_sinusoid",
    "read_quiroz_file",
    "read_quiroz_validation",
    "read_quiroz_mat",
    "QUIROZ_RAW_TESTS",
    "read_quiroz_raw",
    "QUIROZ_VALIDATION_WINDOW",
    "causal_moving_average",
    "undo_causal_moving_average",
    "read_quiroz_validation_unsmoothed",
]

#: Coil currents of the Quiroz (2022) UTFSM sinusoids [A] and of the columns 2-6 of its validation record.
QUIROZ_CURRENTS = (0.0, 0.25, 0.5, 0.75, 1.0)
QUIROZ_VALIDATION_CURRENTS = (0.2, 0.4, 0.6, 0.8, 1.0)
#: The causal moving average the source applied to every column of its validation record, [samples at 1 kHz]
#: (shared/data/README.md; the spectra of displacement and force both have its zeros at multiples of 3.33 Hz).
QUIROZ_VALIDATION_WINDOW = 300
#: The six sinusoids: amplitude [mm] and frequency [Hz] as in the file names ('x' is the decimal point).
QUIROZ_TESTS = (
    ("10mm1Hz", 1.0),
    ("25mm0x1Hz", 0.1),
    ("25mm0x25Hz", 0.25),
    ("25mm0x5Hz", 0.5),
    ("2mm5Hz", 5.0),
    ("5mm3Hz", 3.0),
)


#: The six raw DAQ files (raw/ME<test>.txt): test name, frequency [Hz], and whether CHANNEL0 is the force (the
#: channels are swapped in the tests stored every 5 ms, shared/data/README.md).
QUIROZ_RAW_TESTS = (
    ("10mm2Hz", 2.0, False),
    ("25mm0x25Hz", 0.25, True),
    ("25mm0x5Hz", 0.5, True),
    ("2mm5Hz", 5.0, True),
    ("5mm3Hz", 3.0, False),
    ("5mm4Hz", 4.0, False),
)


def quiroz_folder(repository_root=None):
    """The folder ``../shared/data/quiroz2022_utfsm_mr`` next to the repository (None when it is absent)."""
    from pathlib import Path

    root = Path(repository_root) if repository_root else Path(__file__).resolve().parents[2]
    folder = root.parent / "shared" / "data" / "quiroz2022_utfsm_mr"
    return folder if folder.is_dir() else None


def _current_label(i: float) -> str:
    return f"{i:g}".replace(".", "x") + "A"


#: The stem of a preprocessed file's name, ``<amp>mm<freq>Hz<current>A`` ('x' for the decimal point).
QUIROZ_FILE_NAME = r"(?P<amp>\d+(?:x\d+)?)mm(?P<freq>\d+(?:x\d+)?)Hz(?P<cur>\d+(?:x\d+)?)A"


def read_quiroz_sinusoid(
    folder, test: str, current: float, *, cycles: float = 2.5, samples_per_cycle: int = 200
) -> Measurement:
    """One preprocessed sinusoid of the Quiroz (2022) MR damper by test name and current
    (:func:`read_quiroz_file` on ``folder/preprocessed/<test><current>A.txt``)."""
    from pathlib import Path

    return read_quiroz_file(
        Path(folder) / "preprocessed" / f"{test}{_current_label(current)}.txt",
        cycles=cycles,
        samples_per_cycle=samples_per_cycle,
    )


def read_quiroz_file(path, *, cycles: float = 2.5, samples_per_cycle: int = 200) -> Measurement:
    r"""One preprocessed sinusoid of the Quiroz (2022) MR damper, cropped and resampled for identification.

    The file ``<amp>mm<freq>Hz<current>A.txt`` ('x' for the decimal point) holds t [s], x [mm], v [mm/s], F [N]
    (see shared/data/README.md); frequency and coil current are read from its name.  The last ``cycles`` periods
    are kept (the start of each test is a transient of the press) and resampled by linear interpolation to
    ``samples_per_cycle`` per period (the 5 Hz test is stored at only 40 per period; the models take the motion as
    linear between samples, so interpolation adds no information but keeps their time steps short).  The velocity
    is derived from x (Savitzky-Golay), not taken from the file's finite difference.

    Notes
    -----
    The source smoothed x and F alike with a causal moving average over a tenth of a period: both carry the same
    lag (about 1/20 of a period), so the phase between them is kept, but sharp force changes at reversals are
    rounded over that window - a floor on the ESR any model can reach.
    """
    import re
    from pathlib import Path

    path = Path(path)
    match = re.fullmatch(QUIROZ_FILE_NAME, path.stem)
    if match is None:
        raise ErdesignError(
            f"{path}: not a Quiroz (2022) preprocessed file name (<amp>mm<freq>Hz<current>A.txt, "
            "'x' for the decimal point, e.g. 10mm1Hz0x5A.txt)"
        )
    freq, current = (float(match[k].replace("x", ".")) for k in ("freq", "cur"))
    test = f"{match['amp']}mm{match['freq']}Hz"
    try:
        a = np.loadtxt(path, ndmin=2)
    except ValueError as exc:
        raise ErdesignError(f"{path}: not four whitespace-separated numeric columns t, x, v, F ({exc})") from None
    if a.shape[1] != 4 or a.shape[0] < 10 or not np.all(np.isfinite(a)) or np.any(np.diff(a[:, 0]) <= 0):
        raise ErdesignError(
            f"{path}: expected four numeric columns t [s], x [mm], v [mm/s], F [N] with increasing "
            f"time, got {a.shape[1]} columns and {a.shape[0]} rows"
        )
    period = 1.0 / freq
    keep = a[:, 0] >= a[-1, 0] - cycles * period
    t0 = a[keep, 0][0]
    t = np.linspace(0.0, a[-1, 0] - t0, int(round((a[-1, 0] - t0) / period * samples_per_cycle)) + 1)
    x = np.interp(t + t0, a[:, 0], a[:, 1]) * 1e-3
    F = np.interp(t + t0, a[:, 0], a[:, 3])
    return Measurement.from_arrays(
        t, x - x.mean(), F, control=current, control_kind="current", name=f"{test} {current:g} A"
    )


def read_quiroz_validation(folder, *, step: int = 1) -> list[Measurement]:
    """The earthquake-type validation record (validation/validacion.mat, 1 kHz): one record per current
    (0.2 to 1.0 A), every ``step``-th sample (:func:`read_quiroz_mat`)."""
    from pathlib import Path

    return read_quiroz_mat(Path(folder) / "validation" / "validacion.mat", step=step)


def read_quiroz_mat(path, *, step: int = 1) -> list[Measurement]:
    """Quiroz's earthquake-type validation record (variable ``data``, 1 kHz: displacement [mm], then the force [N]
    at 0.2, 0.4, 0.6, 0.8 and 1.0 A): one record per current, every ``step``-th sample."""
    from scipy.io import loadmat

    try:
        data = loadmat(str(path))["data"][::step]
    except (KeyError, ValueError, OSError) as exc:
        raise ErdesignError(
            f"{path}: not Quiroz's validation file (a MATLAB file with a 'data' matrix of 6 columns: {exc})"
        ) from None
    if data.ndim != 2 or data.shape[1] != 1 + len(QUIROZ_VALIDATION_CURRENTS):
        raise ErdesignError(
            f"{path}: 'data' has shape {data.shape}, expected (samples, 6): displacement [mm] and the "
            "force [N] at 0.2, 0.4, 0.6, 0.8, 1.0 A"
        )
    t = np.arange(data.shape[0]) * 1e-3 * step
    x = data[:, 0] * 1e-3
    return [
        Measurement.from_arrays(t, x, data[:, k + 1], control=i, control_kind="current", name=f"earthquake {i:g} A")
        for k, i in enumerate(QUIROZ_VALIDATION_CURRENTS)
    ]


def read_quiroz_raw(folder, test: str, *, cycles: float | None = 3.0) -> list[Measurement]:
    r"""One raw DAQ file of the Quiroz (2022) MR damper (``raw/ME<test>.txt``): one record per coil current.

    The file (shared/data/README.md) holds the five currents 0, 0.25, 0.5, 0.75, 1 A one after another, each
    segment ended by a ``DAQ Pause`` event line; x [mm] = 10 x the displacement channel, F [N] = 980.665 x the force
    channel, the two channels swapped where :data:`QUIROZ_RAW_TESTS` says.  The sampling interval is read from the
    header.  Each segment starts at rest: the force there (the median over the still samples before the first
    motion) is the load cell's offset and is subtracted, as the source removed the offsets of its validation
    record; the displacement is taken about its mean.  With ``cycles`` only the last ``cycles`` periods of the
    motion are kept (the start of a test is a transient of the press, and the press stops before the segment ends);
    None keeps the segment from its start to the end of the motion.  Nothing is smoothed or resampled.

    Assumed: the segments are in rising current order (the force amplitude rises segment by segment in all six
    files: 195-242 N in the first, 1363-1586 N in the last).
    """
    from pathlib import Path

    spec = {name: (freq, swapped) for name, freq, swapped in QUIROZ_RAW_TESTS}
    if test not in spec:
        raise ErdesignError(
            f"read_quiroz_raw: unknown test {test!r}; the raw files are {', '.join(n for n, _, _ in QUIROZ_RAW_TESTS)}"
        )
    freq, swapped = spec[test]
    path = Path(folder) / "raw" / f"ME{test}.txt"
    dt, rows, ends = None, [], []
    with open(path) as fh:
        for k, line in enumerate(fh):
            if line.startswith("Sampling Interval:"):
                dt = float(line.split(":")[1])
            if k < 7:
                continue
            parts = line.split(",")
            rows.append((float(parts[2]), float(parts[3])))
            if len(parts) > 4 and "Pause" in parts[4]:
                ends.append(len(rows))
    if dt is None or len(ends) != len(QUIROZ_CURRENTS):
        raise ErdesignError(
            f"{path}: expected a DAQ export with a sampling interval and {len(QUIROZ_CURRENTS)} "
            f"segments ended by 'DAQ Pause', got {len(ends)}"
        )
    a = np.asarray(rows)
    if swapped:
        a = a[:, ::-1]
    x_all, F_all = a[:, 0] * 1e-2, a[:, 1] * 980.665
    out, start = [], 0
    for current, end in zip(QUIROZ_CURRENTS, ends):
        x, F = x_all[start:end], F_all[start:end]
        start = end
        moving = np.flatnonzero(np.abs(x - x[0]) > 2e-4)
        still = max(int(moving[0]) - int(0.1 / dt), 1) if moving.size else len(x)
        F = F - float(np.median(F[:still]))
        # the press stops before the pause: the motion ends at the last full-amplitude period
        n_period = int(round(1.0 / freq / dt))
        ptp = np.array([np.ptp(x[k : k + n_period]) for k in range(0, len(x) - n_period + 1, max(n_period // 20, 1))])
        last = int(np.flatnonzero(ptp > 0.95 * ptp.max())[-1]) * max(n_period // 20, 1) + n_period
        first = 0 if cycles is None else max(last - int(round(cycles * n_period)) - 1, 0)
        x, F = x[first:last], F[first:last]
        t = np.arange(len(x)) * dt
        out.append(
            Measurement.from_arrays(
                t, x - x.mean(), F, control=current, control_kind="current", name=f"raw {test} {current:g} A"
            )
        )
    return out


def causal_moving_average(y, window: int) -> np.ndarray:
    """The mean of the last ``window`` samples at every sample, the signal taken as 0 before the first: the
    smoothing the source applied to its validation record (whose forces start at 0 with the offsets removed)."""
    from scipy.signal import lfilter

    return lfilter(np.ones(window) / window, 1.0, np.asarray(y, dtype=float))


def undo_causal_moving_average(y, window: int) -> np.ndarray:
    r"""The signal x whose causal moving average over ``window`` samples is ``y``, with x equal to y[0] before the
    first sample (a record that starts at rest).

    From :math:`y_n - y_{n-1} = (x_n - x_{n-W}) / W`: :math:`x_n = x_{n-W} + W (y_n - y_{n-1})`, exact on the stored
    numbers (re-smoothing the result gives ``y`` back to round-off).  What the average removed at its zeros
    (multiples of 1 / (W dt)) cannot come back: there the result carries the rest-state assumption; and a
    quantisation step q of y becomes steps of W q in x (on Quiroz's record q = 0.01 um, so 3 um).
    """
    y = np.asarray(y, dtype=float)
    x = np.empty_like(y)
    dy = np.diff(y, prepend=y[0]) * window
    for start in range(0, len(y), window):
        prev = x[start - window : start] if start >= window else np.full(min(window, len(y)), y[0])
        stop = min(start + window, len(y))
        x[start:stop] = prev[: stop - start] + dy[start:stop]
    return x


def read_quiroz_validation_unsmoothed(folder) -> list[Measurement]:
    """The validation record (1 kHz, every sample) with the displacement the press applied before the source's
    smoothing (:func:`undo_causal_moving_average` over :data:`QUIROZ_VALIDATION_WINDOW`); the force is left as
    stored (smoothed).  A model run on this motion is compared with the force through the same smoothing
    (:func:`causal_moving_average` of its output): the measurement chain applied to the model, not the inverse
    applied to the measured force."""
    out = []
    for r in read_quiroz_validation(folder, step=1):
        x = undo_causal_moving_average(r.displacement, QUIROZ_VALIDATION_WINDOW)
        out.append(
            Measurement.from_arrays(
                r.time, x, r.force, control=float(r.control[0]), control_kind="current", name=r.name
            )
        )
    return out
