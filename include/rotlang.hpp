// rotlang.hpp: a thin C++17 layer over rotlang.h (the C ABI). Header only.
//
// RAII handles, std::string_view in, std::vector<double> out. Failures throw
// rotlang::Error (a std::runtime_error carrying the status and, for a template with
// errors, its diagnostics). Exceptions rather than an expected-style result because
// C++17 has no std::expected, constructors (RAII) can only report failure by throwing,
// and the slicers this is for (OrcaSlicer, PrusaSlicer, Bambu Studio) already report
// slicing failures with exceptions. A template with errors is not a failure of parsing:
// `Template` always constructs and lists the errors in diagnostics(); evaluating it in
// the rotlang dialect throws. The OrcaSlicer dialect evaluates any text.
//
// Thread safety: a const Template may be evaluated from any number of threads at once.
// An Evaluator has a cursor: one per thread.
#ifndef ROTLANG_HPP
#define ROTLANG_HPP

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rotlang.h"

namespace rotlang {

enum class Target : std::uint32_t { Sparse = ROTLANG_TARGET_SPARSE, Solid = ROTLANG_TARGET_SOLID };
enum class Dialect : std::uint32_t {
    Rotlang = ROTLANG_DIALECT_ROTLANG,
    OrcaSlicer = ROTLANG_DIALECT_ORCASLICER,
};
enum class Fill : std::uint8_t {
    Sparse = ROTLANG_FILL_SPARSE,
    Dense = ROTLANG_FILL_DENSE,
    Solid = ROTLANG_FILL_SOLID,
    Concentric = ROTLANG_FILL_CONCENTRIC,
    Monotonic = ROTLANG_FILL_MONOTONIC,
    Rectilinear = ROTLANG_FILL_RECTILINEAR,
};
enum class Severity { Warning = ROTLANG_SEVERITY_WARNING, Error = ROTLANG_SEVERITY_ERROR };

/// One diagnostic; `start`/`end` are byte offsets into the template text.
struct Diagnostic {
    std::string code;
    Severity severity;
    std::string message;
    std::string help;
    std::size_t start;
    std::size_t end;
};

/// A defect of OrcaSlicer's reading (OrcaSlicer dialect only): hang, undefined, NaN layers.
struct Finding {
    RotlangFindingKind kind;
    std::string code;  // "orcaslicer::hangs", "orcaslicer::undefined", "orcaslicer::nan"
    std::size_t first_layer;
    std::size_t layers;
};

class Error : public std::runtime_error {
public:
    Error(RotlangStatus status, const std::string& message, std::vector<Diagnostic> diagnostics = {})
        : std::runtime_error(message), status_(status), diagnostics_(std::move(diagnostics)) {}
    RotlangStatus status() const noexcept { return status_; }
    /// The template's diagnostics when the status is ROTLANG_STATUS_TEMPLATE_HAS_ERRORS.
    const std::vector<Diagnostic>& diagnostics() const noexcept { return diagnostics_; }

private:
    RotlangStatus status_;
    std::vector<Diagnostic> diagnostics_;
};

namespace detail {
inline std::string last_error() {
    std::string message(rotlang_last_error(nullptr, 0), '\0');
    rotlang_last_error(message.data(), message.size() + 1);
    return message;
}
inline void check(RotlangStatus status, const std::vector<Diagnostic>& diagnostics = {}) {
    if (status != ROTLANG_STATUS_OK) {
        std::vector<Diagnostic> attached;
        if (status == ROTLANG_STATUS_TEMPLATE_HAS_ERRORS) attached = diagnostics;
        throw Error(status, "rotlang: " + last_error(), std::move(attached));
    }
}
}  // namespace detail

inline std::string version() { return rotlang_version(); }

struct Options {
    double base = 0.0;  // degrees added to every angle
    std::uint64_t seed = 0;
    Dialect dialect = Dialect::Rotlang;

