// OrcaSlicer's calculate_infill_rotation_angle on rotlang: a drop-in replacement.
//
// Same signature, same results (rotlang's OrcaSlicer dialect reproduces OrcaSlicer's own
// reading of any template, valid or not), without its failure modes: a template that
// makes OrcaSlicer hang, crash or compute NaN gets finite angles here instead.
//
// The template is parsed and the object's whole angle table computed once per
// (object, template); a later call looks the angle up after checking, in O(1), that the
// object still has the table's layer count, layer height, raft and shell counts and that
// the layer asked for (and the one below it, and the top) sit where they did. A call for
// layer 0, which every pass over the layers makes once, compares every layer's print_z,
// so a re-slice that restacks the same count of layers to the same top is noticed too.
// A re-sliced object gets a new table. Thread-safe: OrcaSlicer calls this from its layer
// threads, in any order; a call for the object and template the thread asked for last
// takes no lock (its checks and the table are read without contention).
#include <algorithm>
#include <atomic>
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

// What a table was computed from, to notice a re-sliced object: every layer's print_z,
// not only the count and the top, since a re-slice can restack the same number of layers
// to the same top with other heights (and other angles).
struct Fingerprint {
    std::vector<double> print_z;
    double layer_height = 0, z_min = 0;
    int bottom_shells = 0, top_shells = 0;

    explicit Fingerprint(const PrintObject* object) {
        const auto& layers = object->layers();
        print_z.reserve(layers.size());
        for (const auto* layer : layers) print_z.push_back(layer->print_z);
        read_settings(object, layer_height, z_min, bottom_shells, top_shells);
    }

    // O(1): the settings, the count, the top, and layer `id` and the one below it. Any
    // layer whose place changed is noticed when it is asked for; `matches` (on layer 0)
    // catches the rest once per pass.
    bool quick_matches(const PrintObject* object, std::size_t id) const {
        double h, z;
        int b, t;
        read_settings(object, h, z, b, t);
        const auto& layers = object->layers();
        if (h != layer_height || z != z_min || b != bottom_shells || t != top_shells ||
            layers.size() != print_z.size())
            return false;
        if (layers.empty()) return true;
        if (layers.back()->print_z != print_z.back()) return false;
        if (id < layers.size() && layers[id]->print_z != print_z[id]) return false;
        return id == 0 || id > layers.size() || layers[id - 1]->print_z == print_z[id - 1];
    }

    // O(layers), no allocation: every layer's print_z.
    bool matches(const PrintObject* object) const {
        if (!quick_matches(object, 0)) return false;
        const auto& layers = object->layers();
        for (std::size_t i = 0; i < layers.size(); i++)
            if (layers[i]->print_z != print_z[i]) return false;
        return true;
    }

private:
    static void read_settings(const PrintObject* object, double& h, double& z, int& b, int& t) {
        h = object->config().layer_height.value;
        z = object->slicing_parameters().object_print_z_min;
        const auto& region = object->print()->default_region_config();
        b = region.bottom_shell_layers.value;
        t = region.top_shell_layers.value;
    }
};

struct AngleTable {
    AngleTable(std::string text, const PrintObject* object) : text(std::move(text)), fingerprint(object) {}
    const std::string text;
    const Fingerprint fingerprint;
    std::once_flag computed;
    std::vector<double> radians;  // empty: rotlang could not evaluate (see below)
};

std::mutex cache_mutex;
std::unordered_map<const PrintObject*, std::vector<std::shared_ptr<AngleTable>>> cache;
// Tables replaced by a re-slice, kept until the cache is cleared: a thread's last table
// (below) may still point to one.
std::vector<std::shared_ptr<AngleTable>> retired;
// Bumped by clear_infill_rotation_cache: a thread's last table from before is gone.
std::atomic<std::uint64_t> generation{1};

// Each thread's last (object, table): a cached call reads it without any lock. Plain
// pointers (no destructor), so the thread-local access is a single load; the table they
// point to lives until the cache is cleared, which OrcaSlicer does only between slices.
thread_local const PrintObject* last_object = nullptr;
thread_local const AngleTable* last_table = nullptr;
thread_local std::uint64_t last_generation = 0;

// Whether `table` still fits `object`: checked outside the lock (a table's fingerprint never
// changes; the object's layers do not change while OrcaSlicer runs its layer threads).
// Layer 0's call reads every layer, once per pass over the object: O(1) a call on average.
bool current(const AngleTable& table, const PrintObject* object, std::size_t layer_id) {
    return layer_id == 0 ? table.fingerprint.matches(object) : table.fingerprint.quick_matches(object, layer_id);
}

