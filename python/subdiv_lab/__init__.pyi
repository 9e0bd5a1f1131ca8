"""Type stubs of the subdiv_lab package (see the docstrings in __init__.py)."""
import os
from typing import Any, Dict, List, Mapping, Optional, Protocol, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt
import pyarrow as pa

__version__: str

Spec = Union[str, os.PathLike[str], Mapping[str, Any]]

def matrix(
    scheme: str = ...,
    valence: Optional[int] = ...,
    knots: Optional[Sequence[Tuple[float, float]]] = ...,
    ratios: Optional[Sequence[float]] = ...,
    uniform: bool = ...,
    c: Optional[float] = ...,
    block: str = ...,
    force: bool = ...,
) -> Tuple[npt.NDArray[np.float64], List[str]]: ...
class SchemeLike(Protocol):
    """A scheme of one's own: its name and its local matrix at a valence."""
    name: str
    def matrix(self, valence: int) -> Tuple[npt.ArrayLike, Optional[Sequence[str]]]: ...

def analyze(
    scheme: Optional[Union[str, SchemeLike]] = ...,
    valence: Optional[int] = ...,
    knots: Optional[Sequence[Tuple[float, float]]] = ...,
    ratios: Optional[Sequence[float]] = ...,
    uniform: bool = ...,
    c: Optional[float] = ...,
    path: str = ...,
    levels: int = ...,
    seed: int = ...,
    force: bool = ...,
    scheme_file: Optional[Union[str, os.PathLike[str]]] = ...,
    matrix: Optional[npt.ArrayLike] = ...,
    labels: Optional[Sequence[str]] = ...,
    charmap: str = ...,
) -> Dict[str, Any]: ...
def classify_batch(
    ratios: npt.ArrayLike,
    scheme: str = ...,
    columns: Optional[Mapping[str, Any]] = ...,
    threads: Optional[int] = ...,
    force: bool = ...,
) -> Dict[str, npt.NDArray[Any]]: ...
@overload
def sweep(
    spec: Spec,
    threads: Optional[int] = ...,
    shard: Optional[Union[str, Tuple[int, int]]] = ...,
    limit: Optional[int] = ...,
    force: bool = ...,
    scheme_file: Optional[Union[str, os.PathLike[str]]] = ...,
    scheme: Optional[SchemeLike] = ...,
    out: None = ...,
    resume: bool = ...,
) -> pa.Table: ...
@overload
def sweep(
    spec: Spec,
    threads: Optional[int] = ...,
    shard: Optional[Union[str, Tuple[int, int]]] = ...,
    limit: Optional[int] = ...,
    force: bool = ...,
    scheme_file: Optional[Union[str, os.PathLike[str]]] = ...,
    scheme: Optional[SchemeLike] = ...,
    *,
    out: Union[str, os.PathLike[str]],
    resume: bool = ...,
) -> Dict[str, Any]: ...
def merge(
    inputs: Union[str, os.PathLike[str], Sequence[Union[str, os.PathLike[str]]]],
    spec: Spec,
    force: bool = ...,
) -> Tuple[pa.Table, Dict[str, Any]]: ...
def subdivide(
    vertices: npt.ArrayLike,
    faces: Sequence[Sequence[int]],
    scheme: str = ...,
    knots: Optional[Mapping[Tuple[int, int], float]] = ...,
    levels: int = ...,
    c: Optional[float] = ...,
    force: bool = ...,
) -> Tuple[npt.NDArray[np.float64], List[List[int]]]: ...
def report(
    spec: Spec,
    out: Union[str, os.PathLike[str]],
) -> List[str]: ...
def verify(
    spec: Spec,
    threads: Optional[int] = ...,
    max_cells: Optional[int] = ...,
    force: bool = ...,
) -> Tuple[Dict[str, Any], pa.Table]: ...
def g2_cap(
    c: float,
    vertices: Optional[npt.ArrayLike] = ...,
    faces: Optional[Sequence[Sequence[int]]] = ...,
    vertex: Optional[int] = ...,
    valence: Optional[int] = ...,
    random_net: Optional[int] = ...,
    samples: Optional[int] = ...,
) -> Dict[str, Any]: ...
def plot(
    data: Union[str, os.PathLike[str], pa.Table],
    out: Optional[Union[str, os.PathLike[str]]] = ...,
    kind: Optional[str] = ...,
    x: Optional[str] = ...,
    y: Optional[str] = ...,
    color: Optional[str] = ...,
    title: Optional[str] = ...,
    width: int = ...,
    height: int = ...,
    format: Optional[str] = ...,
    force: bool = ...,
) -> bytes: ...
def cc_study(
    n_min: int = ...,
    n_max: int = ...,
    samples: int = ...,
    tol: float = ...,
    curves: bool = ...,
    criterion: str = ...,
    force: bool = ...,
) -> pa.Table: ...
def ccss_bound(
    valence: Optional[int] = ...,
    levels: int = ...,
    table_to: Optional[int] = ...,
    net: Optional[npt.ArrayLike] = ...,
    epsilon: Optional[float] = ...,
    force: bool = ...,
) -> Union[Dict[str, Any], pa.Table]: ...