    RotlangOptions c() const { return RotlangOptions{base, seed, static_cast<std::uint32_t>(dialect)}; }
};

/// The layers of one object: a list of heights or a uniform model, plus h, B and T.
class Model {
public:
    static Model uniform(std::size_t layers, double layer_height, double first_layer_height = 0.0) {
        Model m;
        m.model_ = rotlang_model_uniform(layers, layer_height, first_layer_height);
        return m;
    }
    static Model from_heights(std::vector<double> heights, double layer_height) {
        Model m;
        m.heights_ = std::move(heights);
        m.model_ = rotlang_model_heights(nullptr, 0, layer_height);
        m.list_ = true;
        return m;
    }
    Model& shells(std::uint32_t bottom, std::uint32_t top) {
        model_.bottom_shells = bottom;
        model_.top_shells = top;
        return *this;
    }
    /// The number of layers; throws Error (INVALID_MODEL, with the reason) when unusable.
    std::size_t size() const {
        std::size_t n = 0;
        RotlangModel m = c();
        detail::check(rotlang_model_layer_count(&m, &n));
        return n;
    }
    /// The number of layers as given, unchecked (0 for a model that cannot have any);
    /// the evaluation checks the model. Saves the copy `size()` makes to check it.
    std::size_t layers_given() const noexcept { return list_ ? heights_.size() : model_.layers; }
    /// The number of layers, safe to size an output by: a list's own length (its memory
    /// exists already; the library checks its values), or a uniform model's count once
    /// the library accepted it (throws Error(INVALID_MODEL) for SIZE_MAX layers instead
    /// of allocating them).
    std::size_t bounded_size() const { return list_ ? heights_.size() : size(); }
    /// The C struct, pointing into this object's heights (valid while it lives unchanged).
    RotlangModel c() const {
        RotlangModel m = model_;
        if (list_) {
            // An empty list still passes a non-NULL pointer, so the library reports the
            // empty model instead of reading it as a uniform one.
            static const double none = 0.0;
            m.heights = heights_.empty() ? &none : heights_.data();
            m.heights_len = heights_.size();
        }
        return m;
    }

private:
    Model() = default;
    std::vector<double> heights_;
    RotlangModel model_{};
    bool list_ = false;
};

struct Layer {
    std::size_t index;
    double bottom, top;  // mm above the object's bottom
    double angle;        // degrees, base included, not wrapped
    Fill fill;
};

/// What an expansion returns: one angle (degrees) and one fill per layer, and findings.
struct Expansion {
    std::vector<double> angles;
    std::vector<Fill> fills;
    std::vector<Finding> findings;
};

namespace detail {
inline std::vector<Finding> findings(const RotlangFinding* items, std::size_t count) {
    std::vector<Finding> out;
    for (std::size_t i = 0; i < count; i++)
        out.push_back(Finding{items[i].kind, rotlang_finding_code(static_cast<std::uint32_t>(items[i].kind)),
                              items[i].first_layer, items[i].layers});
    return out;
}
struct FreeTemplate {
    void operator()(RotlangTemplate* t) const noexcept { rotlang_template_free(t); }
};
struct FreeEvaluator {
    void operator()(RotlangEvaluator* e) const noexcept { rotlang_evaluator_free(e); }
};
}  // namespace detail

class Evaluator;

/// A parsed template. Movable, not copyable (share it by reference or shared_ptr).
class Template {
public:
    /// Parses `text`. Throws Error only for text that is not UTF-8; template errors are
    /// listed in diagnostics().
    explicit Template(std::string_view text, Target target = Target::Sparse)
        : Template(rotlang_parse, text, target) {}

    /// Parses any bytes, as OrcaSlicer reads its template (rotlang_parse_bytes): never
    /// throws for the text. Text that is not UTF-8 evaluates in the OrcaSlicer dialect
    /// only (each invalid byte is one unknown character, as OrcaSlicer sees it); the
    /// rotlang dialect throws Error(ROTLANG_STATUS_INVALID_UTF8) for it.
    static Template from_bytes(std::string_view text, Target target = Target::Sparse) {
        return Template(rotlang_parse_bytes, text, target);
    }

    const std::vector<Diagnostic>& diagnostics() const noexcept { return diagnostics_; }
    bool has_errors() const noexcept { return has_errors_; }

