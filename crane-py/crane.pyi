"""Inverse dynamics of underactuated cranes: whole runs into numpy arrays."""

from os import PathLike
from typing import IO, Any, Literal, Mapping, Optional, Protocol, Sequence, Union, final

import numpy as np
import numpy.typing as npt
from typing_extensions import Self, TypeAlias, TypedDict, Unpack

__version__: str
"""The version of the crane library the module was built with (the wheel's)."""
__all__ = [
    "__version__",
    "CraneError",
    "CraneWarning",
    "Run",
    "Stepper",
    "models",
    "run",
    "stepper",
    "fastest",
    "sweep",
    "sweep_points",
    "convergence",
]

_Floats: TypeAlias = Union[Sequence[float], npt.NDArray[np.floating[Any]]]
"""Numbers as a sequence or a numpy array (grids, durations, steps)."""

class _SweepOptions(TypedDict, total=False):
    """The keywords `crane.distributed` passes on to `sweep_points`."""

    limits: Optional[Mapping[str, float]]
    min_tension: Optional[Mapping[str, float]]
    scenario: Union[str, PathLike[str], Mapping[str, Any], None]
    parameters: Optional[Mapping[str, float]]
    scheme: Optional[str]
    dt: Optional[float]

class _Distributed(Protocol):
    """The submodule `crane.distributed`: sweeps on a Dask cluster (dask is
    imported only when used: `pip install "crane[distributed]"`)."""

    def sweep(
        self,
        model: str,
        grid: Optional[Mapping[str, _Floats]] = None,
        points: Optional[Mapping[str, _Floats]] = None,
        *,
        client: Any,
        durations: Optional[_Floats] = None,
        chunk_size: int = 10_000,
        progress: bool = False,
        **options: Unpack[_SweepOptions],
    ) -> dict[str, Any]:
        """The sweep of `model` over `grid` (with `durations`, as `sweep`)
        or over `points` (with per-point `durations`, as `sweep_points`) on
        the Dask cluster of `client` (a `dask.distributed.Client`), in
        chunks of `chunk_size` points: `sweep`'s columns in the order of
        the points, the same numbers as one machine's."""

    def to_parquet(
        self,
        path: Union[str, PathLike[str]],
        model: str,
        grid: Optional[Mapping[str, _Floats]] = None,
        points: Optional[Mapping[str, _Floats]] = None,
        *,
        client: Any,
        durations: Optional[_Floats] = None,
        chunk_size: int = 10_000,
        progress: bool = False,
        **options: Unpack[_SweepOptions],
    ) -> list[str]:
        """The same sweep written by the workers as Parquet shards, one per
        chunk (`path/part-00000.parquet`, ...); returns their paths."""

distributed: _Distributed
"""Sweeps on a Dask cluster: `distributed.sweep(...)` and
`distributed.to_parquet(...)`."""

class CraneError(ValueError):
    """A run the tool could not make, or an argument it refuses: the tool's one-line message."""

class CraneWarning(UserWarning):
    """What the audit found in a run, one warning per finding (`Run.warnings`
    lists them too); filter them, or make them errors, with `warnings`."""

@final
class Run:
    """One run: its states (float64, one row per step), the names of their
    columns, the summary (summary.json as a dict) and what the audit found.
    Its attributes are read-only."""

    @property
    def t(self) -> npt.NDArray[np.float64]:
        """Times, s: shape (steps + 1,)."""
    @property
    def q(self) -> npt.NDArray[np.float64]:
        """Coordinates: shape (steps + 1, n), columns `coordinates`."""
    @property
    def v(self) -> npt.NDArray[np.float64]:
        """Velocities: shape (steps + 1, n), columns `coordinates`."""
    @property
    def u(self) -> npt.NDArray[np.float64]:
        """Inputs: shape (steps + 1, a), columns `inputs`."""
    @property
    def lambda_(self) -> npt.NDArray[np.float64]:
        """Multipliers: shape (steps + 1, m)."""
    @property
    def tensions(self) -> npt.NDArray[np.float64]:
        """Rope tensions, N: shape (steps + 1, ropes), columns `ropes`."""
    @property
    def coordinates(self) -> list[str]:
        """The names of the coordinates."""
    @property
    def inputs(self) -> list[str]:
        """The names of the inputs."""
    @property
    def ropes(self) -> list[str]:
        """The names of the rope tensions."""
    @property
    def summary(self) -> dict[str, Any]:
        """The summary `crane run` writes as summary.json."""
    @property
    def warnings(self) -> list[str]:
        """What the audit found: empty for a trustworthy run."""
    @property
    def replay(self) -> Optional[dict[str, Any]]:
        """With replay=True: the forward run of the computed inputs, a dict of
        `t`, `q`, `v`, `u`, `lambda_`, `tensions` (numpy arrays); else None."""
    def __new__(
        cls,
        t: npt.NDArray[np.float64],
        q: npt.NDArray[np.float64],
        v: npt.NDArray[np.float64],
        u: npt.NDArray[np.float64],
        lambda_: npt.NDArray[np.float64],
        tensions: npt.NDArray[np.float64],
        coordinates: list[str],
        inputs: list[str],
        ropes: list[str],
        summary: dict[str, Any],
        warnings: list[str],
        replay: Optional[dict[str, Any]] = None,
    ) -> Self:
        """A run from its parts (what unpickling calls); raises CraneError
        where an array's shape does not match `t` and the names."""
    def to_csv(self, target: Union[str, PathLike[str], IO[str]]) -> None:
        """Write the run as `crane run` writes results.csv (without the
        crane's derived outputs): to a path, whole or not at all, refusing a
        symbolic link, folder, FIFO or device there (CraneError); or through
        a file object's write()."""
    def to_dataframe(self) -> Any:
        """The run as a pandas DataFrame (`t` the index, the columns of
        `to_csv`, values copied); pandas is optional: ImportError without it."""

