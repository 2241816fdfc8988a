// The OrcaSlicer drop-in over every layer of a 10,000-layer object, as OrcaSlicer calls
// it (one call per layer): the first pass parses and fills the table, later passes are
// lookups. Compare with `orcaslicer_table_10k` in capi/benches/capi.rs (the same table
// computed through the Rust API). Run: capi/benches/dropin.sh
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "Print.hpp"

namespace Slic3r {
double calculate_infill_rotation_angle(const PrintObject* object, size_t layer_id, const double& fixed_infill_angle,
                                       const std::string& template_string);
void clear_infill_rotation_cache();
}  // namespace Slic3r

using namespace Slic3r;
using Clock = std::chrono::steady_clock;

static double pass(const PrintObject& object, const std::string& text, double& sum) {
    auto start = Clock::now();
    double fixed = 45.0;
    for (size_t i = 0; i < object.layer_count(); i++) sum += calculate_infill_rotation_angle(&object, i, fixed, text);
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

int main() {
    const std::string text = "5, 10!, +20, +10L25%, -10l25%";
    Print print;
    print.m_region.bottom_shell_layers.value = 3;
    print.m_region.top_shell_layers.value = 4;
    PrintObject object(&print, std::vector<double>(10000, 0.2), 0.2, 0.0);
    double sum = 0, first = 1e300, cached = 1e300, table = 1e300;
    for (int round = 0; round < 50; round++) {
        clear_infill_rotation_cache();
        auto start = Clock::now();
        double fixed = 45.0;
        sum += calculate_infill_rotation_angle(&object, 0, fixed, text);  // parse + table
        double t = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
        table = t < table ? t : table;
        clear_infill_rotation_cache();
        double f = pass(object, text, sum);  // parse + table + 10,000 lookups
        double c = pass(object, text, sum);  // 10,000 lookups
        first = f < first ? f : first;
        cached = c < cached ? c : cached;
    }
    std::printf("drop-in, 10,000 layers: first call (parse + table) %.1f us; first pass (the same + 10,000 "
                "lookups) %.1f us; cached pass %.1f us (%.1f ns per call); checksum %g\n",
                table, first, cached, cached * 1000.0 / 10000.0, sum);
    return 0;
}
