"""unimo: compile and simulate Modelica models from Python.

>>> import unimo
>>> model = unimo.compile("models/BouncingBall.mo")
>>> result = model.simulate(stop_time=3)
>>> result["h"][-1], result.stats["events"]
>>> table = model.sweep({"e": [0.5, 0.7, 0.9]}, outputs=["h"])

Compiling runs the whole pipeline of the ``unimo`` command line (flattening, index
reduction, BLT, code generation). Parameter values given to :func:`compile` are applied
as modifiers and folded into the compiled model; values given to
:meth:`Model.simulate` or :meth:`Model.sweep` compile the model again with them (the
per-point cost is measured in ``docs/python.md``).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import (
    TYPE_CHECKING,
    Any,
    Callable,
    Dict,
    Iterable,
    List,
    Mapping,
    Optional,
    Sequence,
    Union,
)

import numpy as np

from . import _unimo
from .errors import ModelError, SimulationError, UnimoError, UsageError, from_tuple

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "compile",
    "simulate",
    "Model",
    "Result",
    "UnimoError",
    "ModelError",
    "SimulationError",
    "UsageError",
]
__version__: str = _unimo.__version__

PathLike = Union[str, "os.PathLike[str]"]
#: A parameter value: a number, a Boolean or an enumeration literal's name.
ParamValue = Union[float, int, bool, str]


def _modelica_text(name: str, value: Any) -> str:
    """A Python value as Modelica literal text (``True`` -> ``true``, floats exactly)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return value
    raise UsageError("E0004", f"`{name}`: {value!r} is not a number, a Boolean or a name")


def _param_pairs(params: Mapping[str, Any]) -> List[tuple]:
    return [(str(k), _modelica_text(str(k), v)) for k, v in params.items()]


def _raise(error: tuple, result: Optional["Result"] = None) -> None:
    exc = from_tuple(error)
    exc.result = result
    raise exc


class Result:
    """The result of one run.

    ``result.time`` and ``result["h"]`` are numpy arrays (one entry per output point,
    two at each event: the left and right limits); ``names`` lists the columns,
    ``units`` maps names to units (those declared), ``stats`` holds the run statistics
    (``steps``, ``events``, ``rhs``, ``jacobians``, ... as ``unimo simulate --stats``).
    """

    def __init__(self, raw: Dict[str, Any], units: Optional[Mapping[str, str]] = None):
        self.names: List[str] = list(raw["names"])
        ncols = raw["ncols"]
        self.time: np.ndarray = np.frombuffer(raw["time"], dtype=np.float64).copy()
        data = np.frombuffer(raw["data"], dtype=np.float64)
        self._data: np.ndarray = data.reshape(len(self.time), ncols).copy()
        given = list(raw.get("units") or [])
        if given:
            self.units: Dict[str, str] = {n: u for n, u in zip(self.names, given) if u}
        else:
            self.units = {n: units[n] for n in self.names if units and units.get(n)}
        self.stats: Dict[str, Any] = dict(raw.get("stats") or {})
        self._index = {n: k for k, n in enumerate(self.names)}

    def __getitem__(self, name: str) -> np.ndarray:
        """The column of variable ``name`` (``"time"`` gives the time)."""
        if name == "time":
            return self.time
        try:
            return self._data[:, self._index[name]]
        except KeyError:
            raise KeyError(f"no column `{name}` in the result") from None

    def __contains__(self, name: str) -> bool:
        return name == "time" or name in self._index

    def __len__(self) -> int:
        return len(self.time)

    def final(self) -> Dict[str, float]:
        """Every column's last value, ``time`` first."""
        out = {"time": float(self.time[-1]) if len(self.time) else float("nan")}
        if len(self.time):
            out.update({n: float(self._data[-1, k]) for n, k in self._index.items()})
        return out

    def to_pandas(self) -> pd.DataFrame:
        """The result as a ``pandas.DataFrame``: a ``time`` column, then one per name."""
        import pandas as pd

        frame = pd.DataFrame(self._data, columns=self.names)
        frame.insert(0, "time", self.time)
        return frame

    def __repr__(self) -> str:
        return f"<unimo.Result {len(self.time)} rows x {len(self.names)} columns>"


