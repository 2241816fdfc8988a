"""The Python package against the conformance corpus, and its behaviour on bad input."""

import json
import math
import os
import subprocess
import sys
from array import array
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

import rotlang

# The corpus lives beside the project (`../shared/conformance/` from the repository root).
CORPUS = Path(
    os.environ.get(
        "ROTLANG_CONFORMANCE",
        Path(__file__).resolve().parents[3] / ".." / "shared" / "conformance",
    )
)


def _lines(name):
    with open(CORPUS / name, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


MODELS = {
    name: rotlang.Model.from_heights(
        m["layer_heights"], m["layer_height"], m["bottom_shell_layers"], m["top_shell_layers"]
    )
    for name, m in json.loads((CORPUS / "models.json").read_text(encoding="utf-8")).items()
}
CASES = _lines("cases.jsonl")


def close(got, expected):
    if expected is None:  # OrcaSlicer's angle is NaN there; rotlang's is finite
        return math.isfinite(got)
    if abs(expected) > 1e9:
        return abs(got - expected) <= 1e-9 * abs(expected)
    d = math.fmod(abs(got - expected), 360.0)
    return min(d, 360.0 - d) <= 1e-4


def test_every_exact_case_in_the_rotlang_dialect():
    assert len(CASES) >= 1500
    failures = []
    for case in CASES:
        e = rotlang.evaluate_layers(case["template"], MODELS[case["model"]])
        fills = case.get("fills") or ["sparse"] * len(case["degrees"])
        if len(e.angles) != len(case["degrees"]) or e.fills != fills or e.findings:
            failures.append(case)
            continue
        if not all(close(g, x) for g, x in zip(e.angles, case["degrees"])):
            failures.append(case)
    assert not failures, f"{len(failures)} cases differ, first: {failures[0]}"


def test_every_exact_case_in_the_orcaslicer_dialect():
    failures = []
    for case in CASES:
        orca = case["orcaslicer"]
        expected = case["degrees"] if orca["status"] == "same" else orca["degrees"]
        e = rotlang.evaluate_layers(case["template"], MODELS[case["model"]], dialect="orcaslicer")
        codes = {f.code for f in e.findings}
        if orca["status"] in ("hangs", "nan") and f"orcaslicer::{orca['status']}" not in codes:
            failures.append((case, "finding"))
        if len(e.angles) != len(expected):
            failures.append((case, f"{len(e.angles)} angles for {len(expected)} layers"))
        elif not all(close(g, x) for g, x in zip(e.angles, expected)):
            failures.append((case, "angles"))
    assert not failures, f"{len(failures)} cases differ, first: {failures[0]}"


def test_random_cases_stay_in_bounds_and_follow_the_seed():
    for case in _lines("cases-random.jsonl"):
        model = MODELS[case["model"]]
        a = rotlang.expand(case["template"], model, seed=7)
        assert a == rotlang.expand(case["template"], model, seed=7)
        assert len(a) == len(case["min_degrees"]) == len(case["max_degrees"]), case["template"]
        for got, lo, hi in zip(a, case["min_degrees"], case["max_degrees"]):
            assert lo - 1e-4 <= got <= hi + 1e-4, case["template"]


def test_expand_returns_a_list_or_an_array_of_doubles():
    angles = rotlang.expand("5, 10!, +20")
    assert isinstance(angles, list) and len(angles) == 100
    assert angles[:7] == [5, 10, 30, 5, 25, 5, 25]
    packed = rotlang.expand("5, 10!, +20", array=True)
    assert isinstance(packed, array) and packed.typecode == "d"
    assert list(packed) == angles
    assert rotlang.expand("5, 10!, +20", base=45)[:2] == [50, 55]


def test_models():
    m = rotlang.Model.uniform(10, 0.2, first_layer_height=0.3, bottom_shells=2, top_shells=5)
    assert len(m) == 10 and m.bottom_shells == 2 and m.top_shells == 5
    assert abs(m.height - 2.1) < 1e-9
    assert len(rotlang.Model.from_total_height(20.0)) == 100
    for bad in ([], [0.2, float("nan")], [0.2, -0.2], [0.2, 0.0]):
        with pytest.raises(ValueError):
            rotlang.Model.from_heights(bad, 0.2)
    with pytest.raises(ValueError):
        rotlang.Model.uniform(0)
    with pytest.raises(ValueError):
        rotlang.Model.uniform(10, float("inf"))
    with pytest.raises(ValueError):
        rotlang.Model.uniform(-1)


# Out-of-range integers raise ValueError with the allowed range (the wording of
# rotlang::eval::limits, which the JavaScript binding shares), never OverflowError.
@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: rotlang.Model.uniform(-1), "`layers` must be a whole number from 1 to 100000000, not -1"),
        (lambda: rotlang.Model.uniform(0), "`layers` must be a whole number from 1 to 100000000, not 0"),
        (lambda: rotlang.Model.uniform(10**30), f"`layers` must be a whole number from 1 to 100000000, not {10**30}"),
        (lambda: rotlang.Model.uniform(10**50), f"`layers` must be a whole number from 1 to 100000000, not {10**50}"),
        (lambda: rotlang.Model.uniform(10, bottom_shells=-1), "`bottom_shells` must be a whole number from 0 to 4294967295, not -1"),
        (lambda: rotlang.Model.uniform(10, top_shells=2**40), "`top_shells` must be a whole number from 0 to 4294967295, not 1099511627776"),
        (lambda: rotlang.Model.from_heights([0.2], 0.2, top_shells=-3), "`top_shells` must be a whole number from 0 to 4294967295, not -3"),
        (lambda: rotlang.Model.from_total_height(2.0, bottom_shells=2**32), "`bottom_shells` must be a whole number from 0 to 4294967295, not 4294967296"),
        (lambda: rotlang.expand("+10~90", seed=-1), "`seed` must be a whole number from 0 to 18446744073709551615, not -1"),
        (lambda: rotlang.expand("+10~90", seed=2**64), "`seed` must be a whole number from 0 to 18446744073709551615, not 18446744073709551616"),
        (lambda: rotlang.evaluate_layers("+10", seed=-5), "`seed` must be a whole number from 0 to 18446744073709551615, not -5"),
        (lambda: rotlang.expand("0, 90", base=2e300), "`base` must be a finite number of degrees within ±1000000000, not 2e300"),
        (lambda: rotlang.expand("0, 90", base=2e300, dialect="orcaslicer"), "`base` must be a finite number of degrees within ±1000000000, not 2e300"),
    ],
)
def test_out_of_range_numbers_raise_value_error_with_the_range(call, message):
    with pytest.raises(ValueError) as caught:
        call()
    assert not isinstance(caught.value, OverflowError)
    assert str(caught.value) == message


