"""The experiment's keywords come from the library's key table (``_core.KEYS``): every key is
accepted under its Python spelling and refused out of range with the table's words, and the
keyword types of the stubs (``_core.pyi``) are generated from the table, so that a new key is
one row of the library's table.

``STICKSLIP_BLESS=1`` rewrites the generated part of the stubs."""

from __future__ import annotations

import inspect
import math
import os
import pathlib
import re
from typing import Any, Dict, List

import pytest

import stickslip
from stickslip import Experiment, _core

STUBS = pathlib.Path(__file__).resolve().parents[1] / "python" / "stickslip" / "_core.pyi"
BEGIN = ("# BEGIN keywords: generated from the library's key table by tests/test_keys.py "
         "(STICKSLIP_BLESS=1 rewrites)\n")
END = "# END keywords\n"
#: The constructors that take any key beside their own (``**keys``), and the name of the
#: stubs' TypedDict of their keys.
KEYWORD_METHODS = {"paper": "_PaperKeys", "circuit": "_CircuitKeys",
                   "shockley": "_ShockleyKeys", "mechanics": "_MechanicsKeys",
                   "replace": "_ExperimentKeys"}


def keywords() -> Dict[str, Dict[str, Any]]:
    """Every Python keyword of an experiment key, with the key's row of the table."""
    return {keyword: row for row in _core.KEYS for keyword in [row["name"], *row["name_aliases"]]}


def numeric(row: Dict[str, Any]) -> bool:
    """Whether the key holds a number (the others hold a name: the diode law, a preset)."""
    return row["form"] != "choice"


def named_parameters(method: str) -> List[str]:
    """The keywords that ``Experiment.<method>`` names in its signature."""
    parameters = inspect.signature(getattr(Experiment, method)).parameters.values()
    return [p.name for p in parameters
            if p.kind is not inspect.Parameter.VAR_KEYWORD and p.name != "self"]


def generated() -> str:
    """The stubs' TypedDicts of keywords, from the table."""
    out = [BEGIN]
    every = keywords()
    for method, typed_dict in KEYWORD_METHODS.items():
        own = set(named_parameters(method))
        out.append(f"class {typed_dict}(TypedDict, total=False):\n")
        what = ("every experiment key" if method == "replace"
                else f"the keys of Experiment.{method} beside its own")
        out.append(f'    """{what[0].upper()}{what[1:]}."""\n\n')
        for keyword, row in every.items():
            if keyword in own:
                continue
            kind = "_Value" if numeric(row) else "Optional[str]"
            out.append(f"    {keyword}: {kind}  # {row['description']}\n")
        out.append("\n")
    out.append(END)
    return "".join(out)


def test_the_stubs_keywords_are_the_key_table():
    text = STUBS.read_text()
    start, end = text.index(BEGIN), text.index(END) + len(END)
    expected = generated()
    if os.environ.get("STICKSLIP_BLESS") == "1":
        STUBS.write_text(text[:start] + expected + text[end:])
        text = STUBS.read_text()
        start, end = text.index(BEGIN), text.index(END) + len(END)
    assert text[start:end] == expected, (
        "the stubs' keywords differ from the library's key table: regenerate them with "
        "STICKSLIP_BLESS=1 pytest crates/stickslip-py/tests/test_keys.py")


def test_every_named_keyword_is_a_key():
    every = keywords()
    for method in ("__new__", *KEYWORD_METHODS):
        if method == "__new__":
            names = [p for p in inspect.signature(Experiment).parameters]
        else:
            names = named_parameters(method)
        for name in names:
            assert name in every, f"Experiment.{method} names {name!r}, which is not a key"


def test_the_class_docstring_lists_every_keyword():
    doc = Experiment.__doc__ or ""
    listed = set(re.findall(r"\w+", doc[doc.index("Keyword names are"):doc.index("Physical values")]))
    for keyword in keywords():
        assert keyword in listed, f"{keyword} is not in the class docstring's list of keywords"


def outside(row: Dict[str, Any]) -> float:
    """A value out of the key's range (NaN for a key whose only rule is to be finite)."""
    low, high = row["min"], row["max"]
    if low is not None:
        return low - 1 - abs(low)
    if high is not None:
        return high + 1 + abs(high)
    return float("nan")


def inside(row: Dict[str, Any]) -> Any:
    """A value the key takes: its default, else one in its range."""
    if not numeric(row):
        return row["choices"][0]
    if isinstance(row["default"], (int, float)):
        return row["default"]
    low, high = row["min"], row["max"]
    if low is None:
        return 0.0 if high is None or high > 0 else high - 1
    if high is None or low + 1 <= high:
        return low + 1
    return (low + high) / 2


@pytest.mark.parametrize("keyword", sorted(keywords()))
def test_every_key_is_refused_out_of_range_with_the_tables_words(keyword):
    row = keywords()[keyword]
    if not numeric(row):
        with pytest.raises(ValueError, match=f"^invalid {keyword} 'no-such-name': must be "):
            Experiment.from_dict({keyword: "no-such-name"})
        return
    value = outside(row)
    given: List[Any] = [value, repr(value)] if math.isfinite(value) else [value]
    for v in given:
        with pytest.raises(ValueError) as raised:
            Experiment.from_dict({keyword: v})
        message = str(raised.value)
        assert message.startswith(f"invalid {row['name']} = "), message
        assert message.endswith(f": {row['allowed']}"), message


@pytest.mark.parametrize("keyword", sorted(keywords()))
def test_every_key_is_accepted_under_its_python_spelling(keyword):
    row = keywords()[keyword]
    value = inside(row)
    base = Experiment.paper(w=0.7, beta=1.2)
    builds = (lambda: base.replace(**{keyword: value}),
              lambda: Experiment.from_dict({keyword: value}))
    for build in builds:
        try:
            changed = build()
        except ValueError as e:
            # A key that does not fit the description (a mass in a circuit, a mass alone) is
            # refused with the description as a whole, never for its spelling or its value;
            # an unknown keyword would be a TypeError.
            assert not str(e).startswith(f"invalid {row['name']} "), e
            continue
        assert Experiment.from_dict(changed.to_dict()) == changed
