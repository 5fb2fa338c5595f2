// Automatic settings: every field a DetectSettings leaves empty, filled in from what the
// world knows about its scene on the host (auto_settings.cpp), and what that knowledge
// costs to keep: the host meshes' shapes are measured only while a setting that uses them
// is automatic.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>

#include "api/grid_tuner.hpp"
#include "api/object_registry.hpp"
#include "vkcollide/thread_pool.hpp"
#include "vkcollide/world.hpp"

namespace vkcollide {

// What GridTuning::Auto means on `device`: On, but Off on a CPU implementation.
GridTuning autoGridTuning(const vk::Device& device);

struct AutoSettings {
    using Object = ObjectRegistry::Object;

    // The scene box the last detection measured on the GPU (engine meshes included), for
    // the automatic settings of scenes with GPU meshes.
    std::optional<std::array<float, 6>> measured_box;
    // Whether the last resolve() needed the shapes of all host meshes (automatic direction
    // or resolution) or of open ones (automatic open epsilon): updateVertices then measures
    // them with its copy (the same shape, bit for bit, as a later measureShapes).
    mutable bool shapes_wanted_all = true, shapes_wanted_open = true;
    // Whether the last resolve() needed this object's shape (measureShapes and
    // updateVertices ask the same question).
    bool wantsShape(const Object& o) const { return shapes_wanted_all || (shapes_wanted_open && o.options.open); }

    // The reliable method's grid per scene (reliable.grid_tuning On): resolve() asks it for
    // the step of the next detection, the detection reports its GPU time back (detect.cpp).
    // Mutable: choosing a step for another scene starts the tuner again.
    mutable GridTuner grid;
    // The tuned grid a resolve() chose: the step to report the detection's time against.
    struct GridChoice {
        GridTuner::Scene scene;
        int step = 0;
    };

    // Every automatic field of `in` filled in for the live objects of `registry`
    // (validation::checkSettings checks the result); stale shapes are measured first, on
    // `executor`, when an automatic field needs them (measureShapes). `grid_choice`
    // (optional): set when the resolution came from the tuned grid, else reset.
    DetectSettings resolve(const DetectSettings& in, const ObjectRegistry& registry, const vk::Device& device, Executor& executor,
                           std::string* note, std::optional<GridChoice>* grid_choice = nullptr) const;
    // A new host mesh's box and largest |coordinate|; its shape is left to measureShapes.
    static void measureHost(Object& o, std::span<const Float3> positions);
    // Measures the shape of every live host mesh whose geometry changed since it was last
    // measured, on the executor, if `in` leaves a setting automatic that uses shapes.
    void measureShapes(const DetectSettings& in, const ObjectRegistry& registry, Executor& executor) const;
};

}  // namespace vkcollide
