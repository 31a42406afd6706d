"""Type stubs of the Rust extension (python/src/lib.rs); the package's API is `reconfig`."""

from typing import Dict, List, Optional, Union

Column = Union[List[int], List[Optional[float]], List[str], List[Optional[bool]], List[Optional[int]], List[float]]

def solve_text(name: str, fixture_text: str) -> Dict[str, Column]: ...
def campaign(
    name: str,
    fixture_text: str,
    cases: int,
    disperse: List[str],
    uniform: List[str],
    seed: int,
    threads: int,
) -> Dict[str, Column]: ...
def case_text(
    name: str,
    fixture_text: str,
    disperse: List[str],
    uniform: List[str],
    seed: int,
    case: int,
) -> str: ...
