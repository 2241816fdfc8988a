// The OrcaSlicer drop-in (examples/orcaslicer/rotation_angle.cpp) against the conformance
// corpus: every layer of every case on all four models, from several threads at once,
// each walking the cases and layers in its own random order. Run by capi/tests/cpp.rs.
//
// Usage: dropin_test CORPUS THREADS STRIDE [same-only]
//   CORPUS: lines "model NAME h B T N heights..." and "case MODEL STATUS HEX N degrees..."
//   (written by cpp.rs from ../shared/conformance; "nan" where OrcaSlicer's angle is NaN);
//   STRIDE: check every STRIDE-th case (valgrind runs a sample); same-only: only cases
//   whose OrcaSlicer angles equal rotlang's (for a build in the rotlang dialect).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "Print.hpp"
#include "rotlang.hpp"

namespace Slic3r {
double calculate_infill_rotation_angle(const PrintObject* object, size_t layer_id, const double& fixed_infill_angle,
                                       const std::string& template_string);
void clear_infill_rotation_cache();
}  // namespace Slic3r

using namespace Slic3r;

struct Case {
    std::string model, status, text;
    std::vector<double> degrees;  // NaN: OrcaSlicer's angle is NaN there
    std::vector<double> on_raft;  // the dialect on the raft object's own layer tops
    size_t raft = 0;              // which raft (0, 1, 2: 1, 2 or 3 raft layers)
};

// Rafts of 1, 2 and 3 layers whose tops (object_print_z_min, raft and gap) are not a
// multiple of any model's layer height, so the object's layers sit off the layer grid.
static const size_t RAFT_LAYERS[3] = {1, 2, 3};
static const double RAFT_TOP[3] = {0.35, 0.53, 0.81};

struct ModelSpec {
    double layer_height;
    int bottom, top;
    std::vector<double> heights;
};

