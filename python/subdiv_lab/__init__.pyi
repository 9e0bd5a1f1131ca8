"""Type stubs of the subdiv_lab package (see the docstrings in __init__.py)."""
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
import pyarrow as pa

__version__: str

def matrix(
    scheme: str = ...,
    valence: Optional[int] = ...,
    knots: Optional[Sequence[Tuple[float, float]]] = ...,
    ratios: Optional[Sequence[float]] = ...,
    uniform: bool = ...,
    c: Optional[float] = ...,
    block: str = ...,
) -> Tuple[npt.NDArray[np.float64], List[str]]: ...
def analyze(
    scheme: str = ...,
    valence: Optional[int] = ...,
    knots: Optional[Sequence[Tuple[float, float]]] = ...,
    ratios: Optional[Sequence[float]] = ...,
    uniform: bool = ...,
    c: Optional[float] = ...,
    path: str = ...,
    levels: int = ...,
    seed: int = ...,
) -> Dict[str, Any]: ...
def classify_batch(
    ratios: npt.ArrayLike,
    scheme: str = ...,
    columns: Optional[Mapping[str, Any]] = ...,
    threads: Optional[int] = ...,
) -> Dict[str, npt.NDArray[Any]]: ...
def sweep(
    spec: Union[str, os.PathLike[str], Mapping[str, Any]],
    threads: Optional[int] = ...,
    shard: Optional[Union[str, Tuple[int, int]]] = ...,
    limit: Optional[int] = ...,
) -> pa.Table: ...
def subdivide(
    vertices: npt.ArrayLike,
    faces: Sequence[Sequence[int]],
    scheme: str = ...,
    knots: Optional[Mapping[Tuple[int, int], float]] = ...,
    levels: int = ...,
    c: Optional[float] = ...,
) -> Tuple[npt.NDArray[np.float64], List[List[int]]]: ...
def report(
    spec: Union[str, os.PathLike[str], Mapping[str, Any]],
    out: Union[str, os.PathLike[str]],
) -> List[str]: ...
