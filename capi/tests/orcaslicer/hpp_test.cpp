// include/rotlang.hpp from C++17: RAII, exceptions carrying diagnostics, models, ranges,
// the evaluator. Run by capi/tests/cpp.rs (plain and under valgrind).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rotlang.hpp"

static int failures = 0;
#define CHECK(cond)                                                                    \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            failures++;                                                                \
            std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                              \
    } while (0)

template <typename F>
static RotlangStatus status_of(F f) {
    try {
        f();
    } catch (const rotlang::Error& e) {
        return e.status();
    } catch (...) {
        return static_cast<RotlangStatus>(-1);  // anything but rotlang::Error
    }
    return ROTLANG_STATUS_OK;
}

static void run() {
    CHECK(rotlang::version().size() >= 5);

    // Parse and evaluate: the documentation's example on the 20 mm cube.
    rotlang::Template tpl(std::string_view("5, 10!, +20"));
    CHECK(!tpl.has_errors() && tpl.diagnostics().empty());
    auto cube = rotlang::Model::uniform(100, 0.2);
    std::vector<double> angles = tpl.angles(cube);
    CHECK(angles.size() == 100 && angles[0] == 5 && angles[1] == 10 && angles[2] == 30 && angles[4] == 25);

    // A range with the base direction; fills.
    rotlang::Options options;
    options.base = 45;
    rotlang::Expansion part = tpl.expand(cube, options, 2, 3);
    CHECK(part.angles == (std::vector<double>{75, 50, 70}) && part.fills.size() == 3 && part.findings.empty());
    rotlang::Template solid(std::string_view("+30, S2"));
    rotlang::Expansion s = solid.expand(rotlang::Model::from_heights({0.3, 0.2, 0.2, 0.2}, 0.2).shells(2, 2));
    CHECK(s.fills[0] == rotlang::Fill::Sparse && s.fills[1] == rotlang::Fill::Solid);

    // The evaluator, in any order, equals the batch.
    rotlang::Evaluator ev = tpl.evaluator(cube);
    for (size_t i : {99u, 3u, 50u, 0u, 51u}) CHECK(ev.layer(i).angle == angles[i]);
    CHECK(std::fabs(ev.layer(9).top - 2.0) < 1e-12);

    // A template with errors constructs; evaluating it throws with the diagnostics.
    rotlang::Template bad(std::string_view("+30°, X"));
    CHECK(bad.has_errors() && bad.diagnostics().size() == 2);
    CHECK(bad.diagnostics()[1].code == "rotlang::unknown-sign" && bad.diagnostics()[1].start == 7);
    try {
        bad.angles(cube);
        CHECK(false);
    } catch (const rotlang::Error& e) {
        CHECK(e.status() == ROTLANG_STATUS_TEMPLATE_HAS_ERRORS && e.diagnostics().size() == 2);
    }

    // Bad input: non-UTF-8, bad models, out of range.
    try {
        rotlang::Template t(std::string_view("+10\xff", 4));
        CHECK(false);
    } catch (const rotlang::Error& e) {
        CHECK(e.status() == ROTLANG_STATUS_INVALID_UTF8);
    }
    try {
        tpl.angles(rotlang::Model::from_heights({0.2, NAN}, 0.2));
        CHECK(false);
    } catch (const rotlang::Error& e) {
        CHECK(e.status() == ROTLANG_STATUS_INVALID_MODEL && std::string(e.what()).find("layer 1") != std::string::npos);
    }
    try {
        tpl.angles(rotlang::Model::from_heights({}, 0.2));
        CHECK(false);
    } catch (const rotlang::Error& e) {
        CHECK(e.status() == ROTLANG_STATUS_INVALID_MODEL);
    }
    try {
        ev.layer(100);
        CHECK(false);
    } catch (const rotlang::Error& e) {
        CHECK(e.status() == ROTLANG_STATUS_OUT_OF_RANGE);
    }

    // The OrcaSlicer dialect: any text, its defects as findings.
    rotlang::Options orca;
    orca.dialect = rotlang::Dialect::OrcaSlicer;
    rotlang::Expansion hang = rotlang::Template(std::string_view("10!, 5*")).expand(cube, orca);
    CHECK(hang.findings.size() == 1 && hang.findings[0].code == "orcaslicer::hangs" &&
          hang.findings[0].first_layer == 1 && hang.angles[99] == 10);
    rotlang::Evaluator orca_ev = bad.evaluator(cube, orca);
    CHECK(std::isfinite(orca_ev.layer(42).angle) && orca_ev.findings().empty());

    // Ranges at and past the top are OUT_OF_RANGE, never NULL_POINTER (an empty vector's
    // data()) or std::length_error (a vector sized from an unchecked count).
    CHECK(status_of([&] { tpl.expand(cube, {}, 100); }) == ROTLANG_STATUS_OUT_OF_RANGE);
    CHECK(status_of([&] { tpl.expand(cube, {}, 0, SIZE_MAX - 2); }) == ROTLANG_STATUS_OUT_OF_RANGE);
    CHECK(status_of([&] { tpl.expand(cube, {}, 98, 3); }) == ROTLANG_STATUS_OUT_OF_RANGE);
    CHECK(tpl.expand(cube, {}, 10, 0).angles.empty());
    CHECK(status_of([&] { tpl.expand(rotlang::Model::uniform(SIZE_MAX, 0.2)); }) == ROTLANG_STATUS_INVALID_MODEL);
    CHECK(status_of([&] { tpl.angles(rotlang::Model::uniform(SIZE_MAX, 0.2)); }) == ROTLANG_STATUS_INVALID_MODEL);

    // Bytes as OrcaSlicer reads them: "+30\xb0" is "+30°" in the OrcaSlicer dialect; the
    // rotlang dialect refuses text that is not UTF-8.
    auto latin1 = rotlang::Template::from_bytes(std::string_view("+30\xb0", 4));
    CHECK(latin1.has_errors() && latin1.diagnostics()[0].start == 3 && latin1.diagnostics()[0].end == 4);
    CHECK(latin1.expand(cube, orca, 0, 3).angles == (std::vector<double>{30, 60, 90}));
    CHECK(status_of([&] { latin1.angles(cube); }) == ROTLANG_STATUS_INVALID_UTF8);

    // Move semantics: the moved-to template works, the handle is freed once.
    rotlang::Template moved = std::move(tpl);
    CHECK(moved.angles(cube) == angles);
}

int main() {
    run();
    // Every handle was freed by its RAII owner (valgrind counts the library's registry as
    // still reachable, so it would not see a leaked handle).
    CHECK(rotlang_live_handles() == 0);
    if (failures) return 1;
    std::printf("ok\n");
    return 0;
}