static std::string unhex(const std::string& hex) {
    if (hex == "-") return "";
    std::string out;
    for (size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
    return out;
}

static bool close(double got, double expected) {
    if (!std::isfinite(got)) return false;
    if (std::isnan(expected)) return true;  // OrcaSlicer: NaN; rotlang: any finite angle
    if (std::fabs(expected) > 1e9) return std::fabs(got - expected) <= 1e-9 * std::fabs(expected);
    double d = std::fmod(std::fabs(got - expected), 360.0);
    return std::min(d, 360.0 - d) <= 1e-4;
}

int main(int argc, char** argv) {
    if (argc < 4) return 2;
    std::ifstream in(argv[1]);
    unsigned threads = static_cast<unsigned>(std::stoi(argv[2]));
    size_t stride = static_cast<size_t>(std::stoi(argv[3]));
    bool same_only = argc > 4 && std::string(argv[4]) == "same-only";

    std::map<std::string, ModelSpec> specs;
    std::vector<Case> cases;
    std::string line;
    size_t seen = 0;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::string kind;
        s >> kind;
        size_t n = 0;
        if (kind == "model") {
            std::string name;
            ModelSpec m;
            s >> name >> m.layer_height >> m.bottom >> m.top >> n;
            m.heights.resize(n);
            for (auto& h : m.heights) s >> h;
            specs[name] = m;
        } else if (kind == "case") {
            Case c;
            std::string hex;
            s >> c.model >> c.status >> hex >> n;
            c.text = unhex(hex);
            for (size_t i = 0; i < n; i++) {
                std::string d;
                s >> d;
                c.degrees.push_back(d == "nan" ? NAN : std::stod(d));
            }
            if (seen++ % stride == 0 && (!same_only || c.status == "same")) cases.push_back(c);
        }
    }

    // One Print per model (its shell counts) and one object per model, plus the same
    // object on rafts of 1, 2 and 3 layers (each case on one of them in turn). OrcaSlicer
    // calls with Layer::id(), which counts the raft layers: layer i of the object is id
    // R + i. On a raft, OrcaSlicer measures layer tops as print_z - object_print_z_min,
    // which can differ from the running sums in the last bit (and so break a tie the
    // other way): the expectation there is the dialect on exactly those tops, computed
    // here through rotlang.hpp.
    std::map<std::string, std::unique_ptr<Print>> prints;
    std::map<std::string, std::unique_ptr<PrintObject>> objects;
    std::map<std::string, std::unique_ptr<PrintObject>> rafted[3];
    for (const auto& [name, m] : specs) {
        auto print = std::make_unique<Print>();
        print->m_region.bottom_shell_layers.value = m.bottom;
        print->m_region.top_shell_layers.value = m.top;
        objects[name] = std::make_unique<PrintObject>(print.get(), m.heights, m.layer_height, 0.0);
        for (size_t r = 0; r < 3; r++)
            rafted[r][name] =
                std::make_unique<PrintObject>(print.get(), m.heights, m.layer_height, RAFT_TOP[r], RAFT_LAYERS[r]);
        prints[name] = std::move(print);
    }
    for (size_t k = 0; k < cases.size(); k++) {
        Case& c = cases[k];
        c.raft = k % 3;
        const PrintObject* raft = rafted[c.raft].at(c.model).get();
        std::vector<double> heights;
        double below = 0;
        for (const Layer* l : raft->layers()) {
            double top = l->print_z - raft->slicing_parameters().object_print_z_min;
            heights.push_back(top - below);
            below = top;
        }
        const ModelSpec& m = specs.at(c.model);
        rotlang::Options orca;
        orca.dialect = rotlang::Dialect::OrcaSlicer;
        c.on_raft = rotlang::Template(c.text).angles(
            rotlang::Model::from_heights(heights, m.layer_height).shells(m.bottom, m.top), orca);
    }

    std::atomic<size_t> checked{0}, failed{0}, raft_diffs{0};
    auto worker = [&](unsigned seed) {
        std::mt19937 rng(seed);
        std::vector<size_t> order(cases.size());
        for (size_t i = 0; i < order.size(); i++) order[i] = i;
        std::shuffle(order.begin(), order.end(), rng);
        for (size_t k : order) {
            const Case& c = cases[k];
            const PrintObject* object = objects.at(c.model).get();
            const PrintObject* raft = rafted[c.raft].at(c.model).get();
            const size_t raft_layers = RAFT_LAYERS[c.raft];
            std::vector<size_t> layers(c.degrees.size());
            for (size_t i = 0; i < layers.size(); i++) layers[i] = i;
            std::shuffle(layers.begin(), layers.end(), rng);
            for (size_t i : layers) {
                double fixed = 45.0;  // ignored by every non-empty template
                double got = calculate_infill_rotation_angle(object, i, fixed, c.text) * 180.0 / M_PI;
                double on_raft =
                    calculate_infill_rotation_angle(raft, raft_layers + i, fixed, c.text) * 180.0 / M_PI;
                checked++;
                if (!close(got, c.degrees[i])) {
                    if (failed++ < 10)
                        std::fprintf(stderr, "%s on %s (%s), layer %zu: got %.9g, expected %.9g\n", c.text.c_str(),
                                     c.model.c_str(), c.status.c_str(), i, got, c.degrees[i]);
                }
                if (!close(on_raft, c.on_raft[i]) && raft_diffs++ < 10)
                    std::fprintf(stderr, "%s on %s with a raft of %zu layers, layer %zu (id %zu): %.9g, expected %.9g\n",
                                 c.text.c_str(), c.model.c_str(), raft_layers, i, raft_layers + i, on_raft,
                                 c.on_raft[i]);
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; t++) pool.emplace_back(worker, 1234 + t);
    for (auto& t : pool) t.join();

    // The empty template gives the fixed angle in radians; a layer past the top too.
    const PrintObject* cube = objects.begin()->second.get();
    double fixed = 30.0;
    bool fixed_ok = calculate_infill_rotation_angle(cube, 3, fixed, "") == M_PI * 30.0 / 180.0 &&
                    calculate_infill_rotation_angle(cube, 1000000, fixed, "+10") == M_PI * 30.0 / 180.0;

    // Re-slicing an object (new layer heights) gives it a new table.
    const ModelSpec& spec = specs.begin()->second;
    PrintObject object(prints.begin()->second.get(), spec.heights, spec.layer_height, 0.0);
    double before = calculate_infill_rotation_angle(&object, 5, fixed, "+10/5mm");
    std::vector<double> thicker(spec.heights.size(), spec.heights[0] * 2);
    object.restack(thicker);
    double after = calculate_infill_rotation_angle(&object, 5, fixed, "+10/5mm");
    PrintObject fresh(prints.begin()->second.get(), thicker, spec.layer_height, 0.0);
    bool reslice_ok = after != before && after == calculate_infill_rotation_angle(&fresh, 5, fixed, "+10/5mm");

    // A re-slice with the same layer count and the same top, only two heights swapped:
    // layer 0 of `+90/2mm` is at 0.15 mm now, so 6.75 degrees (the old table: 11.25).
    std::vector<double> swapped(40, 0.2);
    swapped[0] = 0.25;
    swapped[1] = 0.15;
    PrintObject restacked(prints.begin()->second.get(), swapped, 0.2, 0.0);
    double old_angle = calculate_infill_rotation_angle(&restacked, 0, fixed, "+90/2mm") * 180.0 / M_PI;
    std::swap(swapped[0], swapped[1]);
    restacked.restack(swapped);
    double new_angle = calculate_infill_rotation_angle(&restacked, 0, fixed, "+90/2mm") * 180.0 / M_PI;
    bool same_top_ok = std::fabs(old_angle - 11.25) < 1e-9 && std::fabs(new_angle - 6.75) < 1e-9;
    if (!same_top_ok)
        std::fprintf(stderr, "re-slice to the same top: layer 0 was %.9g, is %.9g (expected 11.25, 6.75)\n",
                     old_angle, new_angle);

    // Bytes that are not UTF-8, as OrcaSlicer reads them: "+30\xb0" is "+30°" (30, 60, 90).
    bool bytes_ok = true;
    for (size_t i = 0; i < 3; i++) {
        double latin1 = calculate_infill_rotation_angle(cube, i, fixed, "+30\xb0") * 180.0 / M_PI;
        double utf8 = calculate_infill_rotation_angle(cube, i, fixed, "+30\xc2\xb0") * 180.0 / M_PI;
        if (std::fabs(latin1 - 30.0 * (i + 1)) > 1e-9 || std::fabs(utf8 - 30.0 * (i + 1)) > 1e-9) {
            bytes_ok = false;
            std::fprintf(stderr, "layer %zu: \"+30\\xb0\" %.9g, \"+30\u00b0\" %.9g, expected %g\n", i, latin1,
                         utf8, 30.0 * (i + 1));
        }
    }
    // Issue 16: `B!, 90M2, +15#10` on the cube over a raft of 3 layers (0.81 mm). The
    // object's layer i has id 3 + i and gets the angle it has without a raft: layer 1 (id 4)
    // 0 degrees; the top 3 layers their own angles, not the fixed one; an
    // id inside the raft reads layer 0, as OrcaSlicer's function does.
    bool raft_ok = true;
    {
        const ModelSpec& cube_spec = specs.at("cube20");
        PrintObject plain(prints.at("cube20").get(), cube_spec.heights, cube_spec.layer_height, 0.0);
        PrintObject on_raft(prints.at("cube20").get(), cube_spec.heights, cube_spec.layer_height, 0.81, 3);
        const std::string text = "B!, 90M2, +15#10";
        auto deg = [&](const PrintObject& o, size_t id) {
            return calculate_infill_rotation_angle(&o, id, fixed, text) * 180.0 / M_PI;
        };
        for (size_t i = 0; i < cube_spec.heights.size(); i++)
            if (std::fabs(deg(on_raft, 3 + i) - deg(plain, i)) > 1e-9) {
                raft_ok = false;
                std::fprintf(stderr, "%s, raft of 3: layer %zu (id %zu) %.9g, without a raft %.9g\n", text.c_str(), i,
                             3 + i, deg(on_raft, 3 + i), deg(plain, i));
            }
        for (size_t id = 0; id < 3; id++) raft_ok = raft_ok && deg(on_raft, id) == deg(plain, 0);
        // (Layer 4 itself is at 105 degrees: reading layers()[id] would show.)
        raft_ok = raft_ok && std::fabs(deg(on_raft, 4)) < 1e-9 && std::fabs(deg(plain, 4) - 105.0) < 1e-9;
        if (!raft_ok) std::fprintf(stderr, "%s on a raft of 3 layers: ids not read as OrcaSlicer does\n", text.c_str());
    }

    // A cached call takes no lock: it reads the thread's last table. Clearing the cache
    // frees that table; the next call must not read it (valgrind sees a read of freed
    // memory) and gives the same angle from a new table.
    double cached = calculate_infill_rotation_angle(cube, 7, fixed, "+10/1mm, -5");
    clear_infill_rotation_cache();
    bool cleared_ok = calculate_infill_rotation_angle(cube, 7, fixed, "+10/1mm, -5") == cached &&
                      calculate_infill_rotation_angle(cube, 8, fixed, "+10/1mm, -5") != cached;
    if (!cleared_ok) std::fprintf(stderr, "after clearing the cache, a call gave another angle\n");

    clear_infill_rotation_cache();
    // The drop-in frees every template it parses (valgrind cannot see a leaked handle).
    bool handles_ok = rotlang_live_handles() == 0;
    if (!handles_ok) std::fprintf(stderr, "%zu rotlang handles not freed\n", rotlang_live_handles());

    std::printf("checked %zu layers of %zu cases on %zu threads: %zu failed, %zu failed on a raft\n", checked.load(),
                cases.size(), static_cast<size_t>(threads), failed.load(), raft_diffs.load());
    if (!fixed_ok) std::fprintf(stderr, "the fixed angle is not returned for an empty template\n");
    if (!reslice_ok) std::fprintf(stderr, "a re-sliced object kept its old table\n");
    return failed == 0 && raft_diffs == 0 && raft_ok && cleared_ok && fixed_ok && reslice_ok && same_top_ok && bytes_ok && handles_ok &&
                   !cases.empty()
               ? 0
               : 1;
}
