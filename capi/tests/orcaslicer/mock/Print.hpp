// A mock of the parts of OrcaSlicer's PrintObject that calculate_infill_rotation_angle
// reads (libslic3r/Print.hpp in OrcaSlicer), with the same member names and access paths,
// so examples/orcaslicer/rotation_angle.cpp compiles unchanged against it.
#ifndef MOCK_SLIC3R_PRINT_HPP
#define MOCK_SLIC3R_PRINT_HPP

#include <cstddef>
#include <vector>

namespace Slic3r {

struct ConfigOptionFloat { double value = 0.0; };
struct ConfigOptionInt { int value = 0; };

struct PrintObjectConfig { ConfigOptionFloat layer_height; };
struct PrintRegionConfig { ConfigOptionInt bottom_shell_layers, top_shell_layers; };
struct SlicingParameters { double object_print_z_min = 0.0; };

class Layer {
public:
    Layer(std::size_t id, double print_z, double height)
        : print_z(print_z), height(height), slice_z(print_z - height / 2), m_id(id) {}
    std::size_t id() const { return m_id; }
    double print_z;  // top of the layer (mm, above the bed: raft included)
    double height;   // thickness
    double slice_z;  // middle
private:
    std::size_t m_id;
};

using LayerPtrs = std::vector<Layer*>;

class Print {
public:
    const PrintRegionConfig& default_region_config() const { return m_region; }
    PrintRegionConfig m_region;
};

class PrintObject {
public:
    /// Layers stacked from `z_min` (the top of a raft of `raft_layers` layers below the
    /// object, or 0) with these heights. As in OrcaSlicer, the raft layers are not the
    /// object's (they are support layers), but they are counted in its layers' ids: the
    /// object's first layer has id `raft_layers`.
    PrintObject(const Print* print, const std::vector<double>& heights, double layer_height, double z_min,
                std::size_t raft_layers = 0)
        : m_print(print), m_raft_layers(raft_layers) {
        m_config.layer_height.value = layer_height;
        m_slicing.object_print_z_min = z_min;
        restack(heights);
    }
    ~PrintObject() { clear(); }
    PrintObject(const PrintObject&) = delete;
    PrintObject& operator=(const PrintObject&) = delete;

    /// Re-slicing: new layers for the same object (as OrcaSlicer does after a change).
    void restack(const std::vector<double>& heights) {
        clear();
        double top = m_slicing.object_print_z_min;
        for (std::size_t i = 0; i < heights.size(); i++) {
            double below = top;
            top += heights[i];
            m_layers.push_back(new Layer(m_raft_layers + i, top, top - below));
        }
    }

    const LayerPtrs& layers() const { return m_layers; }
    std::size_t layer_count() const { return m_layers.size(); }
    const Layer* get_layer(int idx) const { return m_layers.at(static_cast<std::size_t>(idx)); }
    const PrintObjectConfig& config() const { return m_config; }
    const Print* print() const { return m_print; }
    const SlicingParameters& slicing_parameters() const { return m_slicing; }

private:
    void clear() {
        for (Layer* l : m_layers) delete l;
        m_layers.clear();
    }
    const Print* m_print;
    std::size_t m_raft_layers;
    LayerPtrs m_layers;
    PrintObjectConfig m_config;
    SlicingParameters m_slicing;
};

}  // namespace Slic3r

#endif