@final
class Stepper:
    """A crane one step at a time, from the start `run` takes; its steps are
    the run's, bit for bit. A state is a dict of `t` (float) and numpy
    arrays `q`, `v`, `u`, `lambda_`, `tensions`."""

    def __new__(
        cls,
        model: str,
        *,
        dt: Optional[float] = None,
        scheme: Optional[str] = None,
        formulation: Optional[str] = None,
        scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
        parameters: Optional[Mapping[str, float]] = None,
    ) -> Self:
        """The same as `stepper(model, ...)`; raises CraneError."""

    @property
    def dt(self) -> float:
        """The time step, s."""
    @property
    def state(self) -> dict[str, Any]:
        """The state after the last step (the start before the first)."""
    @property
    def warnings(self) -> list[str]:
        """What the step audit (the FMU's) found so far, each also warned of as a
        CraneWarning when found."""
    def __reduce__(self) -> Any:
        """Refused: a TypeError that says why (a run under way does not pickle)."""
    def step(self) -> dict[str, Any]:
        """One step; the new state. Raises CraneError if it fails."""
    def step_to(self, t: float) -> dict[str, Any]:
        """Advance to the step at `t` (a step time not before the current one, at most 1e9 steps
        on); the state there. Ctrl-C stops it between steps (KeyboardInterrupt); other
        threads run while it steps (it releases the GIL)."""

def models() -> list[dict[str, Any]]:
    """The built-in cranes: name, description, sizes n, m, a, reference,
    minimal, path_order, formulation (the default) and internal_dimension."""

def run(
    model: str,
    *,
    dt: Optional[float] = None,
    tf: Optional[float] = None,
    scheme: Optional[str] = None,
    formulation: Optional[str] = None,
    scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
    parameters: Optional[Mapping[str, float]] = None,
    limits: Optional[Mapping[str, float]] = None,
    replay: bool = False,
    plant: Optional[Mapping[str, float]] = None,
    feedback: Union[str, tuple[float, float], None] = None,
    settle: Optional[float] = None,
) -> Run:
    """Run `model` as `crane run` does (see the module's docs); raises CraneError."""

def stepper(
    model: str,
    *,
    dt: Optional[float] = None,
    scheme: Optional[str] = None,
    formulation: Optional[str] = None,
    scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
    parameters: Optional[Mapping[str, float]] = None,
) -> Stepper:
    """A Stepper of `model` (formulations `redundant`, `dummy-derivative` and
    `state-selection`); raises CraneError."""

def fastest(
    model: str,
    *,
    limits: Optional[Mapping[str, float]] = None,
    min_tension: Optional[Mapping[str, float]] = None,
    scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
    parameters: Optional[Mapping[str, float]] = None,
    scheme: Optional[str] = None,
    dt: Optional[float] = None,
    tolerance: Optional[float] = None,
    shape: Literal["time-scaled", "optimal"] = "time-scaled",
    control_points: Optional[int] = None,
) -> dict[str, Any]:
    """The shortest feasible duration as `crane fastest` finds it: the dict
    of fastest.json with `run`, the run at the answer (a dict of arrays),
    and `scenario`, the answer's scenario keys (`run(model,
    scenario=...)` runs it); `shape="optimal"` optimises the path's shape
    with the duration (`control_points` per load coordinate, 20 by
    default); raises CraneError."""

def sweep(
    model: str,
    grid: Optional[Mapping[str, _Floats]] = None,
    *,
    durations: Optional[_Floats] = None,
    limits: Optional[Mapping[str, float]] = None,
    min_tension: Optional[Mapping[str, float]] = None,
    scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
    parameters: Optional[Mapping[str, float]] = None,
    scheme: Optional[str] = None,
    dt: Optional[float] = None,
) -> dict[str, Any]:
    """Every combination of `grid` and `durations` as `crane sweep` runs it:
    sweep.csv's columns (float64 and bool arrays, lists of strings for
    `error` and `audit`); raises CraneError."""

def sweep_points(
    model: str,
    points: Mapping[str, _Floats],
    *,
    durations: Optional[_Floats] = None,
    limits: Optional[Mapping[str, float]] = None,
    min_tension: Optional[Mapping[str, float]] = None,
    scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
    parameters: Optional[Mapping[str, float]] = None,
    scheme: Optional[str] = None,
    dt: Optional[float] = None,
) -> dict[str, Any]:
    """Any set of points (`points`: each swept parameter's values, one per
    point, as equal-length arrays or a pandas DataFrame; `durations`: each
    point's, the move's own if None): `sweep`'s columns in the order of the
    points; raises CraneError before any run on a bad set."""

def convergence(
    model: str,
    *,
    dts: Optional[_Floats] = None,
    scheme: Optional[str] = None,
    formulation: Optional[str] = None,
    scenario: Union[str, PathLike[str], Mapping[str, Any], None] = None,
    parameters: Optional[Mapping[str, float]] = None,
) -> dict[str, Any]:
    """The error of u at t = 1.5 s for each step as `crane convergence`
    measures it: arrays `dt`, `e_u`, `order`, the list `audit`, and
    `reference`, `formulation`, `scheme`; raises CraneError."""
