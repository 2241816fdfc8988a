"""Check, expand, explain and format infill rotation templates (rotlang)."""

from array import array
from typing import Dict, List, Literal, Optional, Sequence, Union, overload

__version__: str
DIALECTS: List[str]

Target = Literal["sparse", "solid"]
DialectName = Literal["rotlang", "orcaslicer"]

class TemplateError(Exception):
    """The template has errors. ``args == (message, diagnostics)``."""

    diagnostics: List["Diagnostic"]

class OptionsError(ValueError):
    """A target, dialect, base or seed rotlang cannot take (the message names it)."""

class ModelError(ValueError):
    """A model rotlang cannot take: no layers, a bad height, a count out of range."""

class ProfileError(ValueError):
    """A profile file that cannot be read at all (not UTF-8, ...)."""

class Diagnostic:
    code: str
    severity: Literal["error", "warning"]
    message: str
    help: Optional[str]
    start: int
    """Code-point offset of the primary span: ``text[start:end]``."""
    end: int
    byte_start: int
    """UTF-8 byte offset of the same span."""
    byte_end: int

class Finding:
    code: Literal["orcaslicer::hangs", "orcaslicer::undefined", "orcaslicer::nan"]
    message: str
    first_layer: int
    layers: int

class Model:
    @staticmethod
    def uniform(
        layers: int,
        layer_height: float = 0.2,
        first_layer_height: Optional[float] = None,
        bottom_shells: int = 3,
        top_shells: int = 4,
    ) -> "Model": ...
    @staticmethod
    def from_heights(
        heights: Sequence[float], layer_height: float, bottom_shells: int = 3, top_shells: int = 4
    ) -> "Model": ...
    @staticmethod
    def from_total_height(
        height: float,
        layer_height: float = 0.2,
        first_layer_height: Optional[float] = None,
        bottom_shells: int = 3,
        top_shells: int = 4,
    ) -> "Model": ...
    @staticmethod
    def cube20() -> "Model": ...
    def __len__(self) -> int: ...
    @property
    def layer_height(self) -> float: ...
    @property
    def bottom_shells(self) -> int: ...
    @property
    def top_shells(self) -> int: ...
    @property
    def height(self) -> float: ...

class Expansion:
    angles: Union[List[float], "array[float]"]
    fills: List[Literal["sparse", "dense", "solid", "concentric", "monotonic", "rectilinear"]]
    findings: List[Finding]

def check(template: str, target: Target = "sparse") -> List[Diagnostic]: ...
@overload
def expand(
    template: str,
    model: Optional[Model] = None,
    *,
    base: float = 0.0,
    seed: int = 0,
    target: Target = "sparse",
    dialect: DialectName = "rotlang",
    array: Literal[False] = False,
) -> List[float]: ...
@overload
def expand(
    template: str,
    model: Optional[Model] = None,
    *,
    base: float = 0.0,
    seed: int = 0,
    target: Target = "sparse",
    dialect: DialectName = "rotlang",
    array: Literal[True],
) -> "array[float]": ...
def evaluate_layers(
    template: str,
    model: Optional[Model] = None,
    *,
    base: float = 0.0,
    seed: int = 0,
    target: Target = "sparse",
    dialect: DialectName = "rotlang",
    array: bool = False,
) -> Expansion: ...
def format(template: str, target: Target = "sparse") -> str: ...
def format_angle(degrees: float) -> str: ...
def explain(template: str, model: Optional[Model] = None, target: Target = "sparse") -> str: ...
def explain_code(code: str) -> Optional[Dict[str, str]]:
    """``code``, ``severity``, ``summary``, ``explanation``, ``example``, ``fix``."""

def read_profile(name: str, content: Union[str, bytes]) -> Dict[str, object]:
    """The templates, model and direction of a profile file (``.json``, ``.jsonc``, ``.ini``,
    ``.rot``): ``kind``, ``templates`` (dicts: ``key``, ``object``, ``target``, ``text``,
    ``base``), ``model`` (a ``Model``), ``first_layer_height``, ``base``, ``notes`` (dicts:
    ``message``, ``error``), ``has_errors``. Raises ProfileError for an unreadable file."""
