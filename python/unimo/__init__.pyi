"""Type stubs of the unimo package."""

import os
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Union

import numpy as np
import pandas as pd

from .errors import ModelError as ModelError
from .errors import SimulationError as SimulationError
from .errors import UnimoError as UnimoError
from .errors import UsageError as UsageError

__version__: str

PathLike = Union[str, os.PathLike[str]]
ParamValue = Union[float, int, bool, str]

class Result:
    """One run: numpy columns, units, run statistics."""

    names: List[str]
    time: np.ndarray
    units: Dict[str, str]
    stats: Dict[str, Any]
    def __getitem__(self, name: str) -> np.ndarray: ...
    def __contains__(self, name: str) -> bool: ...
    def __len__(self) -> int: ...
    def final(self) -> Dict[str, float]: ...
    def to_pandas(self) -> pd.DataFrame: ...

class Model:
    """A compiled model."""

    params: Dict[str, ParamValue]
    names: List[str]
    @property
    def units(self) -> Dict[str, str]: ...
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
    ) -> Result: ...
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
    ) -> pd.DataFrame: ...

def compile(
    path: Union[PathLike, Sequence[PathLike]],
    model: Optional[str] = None,
    libs: Sequence[PathLike] = (),
    params: Optional[Mapping[str, ParamValue]] = None,
    tunable: Union[None, bool, Sequence[str]] = None,
) -> Model: ...
def simulate(
    path: Union[PathLike, Sequence[PathLike]],
    model: Optional[str] = None,
    libs: Sequence[PathLike] = (),
    params: Optional[Mapping[str, ParamValue]] = None,
    tunable: Union[None, bool, Sequence[str]] = None,
    *,
    stop_time: Optional[float] = None,
    method: str = "auto",
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    outputs: Optional[Sequence[str]] = None,
    start_time: Optional[float] = None,
    interval: Optional[float] = None,
    points: Optional[int] = None,
) -> Result: ...
