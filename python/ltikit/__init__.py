"""ltikit for Python: LTI models with exact poles and zeros, closed-form responses, margins
and headless plots, computed by the ltikit Rust library.

>>> import ltikit as lk
>>> G = lk.tf([4], [1, 0.8, 4])
>>> G
G(s) = 4 / (s^2 + 0.8 s + 4)
>>> G.poles()                                   # doctest: +SKIP
array([-0.4+1.95959179j, -0.4-1.95959179j])

Models: :func:`tf`, :func:`zpk`, :func:`ss`, :func:`model`, :func:`plant`, :func:`pid`,
:func:`controller`; every analysis, design (``lqr``, ``lqe``, ``lqg``, ``place``), norm and
reduction is a method of :class:`System`; :func:`batch` analyses many models on all cores;
the matrix equations are :func:`lyap`, :func:`dlyap`, :func:`sylvester`, :func:`care`,
:func:`dare` (and :func:`lqr` on matrices). Errors are :class:`LtiError` (a ``ValueError``) with the command
line's one-line message.
"""

from __future__ import annotations

import json
import math
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import LtiError

__all__ = [
    "LtiError",
    "System",
    "Record",
    "Analysis",
    "StateSpaceAnalysis",
    "ZeroStructure",
    "StepInfo",
    "RouthTable",
    "JuryTable",
    "Margins",
    "Stability",
    "TimeResponse",
    "FrequencyResponse",
    "Nyquist",
    "RootLocus",
    "Residue",
    "Regulator",
    "Estimator",
    "Lqg",
    "Placement",
    "PeakGain",
    "H2Norm",
    "Gramian",
    "Reduction",
    "MatrixSolution",
    "RiccatiSolution",
    "tf",
    "zpk",
    "ss",
    "model",
    "models",
    "plant",
    "plant_line",
    "pid",
    "controller",
    "connect",
    "diagram",
    "batch",
    "from_control",
    "from_scipy",
    "lqr",
    "care",
    "dare",
    "lyap",
    "dlyap",
    "sylvester",
    "__version__",
]

__version__: str = _core.__version__

_MAX_COEFFICIENTS: int = _core.MAX_ORDER + 1

ArrayLike = Any
"""Numbers as a list, tuple or numpy array."""


# ---- results ------------------------------------------------------------------------------


class Record:
    """A result with attribute access (``r.rise_time``) and item access (``r["rise_time"]``).

    Nested documents are records too; :meth:`to_dict` gives plain dicts back.
    """

    def __init__(self, fields: Mapping[str, Any]) -> None:
        self._fill(fields)

    def _fill(self, fields: Mapping[str, Any]) -> None:
        for k, v in fields.items():
            self.__dict__[k] = _wrap(v)

    def _load(self) -> Dict[str, Any]:
        """The fields (a document still held as JSON text is read now)."""
        d = self.__dict__
        raw = d.pop("_raw", None)
        if raw is not None:
            self._fill(json.loads(raw))
        return d

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        d = self._load()
        if name in d:
            return d[name]
        raise AttributeError(
            f"{type(self).__name__} has no field {name!r} (fields: {', '.join(d)})"
        )

    def __getitem__(self, key: str) -> Any:
        return self._load()[key]

    def __contains__(self, key: object) -> bool:
        return key in self._load()

    def keys(self) -> Any:
        """The field names, in the document's order."""
        return self._load().keys()

    def to_dict(self) -> dict:
        """The record as plain dicts and lists (arrays stay numpy arrays)."""
        return {k: _unwrap(v) for k, v in self._load().items()}

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Record):
            return NotImplemented
        return _equal(self.to_dict(), other.to_dict())

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        body = ", ".join(f"{k}={_short(v)}" for k, v in self._load().items())
        return f"{type(self).__name__}({body})"


def _wrap(v: Any) -> Any:
    if isinstance(v, dict):
        return Record(v)
    if isinstance(v, list):
        return [_wrap(x) for x in v]
    return v


def _unwrap(v: Any) -> Any:
    if isinstance(v, Record):
        return v.to_dict()
    if isinstance(v, list):
        return [_unwrap(x) for x in v]
    return v