    /// Layers `first .. first + count` (count = ROTLANG_TO_TOP: to the top). The output
    /// is sized from the model, never from `count` alone: a range past the top throws
    /// Error(OUT_OF_RANGE), an unusable model Error(INVALID_MODEL).
    Expansion expand(const Model& model, const Options& options = {}, std::size_t first = 0,
                     std::size_t count = ROTLANG_TO_TOP) const {
        RotlangModel m = model.c();
        std::size_t total = model.bounded_size();
        std::size_t left = first < total ? total - first : 0;
        std::size_t n = count < left ? count : left;
        Expansion out;
        out.angles.resize(n);
        out.fills.resize(n);
        std::vector<RotlangFinding> items(4);
        RotlangFindings findings{items.data(), items.size(), 0};
        RotlangOptions o = options.c();
        // An empty vector's data() may be NULL, which the library would report before
        // the range (NULL_POINTER instead of OUT_OF_RANGE): give it a real address.
        double no_angle = 0;
        std::uint8_t no_fill = 0;
        double* angles = n ? out.angles.data() : &no_angle;
        std::uint8_t* fills = n ? reinterpret_cast<std::uint8_t*>(out.fills.data()) : &no_fill;
        auto run = [&] {
            return rotlang_expand(handle_.get(), &m, &o, first, count, angles, fills, n, &findings);
        };
        detail::check(run(), diagnostics_);
        if (findings.count > items.size()) {  // more findings than room: once more, with room
            items.resize(findings.count);
            findings = RotlangFindings{items.data(), items.size(), 0};
            detail::check(run(), diagnostics_);
        }
        out.findings = detail::findings(items.data(), findings.count < items.size() ? findings.count : items.size());
        return out;
    }

    /// Every layer's angle in degrees.
    std::vector<double> angles(const Model& model, const Options& options = {}) const {
        RotlangModel m = model.c();
        std::vector<double> out(model.bounded_size());
        RotlangOptions o = options.c();
        double none = 0;  // an empty vector's data() may be NULL: the model's error first
        detail::check(rotlang_expand(handle_.get(), &m, &o, 0, ROTLANG_TO_TOP, out.empty() ? &none : out.data(),
                                     nullptr, out.size(), nullptr),
                      diagnostics_);
        return out;
    }

    inline Evaluator evaluator(const Model& model, const Options& options = {}) const;

    const RotlangTemplate* get() const noexcept { return handle_.get(); }

private:
    using Parser = RotlangStatus (*)(const char*, std::size_t, std::uint32_t, RotlangTemplate**);
    Template(Parser parse, std::string_view text, Target target) {
        RotlangTemplate* raw = nullptr;
        detail::check(parse(text.data(), text.size(), static_cast<std::uint32_t>(target), &raw));
        handle_.reset(raw);
        std::size_t count = 0;
        detail::check(rotlang_template_diagnostic_count(raw, &count));
        for (std::size_t i = 0; i < count; i++) {
            RotlangDiagnostic d;
            detail::check(rotlang_template_diagnostic(raw, i, &d));
            diagnostics_.push_back(Diagnostic{d.code, static_cast<Severity>(d.severity), d.message,
                                              d.help ? d.help : "", d.start, d.end});
            has_errors_ = has_errors_ || d.severity == ROTLANG_SEVERITY_ERROR;
        }
    }

    std::unique_ptr<RotlangTemplate, detail::FreeTemplate> handle_;
    std::vector<Diagnostic> diagnostics_;
    bool has_errors_ = false;
};

/// Layer-by-layer access (cheap for increasing indices). One per thread.
class Evaluator {
public:
    Layer layer(std::size_t index) {
        RotlangLayer l;
        detail::check(rotlang_evaluator_layer(handle_.get(), index, &l));
        return Layer{l.index, l.bottom, l.top, l.angle, static_cast<Fill>(l.fill)};
    }
    std::vector<Finding> findings() const {
        RotlangFindings f{nullptr, 0, 0};
        detail::check(rotlang_evaluator_findings(handle_.get(), &f));
        std::vector<RotlangFinding> items(f.count);
        f = RotlangFindings{items.data(), items.size(), 0};
        detail::check(rotlang_evaluator_findings(handle_.get(), &f));
        return detail::findings(items.data(), items.size() < f.count ? items.size() : f.count);
    }

private:
    friend class Template;
    explicit Evaluator(RotlangEvaluator* raw) : handle_(raw) {}
    std::unique_ptr<RotlangEvaluator, detail::FreeEvaluator> handle_;
};

inline Evaluator Template::evaluator(const Model& model, const Options& options) const {
    RotlangModel m = model.c();
    RotlangOptions o = options.c();
    RotlangEvaluator* raw = nullptr;
    detail::check(rotlang_evaluator_new(handle_.get(), &m, &o, &raw), diagnostics_);
    return Evaluator(raw);
}

}  // namespace rotlang

#endif  // ROTLANG_HPP
