"""The public Python API (pavefric.__all__) has numpydoc docstrings: a
Parameters section naming every parameter of the signature, with a type,
and a Returns section for a function that returns something."""
from __future__ import annotations

import inspect
import re

import pytest

import pavefric

SECTION = re.compile(r"^(\w[\w ]*)\n(-{3,})$", re.M)


def sections(doc: str) -> dict[str, str]:
    """numpydoc sections: title -> body (the text up to the next title)."""
    found = list(SECTION.finditer(doc))
    out = {}
    for i, m in enumerate(found):
        assert len(m[2]) == len(m[1]), f"underline of {m[1]!r} is not its length"
        end = found[i + 1].start() if i + 1 < len(found) else len(doc)
        out[m[1]] = doc[m.end():end]
    return out


def documented_parameters(body: str) -> dict[str, str]:
    """'name : type' lines at the section's left margin -> type."""
    out = {}
    for line in body.splitlines():
        if not line or line[0].isspace():
            continue
        name, _, kind = line.partition(" : ")
        out[name.strip()] = kind.strip()
    return out


def public_callables():
    for name in pavefric.__all__:
        obj = getattr(pavefric, name)
        if callable(obj):
            yield name, obj


def check(obj) -> list[str]:
    """What is wrong with obj's docstring (empty: nothing)."""
    doc = inspect.getdoc(obj)
    if not doc:
        return ["no docstring"]
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):       # an exception class: no signature
        return []
    params = [p for p in sig.parameters.values() if p.name not in ("self", "cls")]
    problems = []
    parts = sections(doc)
    if params:
        if "Parameters" not in parts:
            return ["no Parameters section"]
        documented = documented_parameters(parts["Parameters"])
        for p in params:
            key = {p.VAR_POSITIONAL: f"*{p.name}", p.VAR_KEYWORD: f"**{p.name}"}.get(
                p.kind, p.name)
            if key not in documented:
                problems.append(f"parameter {key} not in Parameters")
            elif p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD) and not documented[key]:
                problems.append(f"parameter {key} has no type")
        extra = set(documented) - {p.name for p in params} - \
            {f"*{p.name}" for p in params} - {f"**{p.name}" for p in params}
        problems += [f"Parameters names {e}, not in the signature" for e in sorted(extra)]
    if inspect.isfunction(obj) and sig.return_annotation not in (None, "None") \
            and "Returns" not in parts:
        problems.append("no Returns section")
    return problems


@pytest.mark.parametrize("name", [n for n, _ in public_callables()])
def test_public_callable_has_a_numpydoc_docstring(name):
    assert check(getattr(pavefric, name)) == []


def test_the_check_can_fail():
    def undocumented(a, b=1, *rest, **kw) -> int:
        """Something.

        Parameters
        ----------
        a : int
            A.
        c : float
            Not a parameter.
        """
        return 0

    assert check(undocumented) == ["parameter b not in Parameters",
                                   "parameter *rest not in Parameters",
                                   "parameter **kw not in Parameters",
                                   "Parameters names c, not in the signature",
                                   "no Returns section"]

    def untyped(a) -> None:
        """Something.

        Parameters
        ----------
        a
            A.
        """

    assert check(untyped) == ["parameter a has no type"]
    assert check(lambda x: x) == ["no docstring"]
    assert len(list(public_callables())) >= 20
