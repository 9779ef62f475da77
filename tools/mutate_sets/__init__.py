"""The fault sets of tools/mutate.py: one module per set, each defining SET (a FaultSet).

A fault is one exact text replacement (file, old text, new text) that must match once in its file;
a set adds the test binary that runs against its faults: the test files it holds, the Catch2 test
spec it runs, the libraries it links and whether it needs the `affray` program (the golden cases and
the CLI tests run it).
"""

import dataclasses


@dataclasses.dataclass(frozen=True)
class Fault:
    name: str
    file: str
    old: str
    new: str
    what: str
    # Why the fault cannot change any result, if it cannot: then it is not counted.
    equivalent: str = ""


@dataclasses.dataclass(frozen=True)
class FaultSet:
    name: str
    what: str
    # The test files of the set's binary (besides tests/main.cpp), relative to the repository.
    test_sources: list
    # Catch2's test spec, run for every mutant (a comma is "or").
    test_spec: str
    # The libraries the binary links: the fewer, the less a mutant of a header rebuilds.
    libraries: list
    faults: list
    # Whether the tests run the `affray` program (AFFRAY_CLI): it is then rebuilt for every mutant.
    cli: bool = False

    @property
    def target(self):
        return f"affray_mutate_{self.name}"


# The sets, in the order `--set all` runs them.
NAMES = ["derivatives", "compiler", "numbers", "intersector"]


def load(name):
    import importlib

    return importlib.import_module(f"mutate_sets.{name}").SET


def all_sets():
    return [load(n) for n in NAMES]
