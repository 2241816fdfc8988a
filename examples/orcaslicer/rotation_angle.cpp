// OrcaSlicer's calculate_infill_rotation_angle on rotlang: a drop-in replacement.
//
// Same signature, same results (rotlang's OrcaSlicer dialect reproduces OrcaSlicer's own
// reading of any template, valid or not), without its failure modes: a template that
// makes OrcaSlicer hang, crash or compute NaN gets finite angles here instead.
//
// The template is parsed and the object's whole angle table computed once per
// (object, template); every later call is a lookup. A re-sliced object (other layers,
// layer height or shell counts) gets a new table. Thread-safe: OrcaSlicer calls this from
// its layer threads, in any order.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include "Print.hpp"
#include "rotlang.hpp"

// The dialect: OrcaSlicer's (existing profiles keep their angles). Define it as
// rotlang::Dialect::Rotlang for rotlang's own semantics (solid signs, exact lengths).
#ifndef ROTLANG_DROPIN_DIALECT
#define ROTLANG_DROPIN_DIALECT rotlang::Dialect::OrcaSlicer
#endif

namespace Slic3r {

namespace {

// What a table was computed from. Comparing it on each call notices a re-sliced object.
struct Fingerprint {
    std::size_t layers = 0;
    double top = 0, layer_height = 0, z_min = 0;
    int bottom_shells = 0, top_shells = 0;
    bool operator==(const Fingerprint& o) const {
        return layers == o.layers && top == o.top && layer_height == o.layer_height && z_min == o.z_min &&
               bottom_shells == o.bottom_shells && top_shells == o.top_shells;
    }
};

Fingerprint fingerprint(const PrintObject* object) {
    Fingerprint f;
    const auto& layers = object->layers();
    f.layers = layers.size();
    f.top = layers.empty() ? 0.0 : layers.back()->print_z;
    f.layer_height = object->config().layer_height.value;
    f.z_min = object->slicing_parameters().object_print_z_min;
    const auto& region = object->print()->default_region_config();
    f.bottom_shells = region.bottom_shell_layers.value;
    f.top_shells = region.top_shell_layers.value;
    return f;
}

struct AngleTable {
    AngleTable(std::string text, Fingerprint f) : text(std::move(text)), fingerprint(f) {}
    const std::string text;
    const Fingerprint fingerprint;
    std::once_flag computed;
    std::vector<double> radians;  // empty: rotlang could not evaluate (see below)
};

std::mutex cache_mutex;
std::unordered_map<const PrintObject*, std::vector<std::shared_ptr<AngleTable>>> cache;

std::shared_ptr<AngleTable> table_for(const PrintObject* object, const std::string& text) {
    Fingerprint f = fingerprint(object);
    std::lock_guard<std::mutex> lock(cache_mutex);
    auto& tables = cache[object];
    for (auto& table : tables) {
        if (table->text != text) continue;
        if (!(table->fingerprint == f)) table = std::make_shared<AngleTable>(text, f);
        return table;
    }
    tables.push_back(std::make_shared<AngleTable>(text, f));
    return tables.back();
}

void compute(AngleTable& table, const PrintObject* object) {
    // The layers' tops relative to the object's bottom (above a raft, if any), as
    // OrcaSlicer measures them; rotlang takes their differences as layer heights.
    const auto& layers = object->layers();
    std::vector<double> heights;
    heights.reserve(layers.size());
    double below = object->slicing_parameters().object_print_z_min;
    for (const auto* layer : layers) {
        heights.push_back(layer->print_z - below);
        below = layer->print_z;
    }
    const auto& region = object->print()->default_region_config();
    try {
        auto model = rotlang::Model::from_heights(std::move(heights), object->config().layer_height.value)
                         .shells(static_cast<std::uint32_t>(std::max(0, region.bottom_shell_layers.value)),
                                 static_cast<std::uint32_t>(std::max(0, region.top_shell_layers.value)));
        rotlang::Template tpl(table.text);
        rotlang::Options options;
        options.dialect = ROTLANG_DROPIN_DIALECT;
        std::vector<double> degrees = tpl.angles(model, options);
        table.radians.reserve(degrees.size());
        for (double a : degrees) table.radians.push_back(M_PI * a / 180.0);  // as OrcaSlicer rounds
    } catch (const rotlang::Error&) {
        // A model rotlang refuses (no layers, a layer of zero height) or, in the rotlang
        // dialect, a template with errors: the table stays empty and every layer gets
        // the fixed angle, as with an empty template.
        table.radians.clear();
    }
}

}  // namespace

double calculate_infill_rotation_angle(const PrintObject* object, size_t layer_id, const double& fixed_infill_angle,
                                       const std::string& template_string) {
    double fixed = M_PI * fixed_infill_angle / 180.0;
    if (template_string.empty() || object == nullptr) return fixed;
    std::shared_ptr<AngleTable> table = table_for(object, template_string);
    std::call_once(table->computed, compute, std::ref(*table), object);
    return layer_id < table->radians.size() ? table->radians[layer_id] : fixed;
}

// Drops every cached table (call when a Print is cleared, so that a new object at the
// address of a deleted one cannot meet its tables; the fingerprint catches most of that).
void clear_infill_rotation_cache() {
    std::lock_guard<std::mutex> lock(cache_mutex);
    cache.clear();
}

}  // namespace Slic3r
