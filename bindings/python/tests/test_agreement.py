"""The bindings' agreement table (bindings/agreement/cases.json): Python gives exactly the
angles, the error kind and the message that the table (and so the C ABI and JavaScript,
whose suites run the same table) gives."""

import json
import math
from pathlib import Path

import pytest

import rotlang

TABLE = json.loads((Path(__file__).parents[2] / "agreement" / "cases.json").read_text("utf-8"))
CASES = [c for c in TABLE["cases"] if "python" in c.get("only", ["python"])]
NUMBERS = {"NaN": math.nan, "inf": math.inf, "-inf": -math.inf}
KINDS = {rotlang.OptionsError: "options", rotlang.ModelError: "model", rotlang.TemplateError: "template"}


def num(v):
    return NUMBERS.get(v, v) if isinstance(v, str) else v


def model(spec):
    if spec is None:
        return None
    shells = {k: spec[k] for k in ("bottom_shells", "top_shells") if k in spec}
    if "heights" in spec:
        return rotlang.Model.from_heights([num(h) for h in spec["heights"]], num(spec["layer_height"]), **shells)
    first = num(spec.get("first_layer_height"))
    if "layers" in spec:
        return rotlang.Model.uniform(spec["layers"], num(spec.get("layer_height", 0.2)), first, **shells)
    return rotlang.Model.from_total_height(num(spec["height"]), num(spec.get("layer_height", 0.2)), first, **shells)


def run(case):
    options = {k: num(case[k]) for k in ("base", "seed", "dialect", "target") if k in case}
    return rotlang.expand(case["template"], model(case.get("model")), **options)


def test_the_table_has_the_cases_every_binding_runs():
    assert len(CASES) >= 30


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_agreement(case):
    expect = case["expect"]
    if "error" in expect:
        with pytest.raises((ValueError, rotlang.TemplateError)) as caught:
            run(case)
        kind = next(k for cls, k in KINDS.items() if isinstance(caught.value, cls))
        assert kind == expect["error"]
        if kind != "template":
            assert str(caught.value) == expect.get("python_message", expect["message"])
    else:
        angles = run(case)
        assert len(angles) == expect["count"]
        assert angles[: len(expect["head"])] == expect["head"]
        assert angles[-1] == expect["last"]


PROFILES = json.loads((Path(__file__).parents[2] / "agreement" / "profiles.json").read_text("utf-8"))["cases"]


@pytest.mark.parametrize("case", PROFILES, ids=[c["name"] for c in PROFILES])
def test_profile_agreement(case):
    content = bytes(case["bytes"]) if "bytes" in case else case["content"]
    expect = case["expect"]
    if "error" in expect:
        with pytest.raises(rotlang.ProfileError) as caught:
            rotlang.read_profile(case["file"], content)
        assert isinstance(caught.value, ValueError)
        assert str(caught.value) == expect["message"]
        return
    p = rotlang.read_profile(case["file"], content)
    m = p["model"]
    assert {
        "kind": p["kind"],
        "templates": [[t["key"], t["target"], t["text"], t["base"]] for t in p["templates"]],
        "model": {
            "layers": len(m),
            "layer_height": m.layer_height,
            "first_layer_height": p["first_layer_height"],
            "bottom_shells": m.bottom_shells,
            "top_shells": m.top_shells,
        },
        "base": p["base"],
        "has_errors": p["has_errors"],
    } == expect
    # The model is one to evaluate on.
    assert len(rotlang.expand("+10", m)) == len(m)