def test_the_ends_of_the_ranges_are_taken():
    assert len(rotlang.Model.uniform(1)) == 1
    m = rotlang.Model.uniform(3, bottom_shells=0, top_shells=2**32 - 1)
    assert (m.bottom_shells, m.top_shells) == (0, 2**32 - 1)
    assert rotlang.expand("+10~90", seed=2**64 - 1) == rotlang.expand("+10~90", seed=2**64 - 1)
    assert rotlang.expand("0", rotlang.Model.uniform(1), base=-1e9) == [-1e9]
    with pytest.raises(TypeError):
        rotlang.expand("0", seed=1.5)


def test_check_gives_code_point_and_byte_offsets():
    text = "+30°, X"
    d = rotlang.check(text)
    assert [x.code for x in d] == ["rotlang::degree-sign", "rotlang::unknown-sign"]
    assert text[d[0].start : d[0].end] == "°" and (d[0].byte_start, d[0].byte_end) == (3, 5)
    assert text[d[1].start : d[1].end] == "X" and (d[1].byte_start, d[1].byte_end) == (7, 8)
    assert d[1].severity == "error" and d[0].help
    assert rotlang.check("+10, -10") == []


def test_bad_templates_raise_with_their_diagnostics():
    with pytest.raises(rotlang.TemplateError) as caught:
        rotlang.expand("+30°, X")
    assert [d.code for d in caught.value.diagnostics][:1] == ["rotlang::degree-sign"]
    assert "rotlang::degree-sign" in str(caught.value)
    with pytest.raises(rotlang.TemplateError):
        rotlang.format("+10X")
    with pytest.raises(ValueError):
        rotlang.expand("+10", dialect="prusa")
    with pytest.raises(ValueError):
        rotlang.check("+10", target="dense")
    with pytest.raises(ValueError):
        rotlang.expand("+10", base=float("nan"))
    # A lone surrogate cannot become UTF-8: an exception, not a crash.
    with pytest.raises(UnicodeEncodeError):
        rotlang.check("+10\ud800")
    # Huge and hostile texts come back with diagnostics.
    assert rotlang.check("+" * 100_000)
    assert rotlang.check("\x00\n\t𝕏" * 1000)


def test_format_and_format_angle():
    assert rotlang.format("5 ,10!,+20") == "5, 10!, +20"
    assert rotlang.format_angle(370.1) == "10.1"
    assert rotlang.format_angle(0.1 + 0.2) == "0.3"
    assert rotlang.format_angle(-1e-12) == "0"


def test_explain_describes_each_instruction():
    words = rotlang.explain("+10/5mm, -10", rotlang.Model.uniform(50, 0.2))
    assert "+10/5mm" in words and "-10" in words and "50 layers" in words
    assert rotlang.explain("+30°") != rotlang.explain("+30")  # the error is mentioned
    doc = rotlang.explain_code("unknown-sign")
    assert doc["code"] == "rotlang::unknown-sign" and doc["severity"] == "error" and doc["fix"]
    assert rotlang.explain_code("rotlang::no-such-code") is None


def test_one_template_from_many_threads():
    model = rotlang.Model.uniform(20_000, 0.2, 0.3)
    text = "5, 10!, +20, +10L25%, -10~50, #3, +45Z10mm"
    expected = rotlang.expand(text, model, array=True)
    with ThreadPoolExecutor(max_workers=8) as pool:
        results = list(pool.map(lambda _: rotlang.expand(text, model, array=True), range(32)))
    assert all(r == expected for r in results)


def test_check_of_a_long_template_costs_at_most_16_times_its_text():
    # Issue 22: `check` built the whole IR, 40x the text (54x for this one). Measured in
    # a child of its own (its rusage from wait4 is its alone); the template is made there,
    # so the text and its copies are in the measure.
    size = 8 << 20
    script = (
        "import rotlang\n"
        f"text = ('0/5, 400, ' * {size // 10})\n"
        "assert rotlang.check(text, 'sparse')\n"
    )
    child = subprocess.Popen([sys.executable, "-c", script])
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    assert child.returncode == 0
    assert usage.ru_maxrss * 1024 <= 16 * size, f"{usage.ru_maxrss} kB for {size} bytes"
