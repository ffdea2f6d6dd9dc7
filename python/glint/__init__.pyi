# Type stubs of the glint package (docs/python.md). Kept beside __init__.py; tests/python checks
# that every public name and parameter here matches the module.
import os
import threading
from typing import Any, Iterator, Mapping, NamedTuple, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, os.PathLike[str]]
SceneLike = Union["Scene", PathLike, Mapping[str, Any], None]

class GlintError(RuntimeError): ...

class Diagnostic(NamedTuple):
    file: str
    line: int
    column: int
    message: str

class SceneError(GlintError):
    diagnostics: list[Diagnostic]
    file: str
    line: int
    column: int
    message: str
    def __init__(self, text: str, diagnostics: Sequence[tuple[str, int, int, str]] = ...) -> None: ...

class Scene:
    name: str
    @property
    def objects(self) -> int: ...
    @property
    def lights(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...

class Image(np.ndarray):
    aovs: dict[str, npt.NDArray[np.float32]]
    spp: int
    complete: bool
    interrupted: bool
    metadata: dict[str, str]
    notes: list[str]
    display: dict[str, Any]
    def _repr_png_(self) -> bytes: ...
    def save(self, path: PathLike) -> None: ...

def load(path: PathLike, *, strict: bool = ..., frame: float = ..., camera: str = ...) -> Scene: ...
def load_dict(scene: Mapping[str, Any], *, name: str = ..., frame: float = ...) -> Scene: ...
def render(
    scene: SceneLike = ...,
    *,
    spp: int | None = ...,
    width: int | None = ...,
    height: int | None = ...,
    threads: int | None = ...,
    seed: int | None = ...,
    max_depth: int | None = ...,
    aovs: Sequence[str] = ...,
    time: float | str | None = ...,
    denoise: bool = ...,
    noise_threshold: float | None = ...,
    min_spp: int | None = ...,
    checkpoint: PathLike | None = ...,
    checkpoint_every: str = ...,
    resume: PathLike | None = ...,
    accel: str | None = ...,
    light_sampler: str | None = ...,
    texture_filter: str | None = ...,
    progress: bool = ...,
    spectral: bool | None = ...,
) -> Image: ...
def render_passes(
    scene: SceneLike = ...,
    *,
    stop: threading.Event | None = ...,
    spp: int | None = ...,
    width: int | None = ...,
    height: int | None = ...,
    threads: int | None = ...,
    seed: int | None = ...,
    max_depth: int | None = ...,
    aovs: Sequence[str] = ...,
    time: float | str | None = ...,
    denoise: bool = ...,
    noise_threshold: float | None = ...,
    min_spp: int | None = ...,
    checkpoint: PathLike | None = ...,
    checkpoint_every: str = ...,
    resume: PathLike | None = ...,
    accel: str | None = ...,
    light_sampler: str | None = ...,
    texture_filter: str | None = ...,
    progress: bool = ...,
    spectral: bool | None = ...,
) -> Iterator[Image]: ...
def write(path: PathLike, image: npt.ArrayLike, *, metadata: Mapping[str, str] | None = ...) -> None: ...
def read(path: PathLike, *, linear: bool = ...) -> Image: ...