std::shared_ptr<AngleTable> table_for(const PrintObject* object, const std::string& text, std::size_t layer_id) {
    std::shared_ptr<AngleTable> found;
    {
        std::lock_guard<std::mutex> lock(cache_mutex);
        for (auto& table : cache[object])
            if (table->text == text) found = table;
    }
    if (found && current(*found, object, layer_id)) return found;
    auto fresh = std::make_shared<AngleTable>(text, object);
    std::lock_guard<std::mutex> lock(cache_mutex);
    auto& tables = cache[object];
    for (auto& table : tables) {
        if (table->text != text) continue;
        // Another thread may have replaced the stale table first: use its table then.
        if (table != found && current(*table, object, layer_id)) return table;
        retired.push_back(table);
        table = fresh;
        return fresh;
    }
    tables.push_back(fresh);
    return fresh;
}

void compute(AngleTable& table, const PrintObject* object) {
    // The layers' tops relative to the object's bottom (above a raft, if any), as
    // OrcaSlicer measures them; rotlang takes their differences as layer heights.
    const auto& layers = object->layers();
    std::vector<double> heights;
    heights.reserve(layers.size());
    const double z_min = object->slicing_parameters().object_print_z_min;
    double below = 0;
    for (const auto* layer : layers) {
        double top = layer->print_z - z_min;
        heights.push_back(top - below);
        below = top;
    }
    const auto& region = object->print()->default_region_config();
    // The C API directly (rotlang.hpp's Template would read the diagnostics, which costs
    // rotlang's own parse of the text; the OrcaSlicer dialect reads the raw text), and the
    // angles written straight into the table.
    RotlangModel model = rotlang_model_heights(heights.data(), heights.size(), object->config().layer_height.value);
    model.bottom_shells = static_cast<std::uint32_t>(std::max(0, region.bottom_shell_layers.value));
    model.top_shells = static_cast<std::uint32_t>(std::max(0, region.top_shell_layers.value));
    RotlangOptions options = {0.0, 0, static_cast<std::uint32_t>(ROTLANG_DROPIN_DIALECT)};
    // OrcaSlicer reads the template's bytes as they are, UTF-8 or not: so does
    // rotlang_parse_bytes (the OrcaSlicer dialect gives "+30\xb0" the angles of "+30°").
    RotlangTemplate* tpl = nullptr;
    RotlangStatus status = rotlang_parse_bytes(table.text.data(), table.text.size(), ROTLANG_TARGET_SPARSE, &tpl);
    if (status == ROTLANG_STATUS_OK) {
        table.radians.resize(heights.size());
        status = rotlang_expand(tpl, &model, &options, 0, ROTLANG_TO_TOP, table.radians.data(), nullptr,
                                table.radians.size(), nullptr);
        rotlang_template_free(tpl);
    }
    if (status != ROTLANG_STATUS_OK) {
        // A model rotlang refuses (no layers, a layer of zero height) or, in the rotlang
        // dialect, a template with errors or not UTF-8: the table stays empty and every
        // layer gets the fixed angle, as with an empty template.
        table.radians.clear();
        return;
    }
    for (double& a : table.radians) a = M_PI * a / 180.0;  // as OrcaSlicer rounds
}

}  // namespace

double calculate_infill_rotation_angle(const PrintObject* object, size_t layer_id, const double& fixed_infill_angle,
                                       const std::string& template_string) {
    double fixed = M_PI * fixed_infill_angle / 180.0;
    if (template_string.empty() || object == nullptr || object->layers().empty()) return fixed;
    // OrcaSlicer passes Layer::id(), which counts the raft layers below the object; its
    // function turns it back into an index into layers() (an id below the object's first
    // layer reads layer 0), and so does this.
    const std::size_t first_id = object->get_layer(0)->id();
    const std::size_t index = layer_id > first_id ? layer_id - first_id : 0;
    // The lock-free path: this thread's last table, if it is this object's and this
    // template's and still fits the object.
    const std::uint64_t now = generation.load(std::memory_order_acquire);
    const AngleTable* last = last_table;
    if (last != nullptr && last_object == object && last_generation == now && last->text == template_string &&
        current(*last, object, index))
        return index < last->radians.size() ? last->radians[index] : fixed;
    std::shared_ptr<AngleTable> table = table_for(object, template_string, index);
    std::call_once(table->computed, compute, std::ref(*table), object);
    last_object = object;
    last_table = table.get();
    last_generation = now;
    return index < table->radians.size() ? table->radians[index] : fixed;
}

// Drops every cached table (call when a Print is cleared, so that a new object at the
// address of a deleted one cannot meet its tables; the fingerprint catches most of that).
void clear_infill_rotation_cache() {
    std::lock_guard<std::mutex> lock(cache_mutex);
    generation.fetch_add(1, std::memory_order_acq_rel);
    cache.clear();
    retired.clear();
}

}  // namespace Slic3r