class Model:
    """A compiled model. Make one with :func:`unimo.compile`."""

    def __init__(self, native: Any, spec: tuple, params: Mapping[str, ParamValue]):
        self._native = native
        self._spec = spec
        self.params: Dict[str, ParamValue] = dict(params)
        #: Result column names (every variable but parameters and constants).
        self.names: List[str] = list(native.names())
        self._units: Optional[Dict[str, str]] = None

    @property
    def units(self) -> Dict[str, str]:
        """Units of the result columns (those declared)."""
        if self._units is None:
            self._units = {n: u for n, u in self._native.units() if u}
        return self._units

    def simulate(
        self,
        stop_time: Optional[float] = None,
        params: Optional[Mapping[str, ParamValue]] = None,
        method: str = "auto",
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        outputs: Optional[Sequence[str]] = None,
        start_time: Optional[float] = None,
        interval: Optional[float] = None,
        points: Optional[int] = None,
    ) -> Result:
        """Simulates the model and returns a :class:`Result`.

        Defaults (stop time, tolerance, output interval) come from the model's
        ``experiment`` annotation. ``params`` compiles the model again with those
        values (on top of the ones given to :func:`compile`); without it the compiled
        model runs as is. ``outputs`` selects columns (a name, or a prefix: ``body``
        selects ``body.x``, ``body.v``...). ``method``: ``auto`` (BDF), ``bdf``,
        ``radau5``, ``dopri5``. The GIL is released while simulating.

        Raises :class:`SimulationError` when the run fails (``.result`` keeps the rows
        computed before), :class:`UsageError` for an unknown output or method.
        """
        model = self if not params else self._recompiled(params)
        options = {
            "stop_time": stop_time,
            "start_time": start_time,
            "rtol": rtol,
            "atol": atol,
            "method": method,
            "interval": interval,
            "points": points,
        }
        raw = model._native.simulate(options, list(outputs or []))
        result = Result(raw)
        if raw["error"] is not None:
            _raise(raw["error"], result)
        return result

    def _recompiled(self, params: Mapping[str, ParamValue]) -> "Model":
        merged = {**self.params, **params}
        native = _unimo.compile(self._spec, _param_pairs(merged))
        return Model(native, self._spec, merged)

    def sweep(
        self,
        grid_or_samples: Union[
            Mapping[str, Iterable[ParamValue]], Sequence[Mapping[str, ParamValue]], pd.DataFrame
        ],
        outputs: Optional[Sequence[str]] = None,
        jobs: Optional[int] = None,
        client: Any = None,
        summary: Optional[Callable[[Result], Dict[str, Any]]] = None,
        stop_time: Optional[float] = None,
        method: str = "auto",
        rtol: Optional[float] = None,
        atol: Optional[float] = None,
        interval: Optional[float] = None,
        points: Optional[int] = None,
        chunks: Optional[int] = None,
    ) -> pd.DataFrame:
        """Runs the model at many parameter points and returns one ``pandas.DataFrame``.

        ``grid_or_samples`` is a dict ``name -> list of values`` (every combination,
        the first name varying slowest) or a list of dicts (samples). Without
        ``client`` the points run on ``jobs`` threads of this process (default: every
        core; the GIL is released). With a ``dask.distributed.Client`` they run on its
        cluster in ``chunks`` tasks (default: 4 per worker); each task receives the
        model's source text and compiles it (a compiled model is not shipped).

        Each point compiles the model with its values (as :meth:`simulate` with
        ``params`` does). A row per point: the parameters, ``status`` (``ok`` or
        ``failed``), ``error_code``, ``error_message``, ``error_location``, the final
        values of ``outputs`` (every variable when ``None``) and, when ``summary`` is a
        function ``Result -> dict``, its entries (computed where the point ran). A
        point that fails keeps its error and the others complete.
        """
        from . import _sweep

        options = {
            "stop_time": stop_time,
            "rtol": rtol,
            "atol": atol,
            "method": method,
            "interval": interval,
            "points": points,
        }
        sweep = _sweep.Sweep(self._spec, self.params, list(outputs or []), options, summary)
        samples = _sweep.samples(grid_or_samples)
        return _sweep.run(sweep, samples, jobs=jobs, client=client, chunks=chunks)

    def __repr__(self) -> str:
        files = ", ".join(f for f, _ in self._spec[0])
        return f"<unimo.Model {self._spec[1] or files} {len(self.names)} variables>"


def _spec(path, model, libs, tunable) -> tuple:
    paths = [path] if isinstance(path, (str, os.PathLike)) else list(path)
    files = []
    for p in paths:
        p = Path(p)
        try:
            files.append((str(p), p.read_text()))
        except OSError as e:
            raise UsageError("E0001", f"cannot read `{p}`: {e}") from None
    if tunable is True:
        tunable = ["*"]
    elif tunable is not None:
        tunable = [str(t) for t in tunable]
    return (files, model, [str(lib) for lib in libs], tunable)


def compile(
    path: Union[PathLike, Sequence[PathLike]],
    model: Optional[str] = None,
    libs: Sequence[PathLike] = (),
    params: Optional[Mapping[str, ParamValue]] = None,
    tunable: Union[None, bool, Sequence[str]] = None,
) -> Model:
    """Compiles a model and returns a :class:`Model`.

    ``path``: the ``.mo`` file (or a list of files, the model's first); ``model``: its
    full name when the file holds several; ``libs``: library folders (searched before
    ``MODELICAPATH``, ``UNIMO_PATH`` and the bundled library); ``params``: parameter
    values, applied as modifiers (as ``unimo simulate -p``); ``tunable``: parameters
    kept out of constant folding (``True``: all). Raises :class:`ModelError` with the
    first error's ``code``, ``message`` and ``location``, or :class:`UsageError`.
    """
    params = dict(params or {})
    spec = _spec(path, model, libs, tunable)
    native = _unimo.compile(spec, _param_pairs(params))
    return Model(native, spec, params)


def simulate(
    path: Union[PathLike, Sequence[PathLike]],
    model: Optional[str] = None,
    libs: Sequence[PathLike] = (),
    params: Optional[Mapping[str, ParamValue]] = None,
    tunable: Union[None, bool, Sequence[str]] = None,
    **options: Any,
) -> Result:
    """Compiles and simulates in one call: ``compile(path, model, libs, params,
    tunable).simulate(**options)``, ``options`` being the keyword arguments of
    :meth:`Model.simulate` (``stop_time``, ``method``, ``rtol``, ``atol``, ``outputs``,
    ``start_time``, ``interval``, ``points``)."""
    return compile(path, model, libs, params, tunable).simulate(**options)