def _equal(a: Any, b: Any) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return bool(np.array_equal(np.asarray(a), np.asarray(b)))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_equal(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_equal(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def _short(v: Any) -> str:
    if isinstance(v, np.ndarray):
        return f"array(shape={v.shape})" if v.size > 6 else np.array2string(v, precision=6)
    text = repr(v)
    return text if len(text) <= 80 else text[:77] + "..."


def _complex(pairs: Any) -> np.ndarray:
    """``[[re, im], …]`` (the JSON contract's complex numbers) as a complex array."""
    a = np.asarray(pairs, dtype=float).reshape(-1, 2)
    return a[:, 0] + 1j * a[:, 1]


class Analysis(Record):
    """What ``ltikit analyze --json`` reports, with attribute access: ``order``,
    ``relative_degree``, ``poles``/``zeros``/``cancelled`` (complex arrays, repeated roots
    repeated), ``dc_gain`` (``None`` when infinite), ``bibo_stable``, ``internally_stable``,
    ``stability_reason``, ``structure``, ``modes``, ``second_order``, ``step_info`` (or
    ``None`` with ``step_info_note``); from :func:`batch` also ``margins`` (or ``None`` with
    ``margins_note``), or ``error`` alone for a model that could not be analysed."""

    def __init__(self, doc: Union[str, Mapping[str, Any]]) -> None:
        if isinstance(doc, str):
            self.__dict__["_raw"] = doc  # from batch: read at the first access
        else:
            self._fill(doc)

    def _fill(self, fields: Mapping[str, Any]) -> None:
        doc = dict(fields)
        for key in ("poles", "zeros", "cancelled"):
            if key in doc:
                doc[key] = _complex(doc[key])
        super()._fill(doc)
        d = self.__dict__
        for m in d.get("modes", []):
            m.__dict__["pole"] = complex(*m.pole)
        for n in d.get("near_cancellations", []):
            n.__dict__["zero"] = complex(*n.zero)
            n.__dict__["pole"] = complex(*n.pole)
        si = d.get("step_info")
        if isinstance(si, Record):
            d["step_info"] = StepInfo(si.to_dict())
        mg = d.get("margins")
        if isinstance(mg, Record):
            d["margins"] = Margins(mg.to_dict())


class StateSpaceAnalysis(Analysis):
    """The whole-model analysis of a state-space model (any numbers of inputs and outputs),
    what ``ltikit analyze`` reports for one: ``n``, ``m``, ``p`` (states, inputs, outputs),
    ``poles`` (the eigenvalues of A with repetition), ``eigenvalues`` (distinct, with
    ``algebraic`` and ``geometric`` multiplicities), ``controllability`` and
    ``observability`` (staircase ``rank`` and ``tol``), ``minimal_order``,
    ``uncontrollable_modes``, ``unobservable_modes``, ``invariant_zeros`` (of this
    realisation, with multiplicities; ``None`` with ``invariant_zeros_note``),
    ``zero_structure`` (``normal_rank``, ``infinite_orders``, ``left_indices``,
    ``right_indices``, ``residuals``), ``dc_gain`` (p × m array, ``inf`` where a channel has a
    pole at 0), ``internally_stable`` with ``internal_reason``, ``bibo_stable`` (p × m bool
    array, per channel) and ``modes`` (``value``, ``wn``, ``zeta``, ``tau``)."""

    def _fill(self, fields: Mapping[str, Any]) -> None:
        doc = dict(fields)
        eig = doc.get("eigenvalues", [])
        doc["poles"] = np.array(
            [complex(*e["value"]) for e in eig for _ in range(e["algebraic"])], dtype=complex
        )
        for e in eig:
            e["value"] = complex(*e["value"])
        for m in doc.get("modes", []):
            m["value"] = complex(*m["value"])
        for key in ("uncontrollable_modes", "unobservable_modes"):
            doc[key] = _complex(doc.get(key, []))
        iz = doc.get("invariant_zeros")
        if iz is not None:
            doc["invariant_zeros"] = [(complex(*z), int(k)) for z, k in iz]
        doc["dc_gain"] = np.array(
            [[math.inf if g == "infinite" else float(g["finite"]) for g in row] for row in doc["dc_gain"]],
            dtype=float,
        ).reshape(doc["p"], doc["m"])
        doc["bibo_stable"] = np.array(doc["bibo_stable"], dtype=bool).reshape(doc["p"], doc["m"])
        Record._fill(self, doc)


class ZeroStructure(Record):
    """The transmission zeros of a model with the Kronecker structure of its (minimal) system
    pencil [A − sI  B; C  D]: ``zeros`` (complex, with repetition), ``multiplicities``
    (``[(zero, m), …]``), ``normal_rank`` (of G(s)), ``infinite_orders`` (orders of the zeros
    at infinity), ``left_indices`` and ``right_indices`` (the Kronecker minimal indices; a
    non-square or rank-deficient G has them)."""


class RouthTable(Record):
    """The Routh–Hurwitz table of a characteristic polynomial: ``polynomial`` (descending
    coefficients of D, or D + K·N with a gain), ``rows`` (a 2-D array, s^n down to s^0),
    ``powers`` (the power of s of each row), ``events`` (a zero first element replaced by ε,
    or a zero row with its auxiliary polynomial), the root counts ``rhp``, ``axis``, ``lhp``
    (decided in exact rational arithmetic on the coefficients as typed when ``exact``,
    otherwise read from the table; the table's own counts are ``table_rhp`` …), ``stable``,
    and ``stable_gains``: the exact set of gains K for which D + K·N has every root in the
    open left half plane, as ``(low, high)`` open intervals (±``inf`` for no bound)."""


class JuryTable(Record):
    """The Jury table of a characteristic polynomial in z (Åström–Wittenmark form):
    ``polynomial``, ``rows`` (a list of arrays, two per stage, each one shorter than the
    stage before), ``alphas``, ``first`` (the
    first elements), ``singular_at`` (the stage at which the table stops, or ``None``), the
    counts ``inside``, ``on``, ``outside`` the unit circle (exact when ``exact``; the table's
    own ``table_inside`` …), ``stable``, and ``stable_gains``: the exact set of gains K for
    which D + K·N has every root strictly inside the unit circle, ``(low, high)`` intervals."""


class StepInfo(Record):
    """Step metrics (MATLAB ``stepinfo``): ``rise_time``, ``settling_time``,
    ``overshoot_percent``, ``peak``, ``peak_time``, ``steady_state``, ``transient_time``,
    ``settling_min``, ``settling_max``, ``undershoot_percent``; a metric that could not be
    computed is ``None`` with ``<name>_note`` beside it."""


class Margins(Record):
    """Stability margins: ``gain_margin`` (ratio, ``None`` when infinite),
    ``gain_margin_db``, ``phase_crossover``, ``phase_margin_deg``, ``gain_crossover``, every
    crossing (``gain_crossings``, ``phase_crossings``), ``bandwidth``, ``resonant_peak``,
    ``resonant_frequency``, ``delay_margin`` and ``delay_margin_w``."""


class Stability(Record):
    """BIBO and internal stability with the reasons (``reason``, ``bibo_reason``,
    ``internal_reason``). True when internally stable (every pole, cancelled ones included,
    in the open left half plane or inside the unit circle)."""

    def __bool__(self) -> bool:
        return bool(self.__dict__["internally_stable"])


class TimeResponse(Record):
    """A time response: ``t``, ``y`` (exact values), and for a standard input the closed form
    (``closed_form``, ``transient``, ``steady_state`` as text; ``closed_form_values`` sampled,
    ``closed_form_error`` the largest disagreement with ``y``) and ``final_value``.
    Unpacks as ``t, y = G.step()``."""

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter((self.__dict__["t"], self.__dict__["y"]))


class FrequencyResponse(Record):
    """A frequency response: ``w`` (rad/s), ``magnitude``, ``magnitude_db``, ``phase_deg``
    (continuous in ω), ``response`` (complex G(jω)). Unpacks as
    ``w, mag, phase = G.freq()``."""

    def __iter__(self) -> Iterator[np.ndarray]:
        d = self.__dict__
        return iter((d["w"], d["magnitude"], d["phase_deg"]))


class Nyquist(Record):
    """The Nyquist contour: ``s`` (its points; z on the unit circle in discrete time), ``g``
    (G there), ``open_loop_rhp_poles`` (P), ``encirclements`` (N, clockwise, of −1),
    ``closed_loop_rhp_poles`` (Z = N + P), ``g_at_infinity``, ``axis_poles``, ``region``."""


class RootLocus(Record):
    """The root locus of 1 + K·G: ``gains`` (K, increasing in |K|), ``branches`` (one row per
    closed-loop pole, one column per gain), ``poles``, ``zeros``, ``asymptotes``,
    ``break_points``, ``crossings``, ``departures``, ``arrivals``, ``notes``."""


class Residue(Record):
    """Partial fractions G = Σ r/(s − p)^k + direct: ``terms`` as (pole, power, residue)
    tuples, ``direct`` the polynomial part (descending coefficients)."""


class Regulator(Record):
    """A linear-quadratic regulator (u = −K x): ``K`` (m × n), ``X`` (the stabilising
    solution of the Riccati equation; the optimal cost from x₀ is x₀ᵀXx₀), ``poles`` (the
    eigenvalues of A − BK, in s or in z), ``equation`` (``"care"`` or ``"dare"``),
    ``residual`` (relative) and ``condition`` (an estimate)."""


class Estimator(Record):
    """A Kalman estimator (x̂' = A x̂ + B u + L (y − C x̂ − D u)): ``L`` (n × p), ``P`` (the
    steady error covariance; discrete: of the one-step prediction), ``poles`` (the eigenvalues
    of A − LC), ``noise`` (where the process noise enters: ``"states"`` or ``"inputs"``),
    ``equation``, ``residual``, ``condition``."""


class Lqg(Record):
    """An LQG design: ``regulator`` (:class:`Regulator`), ``estimator`` (:class:`Estimator`)
    and ``controller``, the :class:`System` from y to −u (so ``G.feedback(ctrl)`` is the
    closed loop)."""


class Placement(Record):
    """Pole placement (u = −K x): ``K``, ``method``, ``requested`` and achieved ``poles``
    (the eigenvalues of A − BK), ``distance`` (of each achieved pole from its request),
    ``relative_error``, ``condition``, ``iterations``, ``note`` (a warning on conditioning, or
    ``None``)."""


class PeakGain(Record):
    """A certified peak gain (H∞ or L∞ norm): ``value`` (= ``lower``, σ_max(G) at ``w``),
    ``upper`` (a γ no singular value of G reaches), ``relative_gap`` (upper/lower − 1),
    ``w`` (the peak frequency, rad/s; ``inf`` for ω → ∞), ``iterations``, ``norm`` (``"H∞"``
    or ``"L∞"``), ``infinite`` (why the norm is infinite, or ``None``). ``float(n)`` is the
    value."""

    def __float__(self) -> float:
        return float(self.__dict__["value"])


class H2Norm(Record):
    """The H2 norm: ``value`` (``inf`` when infinite), ``residual`` (of the Gramian it comes
    from), ``infinite`` (why, or ``None``). ``float(n)`` is the value."""

    def __float__(self) -> float:
        return float(self.__dict__["value"])


class Gramian(Record):
    """A Gramian: ``gramian`` (P or Q), ``factor`` (L, lower triangular, P = L·Lᵀ) and
    ``residual`` (relative, in its Lyapunov equation)."""


class Reduction(Record):
    """A balanced truncation: ``reduced`` (the :class:`System` of ``order`` states, D kept),
    ``states`` (of the full model), ``hsv`` (its Hankel singular values), ``bound`` (the a
    priori bound 2·Σ_{i>k} σᵢ), ``error`` (the certified ‖G − G_r‖∞, a :class:`PeakGain`),
    ``residuals`` (of the two Gramians)."""


class MatrixSolution(Record):
    """The solution ``X`` of a linear matrix equation with its ``residual`` (relative) and
    ``condition`` (a lower-bound estimate of the relative condition number)."""


class RiccatiSolution(Record):
    """The stabilising solution ``X`` of an algebraic Riccati equation with the gain ``K``
    (R⁻¹(BᵀX + Sᵀ); discrete: (R + BᵀXB)⁻¹(BᵀXA + Sᵀ)), the closed-loop ``poles``
    (eigenvalues of A − BK), ``residual`` and ``condition``."""


# ---- argument checks ----------------------------------------------------------------------


def _first_line(e: BaseException) -> str:
    return str(e).splitlines()[0] if str(e) else type(e).__name__


def _vector(x: ArrayLike, name: str, dtype: Any = float, limit: Any = None) -> list:
    """A flat list of numbers from a list, tuple, scalar or numpy array; ``limit`` (one of
    the library's limits, :func:`_points` or :func:`_order`) is checked before it is copied."""
    if isinstance(x, (str, bytes)):
        raise LtiError(f"`{name}` must be a list of numbers (found a string)")
    try:
        a = np.asarray(x, dtype=dtype)
    except (ValueError, TypeError) as e:
        raise LtiError(
            f"`{name}` must be a list of numbers ({_first_line(e)})"
        ) from None
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise LtiError(f"`{name}` must be a flat list of numbers (found shape {a.shape})")
    if limit is not None:
        limit(f"`{name}`", a)
    return a.tolist()


def _points(name: str, a: np.ndarray) -> None:
    """The library's limit on sample points (MAX_POINTS), before a long array is copied."""
    _core.check_points(name, a.size)


def _order(name: str, a: np.ndarray) -> None:
    """The library's limit on the order (MAX_ORDER), leading zeros not counted."""
    if a.size <= _MAX_COEFFICIENTS:
        return  # within the limit whatever the leading zeros (the common case, no scan)
    nonzero = np.flatnonzero(a)
    _core.check_order(name, a.size - int(nonzero[0]) if nonzero.size else 0)


def _matrix(x: ArrayLike, name: str) -> list:
    """Rows of numbers from nested lists or a 2-D array (a scalar is 1×1)."""
    if isinstance(x, (str, bytes)):
        raise LtiError(f"`{name}` must be a matrix of numbers (found a string)")
    try:
        a = np.asarray(x, dtype=float)
    except (ValueError, TypeError) as e:
        raise LtiError(
            f"`{name}` must be a matrix of numbers, rows of equal length ({_first_line(e)})"
        ) from None
    if a.ndim == 0:
        a = a.reshape(1, 1)
    if a.ndim != 2:
        raise LtiError(f"`{name}` must be a 2-D matrix (found shape {a.shape})")
    return a.tolist()


def _samples(u: ArrayLike, n: int, m: int) -> list:
    """Input samples as a flat list, row by row: ``n`` values for one input, or an array of
    shape (n, m) for m inputs (checked here, before it is copied)."""
    if isinstance(u, (str, bytes)):
        raise LtiError("`u` must be an array of numbers (found a string)")
    try:
        a = np.asarray(u, dtype=float)
    except (ValueError, TypeError) as e:
        raise LtiError(f"`u` must be an array of numbers ({_first_line(e)})") from None
    _points("`u`", a)
    if m == 1 and a.ndim == 1:
        a = a.reshape(-1, 1)
    if a.ndim != 2 or a.shape != (n, m):
        raise LtiError(
            f"`u` has shape {a.shape}: the model has {m} input{'s' if m != 1 else ''} and "
            f"`t` {n} times, give shape ({n}, {m})" + (f" or ({n},)" if m == 1 else "")
        )
    return a.ravel().tolist()


def _number(x: Any, name: str) -> float:
    try:
        return float(x)
    except (ValueError, TypeError):
        raise LtiError(f"`{name}` must be a number (found {_short(x)})") from None


def _dt(dt: Any) -> Optional[float]:
    if dt is None or dt is False:
        return None
    if dt is True:
        raise LtiError("`dt` must be a sampling period in seconds (True leaves it unspecified)")
    return _number(dt, "dt")


def _weight(x: ArrayLike, name: str) -> list:
    """A weight or covariance: a matrix, or one number for that multiple of the identity."""
    return _matrix(x, name)


def _noise(noise: Optional[str]) -> Optional[str]:
    if noise is None:
        return None
    if not isinstance(noise, str):
        raise LtiError(f'`noise` must be "states", "inputs" or None (found {_short(noise)})')
    return noise


def _count(x: Any, name: str) -> int:
    if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or int(x) < 0:
        raise LtiError(f"`{name}` must be a whole number ≥ 0 (found {_short(x)})")
    return int(x)


# ---- the model ----------------------------------------------------------------------------


class System:
    """An LTI model: SISO or MIMO, continuous or discrete time. Build it with :func:`tf`,
    :func:`zpk`, :func:`ss`, :func:`model`, :func:`plant` or :func:`pid`.

    Operators: ``G * H`` (series: H first, then G — the product of transfer functions),
    ``G + H`` (parallel), ``-G``, ``G - H``, and :meth:`feedback`; numbers act as constant
    gains. ``G[out, in]`` is one channel of a MIMO model. The factorisation (poles and zeros
    with exact multiplicities) is computed once, at the first analysis.
    """

    __slots__ = ("_m", "_recipe", "_whole")

    def __init__(self, core: _core.Model, recipe: Tuple[Any, ...]) -> None:
        self._m = core
        self._recipe = recipe
        # a MIMO model answers the whole-model calls (state-space analysis) itself
        self._whole = core.shape() != (1, 1)

    # what it is
    def __repr__(self) -> str:
        return self._m.text()

    @property
    def name(self) -> str:
        """The model's name: its transfer function, the model with its parameters, the file."""
        return self._m.name()

    @property
    def dt(self) -> Optional[float]:
        """The sampling period in seconds (``None``: continuous time)."""
        return self._m.dt()

    @property
    def shape(self) -> Tuple[int, int]:
        """(outputs, inputs)."""
        return self._m.shape()

    @property
    def signals(self) -> Dict[str, List[str]]:
        """The names of the ``inputs``, ``outputs`` and ``states`` (a connected diagram's
        signals; empty lists when the model has none)."""
        i, o, x = self._m.signal_names()
        return {"inputs": i, "outputs": o, "states": x}

    def is_siso(self) -> bool:
        """True for one input and one output."""
        return self._m.shape() == (1, 1)

    def __getitem__(self, index: Tuple[int, int]) -> "System":
        """``G[out, in]``: the channel from input ``in`` to output ``out`` (0-based)."""
        if not (isinstance(index, tuple) and len(index) == 2):
            raise LtiError("index a model by G[out, in] (two integers)")
        out, inp = index
        try:
            o, i = int(out), int(inp)
        except (TypeError, ValueError):
            raise LtiError("index a model by G[out, in] (two integers)") from None
        p, m = self.shape
        o, i = (o + p if o < 0 else o), (i + m if i < 0 else i)
        if o < 0 or i < 0:
            raise LtiError(f"channel [{out}, {inp}] does not exist: the model is {p}×{m}")
        return System(self._m.channel(o, i), ("channel", self, o, i))

    def tfdata(self) -> Tuple[np.ndarray, np.ndarray]:
        """Numerator and denominator coefficients (descending powers) of a SISO transfer
        function (of the factors expanded for a model built from them)."""
        c = self._m.coefficients()
        if c is None:
            raise LtiError("a state-space model has no coefficients here: use ssdata()")
        return c

    def ssdata(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The matrices A, B, C, D (a transfer function in controllable canonical form)."""
        return self._m.matrices()

    # analyses
    def poles(self) -> np.ndarray:
        """The poles (roots of the characteristic polynomial, cancelled ones included), a
        complex array with repeated poles repeated, sorted by decreasing real part. For a
        MIMO model the eigenvalues of A (python-control's ``poles()``)."""
        if self._whole:
            return self._m.whole_poles()
        return self._m.poles()

    def zeros(self) -> np.ndarray:
        """The finite zeros, a complex array with repeated zeros repeated. For a MIMO model
        (square or not) the transmission zeros: the finite zeros of the minimal realisation's
        system pencil; :meth:`zero_structure` gives the rest of its Kronecker structure."""
        if self._whole:
            return self._m.whole_zeros()[0]
        return self._m.zeros()

    def zero_structure(self) -> ZeroStructure:
        """The transmission zeros with the Kronecker structure of the minimal system pencil
        [A − sI  B; C  D] (any model; a transfer function through its realisation): see
        :class:`ZeroStructure`."""
        z, doc = self._m.whole_zeros()
        doc["multiplicities"] = [(complex(*v), int(k)) for v, k in doc["multiplicities"]]
        return ZeroStructure({"zeros": z, **doc})

    def pole_multiplicities(self) -> List[Tuple[complex, int]]:
        """Distinct poles with their exact multiplicities: ``[(pole, m), …]``."""
        return self._m.pole_multiplicities()

    def zero_multiplicities(self) -> List[Tuple[complex, int]]:
        """Distinct zeros with their exact multiplicities: ``[(zero, m), …]``."""
        return self._m.zero_multiplicities()

    @property
    def gain(self) -> float:
        """The gain k of G = k·Π(s − z)/Π(s − p)."""
        return self._m.gain()

    def dc_gain(self) -> Union[float, np.ndarray]:
        """The dc gain G(0) of the reduced G (G(1) in discrete time); ``inf`` when infinite.
        For a MIMO model the p × m matrix (``inf`` where a channel has a pole at 0)."""
        if self._whole:
            p, m = self.shape
            return self._m.whole_dc_gain().reshape(p, m)
        return self._m.dc_gain()

    def is_stable(self) -> Stability:
        """Stability with the reason; true when internally stable (``bool(G.is_stable())``).
        For a MIMO model also ``channels_bibo_stable`` (p × m, each channel's minimal
        realisation)."""
        if self._whole:
            d = self._m.whole_stability()
            d["channels_bibo_stable"] = np.array(d["channels_bibo_stable"], dtype=bool)
            return Stability(d)
        return Stability(self._m.stability())

    def analyze(self, whole: bool = False) -> Analysis:
        """Everything ``ltikit analyze --json`` reports, as an :class:`Analysis`. A MIMO
        model (or any model with ``whole=True``) gets the whole-model state-space analysis,
        a :class:`StateSpaceAnalysis`."""
        if self._whole or whole:
            return StateSpaceAnalysis(self._m.whole_analysis())
        return Analysis(self._m.analyze())

    def residue(self) -> Residue:
        """Partial fractions of G (exact multiplicities, conjugate residues exactly conjugate)."""
        return Residue(self._m.residue())

    def step(self, t: Optional[ArrayLike] = None) -> TimeResponse:
        """Unit-step response at the times ``t`` (an automatic grid when ``None``), with the
        closed form. For a MIMO model ``y`` has shape (outputs, inputs, len(t)): the response
        of every output to a unit step on each input in turn (python-control's
        ``step_response``)."""
        return self.response("step", t)

    def impulse(self, t: Optional[ArrayLike] = None) -> TimeResponse:
        """Unit-impulse response at the times ``t`` (a D·δ(t) term is not in the values); for
        a MIMO model shaped (outputs, inputs, len(t)) as :meth:`step`."""
        return self.response("impulse", t)

    def response(
        self,
        u: Union[str, ArrayLike],
        t: Optional[ArrayLike] = None,
        hold: str = "foh",
        x0: Optional[ArrayLike] = None,
    ) -> TimeResponse:
        """The response to ``u``: a standard input by name (``"step"``, ``"impulse"``,
        ``"ramp"``, ``"exp:A"``, ``"sin:W"``, ``"cos:W"``) with its closed form, or input
        samples at the times ``t`` (``hold="foh"`` linear between samples, ``"zoh"`` held):
        one value per time, or for m inputs an array of shape (len(t), m); ``y`` then has one
        row per output (a 1-D array for one output). ``x0``: the initial state of a
        state-space model (with a named input only ``"step"`` and ``"impulse"``; the free
        response :meth:`initial` is added)."""
        tt = None if t is None else _vector(t, "t", limit=_points)
        if isinstance(u, str):
            if x0 is not None:
                return self._forced_from(u, tt, x0)
            if self._whole:
                if u not in ("step", "impulse"):
                    raise LtiError(
                        f"a MIMO model's response takes \"step\", \"impulse\" or input samples (found {u!r})"
                    )
                tw, yw = self._m.whole_step(tt, u == "impulse")
                p, m = self.shape
                return TimeResponse({"t": tw, "y": yw.reshape(p, m, tw.size)})
            return TimeResponse(self._m.response(u, tt))
        if tt is None:
            raise LtiError("`t`: give the times of the input samples `u`")
        uu = _samples(u, len(tt), self.shape[1])
        xx = None if x0 is None else _vector(x0, "x0")
        y = self._m.lsim(uu, tt, hold, xx)
        return TimeResponse({"t": np.asarray(tt), "y": self._outputs(y, len(tt))})

    def initial(self, x0: ArrayLike, t: Optional[ArrayLike] = None) -> TimeResponse:
        """The free response (u = 0) of a state-space model from the initial state ``x0`` at
        the times ``t`` (an automatic grid when ``None``); ``y`` has one row per output (a
        1-D array for one output), python-control's ``initial_response``."""
        tt = None if t is None else _vector(t, "t", limit=_points)
        tw, y = self._m.initial(_vector(x0, "x0"), tt)
        return TimeResponse({"t": tw, "y": self._outputs(y, tw.size)})

    def _outputs(self, y: np.ndarray, n: int) -> np.ndarray:
        """Flat output samples as (outputs, n), or 1-D for one output."""
        p = self.shape[0]
        return y if p == 1 else y.reshape(p, n)

    def _forced_from(self, u: str, t: Optional[list], x0: ArrayLike) -> TimeResponse:
        """A step or impulse response of a state-space model plus the free response from x0."""
        if u not in ("step", "impulse"):
            raise LtiError(
                f"`x0` goes with \"step\", \"impulse\" or input samples (found {u!r})"
            )
        xx = _vector(x0, "x0")
        tw, yw = self._m.whole_step(t, u == "impulse")
        _, free = self._m.initial(xx, tw.tolist())
        p, m = self.shape
        forced = yw.reshape(p, m, tw.size) + free.reshape(p, 1, tw.size)
        return TimeResponse({"t": tw, "y": forced[0, 0] if (p, m) == (1, 1) else forced})

    def step_info(self) -> StepInfo:
        """Step metrics (MATLAB ``stepinfo``); ``LtiError`` with the reason when there are
        none (the response does not settle, settles to 0, or G is improper)."""
        info, note = self._m.step_info()
        if info is None:
            raise LtiError(note or "no step metrics")
        return StepInfo(info)

    def freq(self, w: Optional[ArrayLike] = None) -> FrequencyResponse:
        """Frequency response at ``w`` rad/s (an automatic grid when ``None``): magnitude,
        phase in degrees (continuous in ω), and the complex values."""
        wv = None if w is None else _vector(w, "w", limit=_points)
        if self._whole:
            ww, mag, phase, g = self._m.whole_freq(wv)
            p, m = self.shape
            mag = mag.reshape(p, m, ww.size)
            phase = phase.reshape(p, m, ww.size)
            g = g.reshape(p, m, ww.size)
        else:
            ww, mag, phase, g = self._m.freq(wv)
        with np.errstate(divide="ignore"):
            db = 20.0 * np.log10(mag)
        return FrequencyResponse(
            {"w": ww, "magnitude": mag, "magnitude_db": db, "phase_deg": phase, "response": g}
        )

    def routh(self, gain: Optional[float] = None, gains: bool = True) -> RouthTable:
        """The Routh–Hurwitz table of a continuous-time transfer function's characteristic
        polynomial D (with ``gain=K``: of the closed loop D + K·N in unity negative
        feedback), the root counts decided exactly, and with ``gains`` the exact set of
        stabilising gains (``ltikit routh --json``). See :class:`RouthTable`."""
        k = None if gain is None else _number(gain, "gain")
        return RouthTable(_table(self._m.routh(k, bool(gains))))

    def jury(self, gain: Optional[float] = None, gains: bool = True) -> JuryTable:
        """The Jury table of a discrete-time transfer function's characteristic polynomial
        in z (with ``gain=K``: of D + K·N), the counts inside, on and outside the unit circle
        (exact for the coefficients as typed), and with ``gains`` the exact stabilising gains
        (``ltikit jury --json``). See :class:`JuryTable`."""
        k = None if gain is None else _number(gain, "gain")
        return JuryTable(_table(self._m.jury(k, bool(gains)), ragged=True))

    def margins(self) -> Margins:
        """Gain and phase margins (MATLAB ``margin``), every crossing, bandwidth, resonance
        and the delay margin."""
        return Margins(self._m.margins())

    def nyquist(self) -> Nyquist:
        """The Nyquist contour and the criterion's counts."""
        s, g, meta = self._m.nyquist()
        return Nyquist({"s": s, "g": g, **meta})

    def rlocus(self, negative: bool = False) -> RootLocus:
        """The root locus of 1 + K·G for K ≥ 0 (``negative=True``: K ≤ 0)."""
        gains, branches, rest = self._m.rlocus(bool(negative))
        return RootLocus({"gains": gains, "branches": branches, **rest})


    # design (the model itself: no dead time, at least one state)
    def lqr(self, Q: ArrayLike, R: ArrayLike, S: Optional[ArrayLike] = None) -> Regulator:
        """The linear-quadratic regulator u = −K x minimising ∫ xᵀQx + uᵀRu + 2xᵀSu dt (the
        sum in discrete time: DARE instead of CARE). One number for ``Q`` or ``R`` stands for
        that multiple of the identity. MATLAB ``lqr``/``dlqr``; python-control ``ct.lqr``."""
        s = None if S is None else _matrix(S, "s")
        return Regulator(_core.design_lqr(self._m, _weight(Q, "q"), _weight(R, "r"), s))

    def lqe(
        self,
        Qn: ArrayLike,
        Rn: ArrayLike,
        Nn: Optional[ArrayLike] = None,
        noise: Optional[str] = None,
    ) -> Estimator:
        """The Kalman estimator gain L for process noise covariance ``Qn`` and measurement
        noise covariance ``Rn`` (cross covariance ``Nn``). ``noise="states"``: the noise
        enters every state (Qn n × n); ``"inputs"``: through B (Qn m × m, MATLAB's G = B);
        ``None`` decides by the size of Qn."""
        nn = None if Nn is None else _matrix(Nn, "nn")
        return Estimator(
            _core.design_lqe(self._m, _weight(Qn, "qn"), _weight(Rn, "rn"), nn, _noise(noise))
        )

    def lqg(
        self,
        Q: ArrayLike,
        R: ArrayLike,
        Qn: ArrayLike,
        Rn: ArrayLike,
        noise: Optional[str] = None,
    ) -> Lqg:
        """The LQG controller: :meth:`lqr` with Q, R and :meth:`lqe` with Qn, Rn joined as an
        observer-based compensator; ``.controller`` is the :class:`System` from y to −u, so
        ``G.feedback(d.controller)`` is the closed loop."""
        d = _core.design_lqg(
            self._m,
            _weight(Q, "q"),
            _weight(R, "r"),
            _weight(Qn, "qn"),
            _weight(Rn, "rn"),
            _noise(noise),
        )
        a, b, c, dd = d.pop("controller")
        ctrl = ss(a, b, c, dd, dt=d.pop("dt"))
        return Lqg(
            {
                "regulator": Regulator(d["regulator"]),
                "estimator": Estimator(d["estimator"]),
                "controller": ctrl,
            }
        )

    def place(self, poles: ArrayLike) -> Placement:
        """The state feedback u = −K x putting the eigenvalues of A − BK at ``poles``
        (conjugate pairs complete; in z for a discrete model). MATLAB/python-control
        ``place``."""
        p = Placement(_core.design_place(self._m, _vector(poles, "poles", complex, limit=_points)))
        return p

    # norms and reduction (a state-space model as given, otherwise the minimal realisation)
    def hinf_norm(self) -> PeakGain:
        """The certified H∞ norm: an interval [lower, upper] (upper/lower − 1 ≤ 1e-10) and
        the peak frequency; infinite, with the reason, for an unstable model."""
        return PeakGain(_core.peak_gain(self._m, False))

    def linf_norm(self) -> PeakGain:
        """The certified L∞ norm sup_ω σ_max(G(jω)) of a model without poles on the
        imaginary axis (unit circle); the H∞ norm for a stable model."""
        return PeakGain(_core.peak_gain(self._m, True))

    def h2_norm(self) -> H2Norm:
        """The H2 norm (from a Gramian); infinite, with the reason, for an unstable model or
        a continuous one with D ≠ 0."""
        return H2Norm(_core.norm_h2(self._m))

    def gram(self, kind: str = "c") -> Gramian:
        """The controllability (``"c"``: A P + P Aᵀ + B Bᵀ = 0) or observability (``"o"``:
        Aᵀ Q + Q A + Cᵀ C = 0) Gramian of a stable model (the Stein equations in discrete
        time)."""
        return Gramian(_core.gram(self._m, str(kind)))

    def hsv(self) -> np.ndarray:
        """The Hankel singular values of a stable model, largest first."""
        return np.asarray(_core.hsv(self._m), dtype=float)

    def balred(self, order: Optional[int] = None, error: Optional[float] = None) -> Reduction:
        """Balanced truncation (square-root method) to ``order`` states, or to the smallest
        order whose bound 2·Σ_{i>k} σᵢ is at most ``error``; with the bound and the certified
        error ‖G − G_r‖∞."""
        k = None if order is None else _count(order, "order")
        e = None if error is None else _number(error, "error")
        r = _core.balred(self._m, k, e)
        a, b, c, d = r.pop("reduced")
        reduced = ss(a, b, c, d, dt=r.pop("dt"))
        r["hsv"] = np.asarray(r["hsv"], dtype=float)
        r["error"] = PeakGain(r["error"])
        return Reduction({"reduced": reduced, **r})

    def sigma(self, w: ArrayLike) -> np.ndarray:
        """The singular values of G(jω) (G(e^(jωT)) in discrete time) at each frequency of
        ``w`` rad/s: one row per frequency, largest first."""
        return _core.sigma(self._m, _vector(w, "w", limit=_points))

    def eval(self, s: complex) -> Any:
        """G at the complex point ``s`` (z in discrete time, the dead time included): a
        complex number for a SISO model, the p × m complex array of a MIMO one. An error at
        a pole, naming it (and the channel)."""
        try:
            point = complex(s)
        except (TypeError, ValueError):
            raise LtiError(f"`s` must be a complex number (found {_short(s)})") from None
        g = self._m.eval_matrix(point)
        return complex(g[0, 0]) if self.is_siso() else g

    def __call__(self, s: complex) -> Any:
        """G(s) at one complex point (:meth:`eval`)."""
        return self.eval(s)

    # interconnections
    def feedback(self, h: Union["System", float] = 1.0, sign: float = -1.0) -> "System":
        """The closed loop through ``h`` (u = r + sign·h·y; ``sign=-1`` negative feedback):
        G/(1 − sign·G·H), its poles found once from every factor as given."""
        hh = _as_system(h)
        s = _number(sign, "sign")
        return System(self._m.feedback(hh._m, s), ("feedback", self, hh, s))

    def __mul__(self, other: Union["System", float]) -> "System":
        o = _as_system(other)
        return System(o._m.series(self._m), ("series", o, self))

    def __rmul__(self, other: float) -> "System":
        o = _as_system(other)
        return System(self._m.series(o._m), ("series", self, o))

    def __add__(self, other: Union["System", float]) -> "System":
        o = _as_system(other)
        return System(self._m.parallel(o._m), ("parallel", self, o))

    __radd__ = __add__

    def __neg__(self) -> "System":
        return self * -1.0

    def __sub__(self, other: Union["System", float]) -> "System":
        return self + (-_as_system(other))

    def __rsub__(self, other: float) -> "System":
        return _as_system(other) + (-self)

    # sampling
    def c2d(self, dt: float, method: str = "zoh", prewarp: Optional[float] = None) -> "System":
        """The model sampled with period ``dt``: ``method`` ``"zoh"``, ``"foh"``,
        ``"tustin"`` (``prewarp`` rad/s optional), ``"matched"`` or ``"impulse"``."""
        p = None if prewarp is None else _number(prewarp, "prewarp")
        d = _number(dt, "dt")
        return System(self._m.c2d(d, str(method), p), ("c2d", self, d, str(method), p))

    def d2c(self, method: str = "zoh", prewarp: Optional[float] = None) -> "System":
        """The continuous model whose ``method`` sampling is this discrete one."""
        p = None if prewarp is None else _number(prewarp, "prewarp")
        return System(self._m.d2c(str(method), p), ("d2c", self, str(method), p))

    # pictures (ltikit's own rasteriser)
    def bode_png(
        self,
        path: str,
        w: Optional[ArrayLike] = None,
        margins: bool = True,
        title: Optional[str] = None,
        size: Optional[Tuple[int, int]] = None,
    ) -> None:
        """Writes a Bode diagram (PNG) with the margins marked."""
        self._m.bode_png(str(path), None if w is None else _vector(w, "w", limit=_points), margins, title, size)

    def step_png(
        self,
        path: str,
        input: str = "step",
        t_end: Optional[float] = None,
        title: Optional[str] = None,
        size: Optional[Tuple[int, int]] = None,
    ) -> None:
        """Writes the step (or ``input``) response (PNG) with the step metrics marked."""
        self._m.step_png(str(path), input, t_end, title, size)

    def pzmap_png(
        self,
        path: str,
        guides: bool = True,
        title: Optional[str] = None,
        size: Optional[Tuple[int, int]] = None,
    ) -> None:
        """Writes the pole-zero map (PNG)."""
        self._m.pzmap_png(str(path), guides, title, size)

    def nyquist_png(
        self, path: str, title: Optional[str] = None, size: Optional[Tuple[int, int]] = None
    ) -> None:
        """Writes the Nyquist diagram (PNG)."""
        self._m.nyquist_png(str(path), title, size)

    def rlocus_png(
        self,
        path: str,
        negative: bool = False,
        title: Optional[str] = None,
        size: Optional[Tuple[int, int]] = None,
    ) -> None:
        """Writes the root locus (PNG)."""
        self._m.rlocus_png(str(path), negative, title, size)

    # matplotlib
    def plot_bode(self, ax: Any = None, w: Optional[ArrayLike] = None) -> Any:
        """Draws |G| in dB and the phase on matplotlib axes: ``ax`` a pair (magnitude, phase)
        or ``None`` (a new figure). Returns the pair of axes."""
        from ._mpl import plot_bode

        return plot_bode(self, ax, w)

    def plot_step(self, ax: Any = None, t: Optional[ArrayLike] = None) -> Any:
        """Draws the step response on matplotlib axes (a new figure when ``None``)."""
        from ._mpl import plot_step

        return plot_step(self, ax, t)

    # interop
    def to_control(self) -> Any:
        """The model as a python-control ``TransferFunction`` (or ``StateSpace`` for a
        state-space model)."""
        from ._interop import to_control

        return to_control(self)

    def __reduce__(self) -> Any:
        return (_rebuild, (self._recipe,))


def _table(doc: Dict[str, Any], ragged: bool = False) -> Dict[str, Any]:
    """A Routh document with its rows as a 2-D array (a Jury document's shrinking rows as a
    list of arrays) and gain intervals as tuples."""
    rows = doc["rows"]
    doc["rows"] = [np.array(r, dtype=float) for r in rows] if ragged else np.array(rows, dtype=float)
    doc["polynomial"] = np.array(doc["polynomial"], dtype=float)
    if "stable_gains" in doc:
        doc["stable_gains"] = [(float(lo), float(hi)) for lo, hi in doc["stable_gains"]]
    return doc


def _as_system(x: Union[System, float]) -> System:
    if isinstance(x, System):
        return x
    if isinstance(x, (int, float, np.integer, np.floating)):
        return tf([float(x)], [1.0])
    raise LtiError(f"cannot combine a model with {type(x).__name__}: give a System or a number")


def _rebuild(recipe: Tuple[Any, ...]) -> System:
    """A model from its recipe (pickling)."""
    kind, *args = recipe
    if kind == "series":
        return System(args[1]._m.series(args[0]._m), recipe)
    if kind == "parallel":
        return System(args[0]._m.parallel(args[1]._m), recipe)
    if kind == "feedback":
        return System(args[0]._m.feedback(args[1]._m, args[2]), recipe)
    if kind == "channel":
        return System(args[0]._m.channel(args[1], args[2]), recipe)
    if kind == "c2d":
        return System(args[0]._m.c2d(args[1], args[2], args[3]), recipe)
    if kind == "d2c":
        return System(args[0]._m.d2c(args[1], args[2]), recipe)
    if kind == "connect":
        spec, sm, ins, outs, name = args
        core = _core.Model.connect([(n, s._m, i, o) for n, s, i, o in spec], sm, ins, outs, name)
        return System(core, recipe)
    return System(getattr(_core.Model, kind)(*args), recipe)


# ---- constructors -------------------------------------------------------------------------


def tf(
    num: ArrayLike,
    den: ArrayLike,
    dt: Optional[float] = None,
    delay: Optional[float] = None,
) -> System:
    """A transfer function from its coefficients in descending powers of s (of z with
    ``dt``): ``tf([4], [1, 0.8, 4])`` is 4/(s² + 0.8 s + 4). Numbers are read like a plant
    file's (their shortest decimal text decides the structure exactly). ``delay=T`` is a dead
    time e^(−sT), kept exact (the phase loses ωT, responses are shifted, margins list the
    delayed crossings); in discrete time a whole number of periods, z^(−d)."""
    args = (
        _vector(num, "num", limit=_order),
        _vector(den, "den", limit=_order),
        _dt(dt),
        None if delay is None else _number(delay, "delay"),
    )
    return System(_core.Model.from_tf(*args), ("from_tf",) + args)


def zpk(
    zeros: ArrayLike,
    poles: ArrayLike,
    gain: float,
    dt: Optional[float] = None,
    delay: Optional[float] = None,
) -> System:
    """A model from its zeros, poles (conjugate pairs complete; repeated roots repeated) and
    gain k of G = k·Π(s − z)/Π(s − p). No root finding: the multiplicities are as given.
    ``delay=T`` is a dead time e^(−sT) as in :func:`tf` (discrete time: z^(−d), a whole
    number d of periods)."""
    args = (
        _vector(zeros, "zeros", complex, limit=_points),
        _vector(poles, "poles", complex, limit=_points),
        _number(gain, "gain"),
        _dt(dt),
        None if delay is None else _number(delay, "delay"),
    )
    return System(_core.Model.from_zpk(*args), ("from_zpk",) + args)


def ss(
    A: ArrayLike,
    B: ArrayLike,
    C: ArrayLike,
    D: ArrayLike = None,
    dt: Optional[float] = None,
    delay: Optional[float] = None,
) -> System:
    """A state-space model ẋ = Ax + Bu, y = Cx + Du (x[k+1] = … with ``dt``); D zero when
    omitted (a scalar D fills the p×m matrix). ``delay=T``: the dead time T on every input,
    u(t − T) (kept exact: responses shifted, phase lag ωT on every channel)."""
    a, b, c = _matrix(A, "a"), _matrix(B, "b"), _matrix(C, "c")
    d: Optional[list] = None
    if D is not None:
        if np.ndim(D) == 0:
            value = _number(D, "d")
            inputs = len(b[0]) if b else 0
            d = None if value == 0 else [[value] * inputs for _ in c]
        else:
            d = _matrix(D, "d")
    args = (a, b, c, d, _dt(dt), None if delay is None else _number(delay, "delay"))
    return System(_core.Model.from_ss(*args), ("from_ss",) + args)


def model(name: str, **params: float) -> System:
    """A textbook model of the seed with parameters: ``model("spring-mass-damper", M=1,
    C=0.4, K=4)``; :func:`models` lists them with their defaults."""
    p = [(str(k), _number(v, k)) for k, v in params.items()]
    return System(_core.Model.from_model(str(name), p), ("from_model", str(name), p))


def models() -> dict:
    """The textbook models and their parameters with default values."""
    return {name: dict(params) for name, params in _core.model_names()}


def plant(path: str) -> System:
    """A plant file (TOML: ``num``/``den``, matrices ``a``…``d``, or ``model`` with
    ``[params]``; optional ``dt``)."""
    return System(_core.Model.from_plant_file(str(path)), ("from_plant_file", str(path)))


def plant_line(line: str) -> System:
    """A batch line (one JSON record, the plant-file schema)."""
    return System(_core.Model.from_json_line(str(line)), ("from_json_line", str(line)))


def controller(kind: str, **params: float) -> System:
    """A controller as a transfer function: ``p`` (kp), ``pi`` (kp, ki), ``pd`` (kp, kd,
    tf), ``pid`` (kp, ki, kd, tf), ``lead``/``lag`` (k, z, p)."""
    p = [(str(k), _number(v, k)) for k, v in params.items()]
    return System(_core.Model.from_controller(str(kind), p), ("from_controller", str(kind), p))


def pid(kp: float = 0.0, ki: float = 0.0, kd: float = 0.0, tf: float = 0.0) -> System:
    """PID controller kp + ki/s + kd·s/(tf·s + 1) (MATLAB's Tf; a zero gain leaves its term
    out)."""
    params = {"kp": kp, "ki": ki, "kd": kd, "tf": tf}
    return controller("pid", **{k: v for k, v in params.items() if k == "kp" or v != 0})


def _signals(x: Any, what: str) -> List[str]:
    """One signal name or a list of them."""
    if isinstance(x, str):
        return [x]
    if isinstance(x, (list, tuple)) and all(isinstance(v, str) for v in x):
        return list(x)
    raise LtiError(f"{what} must be a signal name or a list of names (found {_short(x)})")


def connect(
    blocks: Mapping[str, Tuple[Any, Any, Any]],
    inputs: Union[str, Sequence[str]],
    outputs: Union[str, Sequence[str]],
    sums: Optional[Mapping[str, str]] = None,
    name: Optional[str] = None,
) -> System:
    """Systems joined by named signals, as a diagram file joins its blocks (the library's
    ``connect``, MATLAB's and python-control's ``connect``): ``blocks`` maps a block name to
    ``(system, input signal(s), output signal(s))``; ``sums`` maps a signal to an expression
    such as ``"r - y"`` or ``"2*a + 0.5*b"``; ``inputs`` are the external inputs, ``outputs``
    any signals. The result is one state-space model, its states in the order of the block
    names (``BLOCK.x1``, …), its signals named. Unity feedback around P::

        T = lk.connect({"P": (P, "e", "y")}, inputs="r", outputs="y", sums={"e": "r - y"})

    Errors (each naming the block or signal): a signal driven twice or never, signal lists
    that do not match a block's inputs and outputs, mixed domains, a dead time, an algebraic
    loop that is not well posed."""
    if not isinstance(blocks, Mapping):
        raise LtiError("`blocks` must map block names to (system, inputs, outputs)")
    spec = []
    for key in sorted(blocks):
        item = blocks[key]
        if not (isinstance(item, (tuple, list)) and len(item) == 3 and isinstance(item[0], System)):
            raise LtiError(
                f"block `{key}` must be (system, input signal(s), output signal(s)) (found {_short(item)})"
            )
        spec.append((str(key), item[0], _signals(item[1], f"block `{key}`: inputs"),
                     _signals(item[2], f"block `{key}`: outputs")))
    sm = [] if sums is None else [(str(k), str(v)) for k, v in dict(sums).items()]
    ins, outs = _signals(inputs, "`inputs`"), _signals(outputs, "`outputs`")
    core = _core.Model.connect([(n, s._m, i, o) for n, s, i, o in spec], sm, ins, outs, name)
    return System(core, ("connect", spec, sm, ins, outs, name))


def diagram(d: Mapping[str, Any]) -> System:
    """A diagram given as a dict with the keys of a diagram file (docs/DIAGRAMS.md):
    ``inputs``, ``outputs``, ``blocks`` (name → a dict with ``input``, ``output`` and one of
    ``system`` (a :class:`System`), ``num``/``den``, ``a``/``b``/``c``/``d``, ``controller``
    (``"pid:kp=2,ki=1"``) or ``plant`` (a plant file)), optional ``sums``, ``dt`` (coefficient,
    matrix and controller blocks in discrete time; a continuous controller sampled by Tustin)
    and ``name``; closed by :func:`connect`."""
    if not isinstance(d, Mapping):
        raise LtiError("a diagram is a dict with `inputs`, `outputs`, `blocks` (and `sums`)")
    known = {"inputs", "outputs", "blocks", "sums", "dt", "name", "description"}
    extra = sorted(set(d) - known)
    if extra:
        raise LtiError(f"unknown diagram key `{extra[0]}` (keys: {', '.join(sorted(known))})")
    for key in ("inputs", "outputs", "blocks"):
        if key not in d:
            raise LtiError(f"the diagram has no `{key}`")
    dt = _dt(d.get("dt"))
    blocks: Dict[str, Tuple[Any, Any, Any]] = {}
    if not isinstance(d["blocks"], Mapping):
        raise LtiError("`blocks` must map block names to block dicts")
    for key, b in d["blocks"].items():
        if not isinstance(b, Mapping):
            raise LtiError(f"block `{key}` must be a dict (found {_short(b)})")
        kinds = [k for k in ("system", "num", "a", "controller", "plant") if k in b]
        if len(kinds) != 1:
            raise LtiError(
                f"block `{key}` must have exactly one of `system`, `num`/`den`, `a`/`b`/`c` "
                f"(optional `d`), `controller` or `plant`"
            )
        for s in ("input", "output"):
            if s not in b:
                raise LtiError(f"block `{key}` has no `{s}` signal")
        kind = kinds[0]
        if kind == "system":
            if not isinstance(b["system"], System):
                raise LtiError(f"block `{key}`: `system` must be a System")
            sys = b["system"]
        elif kind == "num":
            sys = tf(b["num"], b.get("den", [1]), dt=dt)
        elif kind == "a":
            sys = ss(b["a"], b.get("b"), b.get("c"), b.get("d"), dt=dt)
        elif kind == "controller":
            spec = str(b["controller"])
            sys = System(_core.Model.from_controller_spec(spec, dt), ("from_controller_spec", spec, dt))
        else:
            sys = plant(b["plant"])
        blocks[str(key)] = (sys, b["input"], b["output"])
    return connect(blocks, d["inputs"], d["outputs"], d.get("sums"), d.get("name"))


def batch(plants: Sequence[System]) -> List[Analysis]:
    """Analyses ``plants`` on all cores with the GIL released: one :class:`Analysis` per
    plant (the ``analyze`` document plus ``margins``), or one with ``error`` alone."""
    cores = []
    for i, p in enumerate(plants):
        if not isinstance(p, System):
            raise LtiError(f"`plants`: item {i} is a {type(p).__name__}, not a System")
        cores.append(p._m)
    return [Analysis(d) for d in _core.batch(cores)]


# ---- matrix equations ---------------------------------------------------------------------


def lyap(A: ArrayLike, Q: ArrayLike) -> MatrixSolution:
    """Solves A X + X Aᵀ + Q = 0 (MATLAB ``lyap(A, Q)``). Note the sign: scipy's
    ``solve_continuous_lyapunov(A, Q)`` solves A X + X Aᴴ = Q, so it equals ``lyap(A, -Q).X``."""
    return MatrixSolution(_core.solve_lyap(_matrix(A, "a"), _matrix(Q, "q")))


def dlyap(A: ArrayLike, Q: ArrayLike) -> MatrixSolution:
    """Solves A X Aᵀ − X + Q = 0 (MATLAB ``dlyap(A, Q)``; scipy's
    ``solve_discrete_lyapunov(A, Q)`` solves the same equation)."""
    return MatrixSolution(_core.solve_dlyap(_matrix(A, "a"), _matrix(Q, "q")))


def sylvester(A: ArrayLike, B: ArrayLike, C: ArrayLike) -> MatrixSolution:
    """Solves A X + X B = C (scipy's ``solve_sylvester(A, B, C)``; MATLAB ``sylvester``)."""
    return MatrixSolution(
        _core.solve_sylvester(_matrix(A, "a"), _matrix(B, "b"), _matrix(C, "c"))
    )


def care(
    A: ArrayLike, B: ArrayLike, Q: ArrayLike, R: ArrayLike, S: Optional[ArrayLike] = None
) -> RiccatiSolution:
    """The stabilising solution of AᵀX + XA − (XB + S)R⁻¹(BᵀX + Sᵀ) + Q = 0 (scipy's
    ``solve_continuous_are(A, B, Q, R, s=S)``), with the gain K and the closed-loop poles."""
    s = None if S is None else _matrix(S, "s")
    return RiccatiSolution(
        _core.solve_riccati(_matrix(A, "a"), _matrix(B, "b"), _matrix(Q, "q"), _matrix(R, "r"), s, False)
    )


def dare(
    A: ArrayLike, B: ArrayLike, Q: ArrayLike, R: ArrayLike, S: Optional[ArrayLike] = None
) -> RiccatiSolution:
    """The stabilising solution of AᵀXA − X − (AᵀXB + S)(R + BᵀXB)⁻¹(BᵀXA + Sᵀ) + Q = 0
    (scipy's ``solve_discrete_are(A, B, Q, R, s=S)``), with the gain K and the closed-loop
    poles."""
    s = None if S is None else _matrix(S, "s")
    return RiccatiSolution(
        _core.solve_riccati(_matrix(A, "a"), _matrix(B, "b"), _matrix(Q, "q"), _matrix(R, "r"), s, True)
    )


def lqr(
    A: ArrayLike, B: ArrayLike, Q: ArrayLike, R: ArrayLike, S: Optional[ArrayLike] = None
) -> Regulator:
    """The continuous-time LQR of ẋ = Ax + Bu (python-control's ``ct.lqr(A, B, Q, R)``):
    ``K``, ``X``, ``poles`` (E in python-control). For a model, :meth:`System.lqr` (which
    also designs discrete-time regulators)."""
    a, b = _matrix(A, "a"), _matrix(B, "b")
    outputs = [[0.0] * len(a)] if a else [[]]
    plant = System(_core.Model.from_ss(a, b, outputs, None, None), ("from_ss", a, b, outputs, None, None))
    return plant.lqr(Q, R, S)


def from_control(sys: Any) -> System:
    """A python-control ``TransferFunction`` or ``StateSpace`` as a :class:`System`."""
    from ._interop import from_control as f

    return f(sys)


def from_scipy(sys: Any) -> System:
    """A scipy.signal ``lti``/``dlti`` (TransferFunction, ZerosPolesGain or StateSpace)."""
    from ._interop import from_scipy as f

    return f(sys)
