// The reliable method's automatic grid, chosen per scene from the detections' own GPU times
// (DetectSettings::reliable.grid_tuning). The method finds every pair, exactly, at any grid:
// the grid decides only the time. Finer cells mean more footprints (setup, fill, sweep and
// memory grow with them) and fewer candidates per exact pair (the pair pass shrinks);
// which wins depends on the scene (large deep overlaps want coarser cells, dense small
// objects and touching stacks finer ones: docs/reliable.md, "The grid per scene"), so no
// constant fits every scene.
//
// The tuner scales kCellsPerEdge (cells per typical edge) by steps of sqrt(2), from 1/4 to
// 2. It starts at 1 and compares each neighbour with the step it holds, by a bracket: the
// neighbour's time against the mean of the held step's times just before and just after
// it. A GPU's clocks move between detections (an idle H100 ramps for hundreds of
// milliseconds, in steps: docs/reliable.md); a bracket cancels a steady drift, and one whose
// two held times differ by more than kSteady is not used (the neighbour is tried again;
// after kMaxUnsteady such brackets the walk ends where it is). It moves to the neighbour
// with the lowest ratio if that is at least kBetter below 1, and walks on (the far
// neighbour only: the step it left was slower) until the step it holds beats both. Settled,
// it walks again after kFirstReprobe detections, then after twice as many each time, up to
// every kReprobe, and at once when the held step becomes kDrift slower than it was (a
// deforming scene may move its best grid). A different scene (another count of objects or
// triangles) starts again at 1. Detections that ran their cell stage more than once (a
// buffer grown after an overflow) are not comparable and are not reported.
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
    static constexpr double kSteady = 0.05;  // a bracket's two held times at most 5 % apart
    static constexpr int kMaxUnsteady = 3;  // unsteady brackets before a walk gives up
    static constexpr double kDrift = 0.25;  // the settled step 25 % slower: walk again
    static constexpr std::uint32_t kReprobe = 200;     // settled: neighbours measured again this often
    // The first walk runs while an idle GPU's clocks ramp up: the settled tuner walks again
    // after kFirstReprobe detections, then after twice as many each time, up to kReprobe.
    static constexpr std::uint32_t kFirstReprobe = 8;
    // The settled detections before the next walk.
    std::uint32_t reprobeAfter() const;

    // The step the next detection of `scene` uses (a different scene starts again at 0).
    // Calling it again without a report returns the same step.
    int next(const Scene& scene);
    // A detection of `scene` at `step` took `gpu_ms` of GPU time (its span). Ignored for
    // another scene than the tuner's, for a step other than the held one and its
    // neighbours, and for gpu_ms <= 0.
    void report(const Scene& scene, int step, double gpu_ms);
    static double scale(int step);
    // Why the next detection uses its step, for DetectStats' settings note.
    std::string describe(int step) const;
    bool settled() const noexcept { return !walking_; }

private:
    static constexpr std::size_t kSteps = kFinest - kCoarsest + 1;
    static bool onLadder(int step) noexcept { return step >= kCoarsest && step <= kFinest; }
    double& ratio(int step) { return ratio_[static_cast<std::size_t>(step - kCoarsest)]; }
    double ratio(int step) const { return ratio_[static_cast<std::size_t>(step - kCoarsest)]; }
    // The neighbour the walk compares next, or current_ when none is left.
    int neighbourToTry() const;
    void startWalk();
    void settle();

    Scene scene_{};
    int current_ = 0;
    bool walking_ = true;
    // The held step's last time (0: none), and whether the last report was of it, so that
    // it can open a bracket.
    double held_ms_ = 0;
    bool held_fresh_ = false;
    // A neighbour measured, waiting for the held step's next time to close its bracket.
    int trial_step_ = 0;
    double trial_ms_ = 0, trial_before_ms_ = 0;
    // Per step, its time over the held step's in a steady bracket (0: not compared since
    // the walk started or moved).
    std::array<double, kSteps> ratio_{};
    int unsteady_ = 0;  // unsteady brackets in this walk
    double settled_ms_ = 0;  // the held step's time when it settled
    std::uint32_t since_settled_ = 0;
    std::uint32_t reprobes_ = 0;  // walks since the scene's first
};

}  // namespace vkcollide
