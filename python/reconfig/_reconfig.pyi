"""Type stubs of the Rust extension (python/src/lib.rs); the package's API is `reconfig`."""

from typing import Any, Dict, List, Optional, Tuple, Union

Column = Union[List[int], List[Optional[float]], List[str], List[Optional[bool]], List[Optional[int]], List[float]]

def solve_text(name: str, fixture_text: str) -> Tuple[Dict[str, Column], Optional[Dict[str, Any]]]: ...
def campaign(
    name: str,
    fixture_text: str,
    cases: int,
    disperse: List[str],
    uniform: List[str],
    seed: int,
    threads: int,
    first: int,
    count: int,
    table: bool,
    times: bool,
    progress: bool,
) -> Tuple[Dict[str, Column], Optional[str]]: ...
def case_text(
    name: str,
    fixture_text: str,
    disperse: List[str],
    uniform: List[str],
    seed: int,
    case: int,
) -> str: ...
def toml_from_json(json_text: str) -> str: ...
def json_from_toml(text: str) -> str: ...
