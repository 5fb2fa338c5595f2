// The reliable method's automatic grid, chosen per scene from the detections' own GPU times
// (DetectSettings::reliable.tune_grid). The method finds every pair, exactly, at any grid:
// the grid decides only the time. Finer cells mean more footprints (setup, fill, sweep and
// memory grow with them) and fewer candidates per exact pair (the pair pass shrinks);
// which wins depends on the scene (large deep overlaps want coarser cells, dense small
// objects and touching stacks finer ones: docs/reliable.md, "The grid per scene"), so no
// constant fits every scene.
//
// The tuner scales kCellsPerEdge (cells per typical edge) by steps of sqrt(2), from 1/4 to
// 2: it starts at 1, measures, tries the coarser neighbour, then the finer one, and moves
// to a neighbour that was at least kBetter faster, until the scale it holds is the fastest
// of its neighbours. Settled, it forgets the other scales' times and walks again every
// kReprobe detections, and at once when the settled scale becomes kDrift slower than it
// was (a deforming scene may move its best grid). A different scene (another count of objects or triangles)
// starts again at 1. Detections that ran their cell stage more than once (a buffer grown
// after an overflow) are not comparable and are not counted.
//
// Host only; one per world, used by one thread at a time (the world's use guard).
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace vkcollide {

class GridTuner {
public:
    // What makes two detections the same scene for the tuner.
    struct Scene {
        std::uint64_t triangles = 0;
        std::uint32_t objects = 0;
        bool operator==(const Scene&) const = default;
    };
    static constexpr int kCoarsest = -4, kFinest = 2;  // steps of sqrt(2): scales 1/4 .. 2
    static constexpr double kBetter = 0.03;            // a neighbour must be 3 % faster to move to it
    static constexpr double kDrift = 0.25;             // the settled scale 25 % slower: measure again
    static constexpr std::uint32_t kReprobe = 200;     // settled: neighbours measured again this often
    // The first walk runs while an idle GPU's clocks ramp up (a few hundred milliseconds of
    // work on an H200), so its later steps look faster than its earlier ones and it drifts
    // towards the side it tried last: the settled tuner measures its neighbours again after
    // kFirstReprobe detections, then after twice as many each time, up to kReprobe.
    static constexpr std::uint32_t kFirstReprobe = 8;
    // The settled detections before the next look at the neighbours.
    std::uint32_t reprobeAfter() const;

    // The step the next detection of `scene` uses (a different scene starts again at 0).
    int next(const Scene& scene);
    // A detection of `scene` at `step` took `gpu_ms` of GPU time (its span). Ignored for
    // another scene than the tuner's, and for gpu_ms <= 0.
    void report(const Scene& scene, int step, double gpu_ms);
    static double scale(int step);
    // Why the next detection uses its step, for DetectStats' settings note.
    std::string describe(int step) const;

private:
    static constexpr std::size_t kSteps = kFinest - kCoarsest + 1;
    double& ms(int step) { return ms_[static_cast<std::size_t>(step - kCoarsest)]; }
    double ms(int step) const { return ms_[static_cast<std::size_t>(step - kCoarsest)]; }
    // Keeps only the current step's time: the others are measured again as the walk needs them.
    void forgetOthers();

    Scene scene_{};
    int current_ = 0;
    // The last GPU time measured at each step (0: not measured since the last reset).
    std::array<double, kSteps> ms_{};
    double settled_ms_ = 0;               // the current step's time when it settled (0: exploring)
    std::uint32_t since_settled_ = 0;
    std::uint32_t reprobes_ = 0;          // looks at the neighbours since the scene's first walk
};

}  // namespace vkcollide
