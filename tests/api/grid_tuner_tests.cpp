// GridTuner (src/api/grid_tuner.hpp) fed made-up GPU times: where a scene's time is lowest
// it settles, it never leaves its ladder, it does not move for less than kBetter, a new
// scene, a slower settled grid or its look-again schedule (kFirstReprobe detections, twice as
// many each time, up to kReprobe) make it measure again, and a first walk on ramping clocks
// ends at the fastest grid once warm.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <vector>

#include "api/grid_tuner.hpp"

using vkcollide::GridTuner;

namespace {

const GridTuner::Scene kScene{100000, 2};

// Runs `detections` detections of `scene` whose GPU time at each step is `cost(step)`; the
// steps they used, in order.
std::vector<int> drive(GridTuner& tuner, const std::function<double(int)>& cost, int detections,
                       const GridTuner::Scene& scene = kScene) {
    std::vector<int> steps;
    for (int i = 0; i < detections; ++i) {
        const int step = tuner.next(scene);
        REQUIRE(step >= GridTuner::kCoarsest);
        REQUIRE(step <= GridTuner::kFinest);
        steps.push_back(step);
        tuner.report(scene, step, cost(step));
    }
    return steps;
}

}  // namespace

TEST_CASE("the grid tuner settles where the scene's GPU time is lowest, at most a step past it", "[grid]") {
    for (int best = GridTuner::kCoarsest; best <= GridTuner::kFinest; ++best) {
        INFO("lowest time at step " << best);
        GridTuner tuner;
        const auto cost = [best](int step) { return 1.0 + 0.2 * (step - best) * (step - best); };
        const std::vector<int> steps = drive(tuner, cost, 40);
        // Exploring: every step between 0 and the best, and one beyond it at most.
        const int lo = std::min(0, best) - 1, hi = std::max(0, best) + 1;
        for (int s : steps) CHECK((s >= lo && s <= hi));
        // Settled within the walk there and one look at each neighbour; then, after
        // kFirstReprobe detections, one more look at each neighbour, warm.
        const std::size_t walk = static_cast<std::size_t>(std::abs(best)) + 4;
        std::size_t looks = 0;
        for (std::size_t i = walk; i < steps.size(); ++i) {
            CHECK(std::abs(steps[i] - best) <= 1);
            if (steps[i] != best) ++looks;
        }
        CHECK(looks >= 2);  // the first look again, after kFirstReprobe detections
        CHECK(tuner.next(kScene) == best);
        CHECK(GridTuner::scale(best) == Approx(std::exp2(0.5 * best)));
    }
}

TEST_CASE("the grid tuner moves only for a neighbour kBetter faster", "[grid]") {
    GridTuner tuner;
    // Neighbours 2 % faster than the start: not enough.
    const auto cost = [](int step) { return step == 0 ? 1.0 : 0.98; };
    const std::vector<int> steps = drive(tuner, cost, 10);
    CHECK(steps[0] == 0);
    CHECK(steps[1] == -1);
    CHECK(steps[2] == 1);
    for (std::size_t i = 3; i < steps.size(); ++i) CHECK(steps[i] == 0);
    // 4 % faster: it moves.
    GridTuner moved;
    const std::vector<int> then = drive(moved, [](int step) { return step == 0 ? 1.0 : step == -1 ? 0.96 : 1.1; }, 10);
    CHECK(then.back() == -1);
}

TEST_CASE("the grid tuner measures again for a new scene, a slower settled grid and every kReprobe detections", "[grid]") {
    GridTuner tuner;
    auto coarse = [](int step) { return 1.0 + 0.3 * (step + 2) * (step + 2); };  // best at -2
    drive(tuner, coarse, 20);
    CHECK(tuner.next(kScene) == -2);

    // Another scene (one more object) starts again at the default grid.
    const GridTuner::Scene other{100000, 3};
    CHECK(tuner.next(other) == 0);
    drive(tuner, coarse, 20, other);
    CHECK(tuner.next(other) == -2);

    // The settled grid 30 % slower (the scene deformed): its neighbours are measured again,
    // and a faster one taken.
    auto fine = [](int step) { return 1.0 + 0.3 * (step + 1) * (step + 1); };  // best at -1 now
    tuner.report(other, -2, 1.3 * 2.0);
    const std::vector<int> after = drive(tuner, fine, 12, other);
    CHECK(after.front() != -2);
    CHECK(after.back() == -1);

    // Settled and steady: it looks at its neighbours again after kFirstReprobe settled
    // detections, then after twice as many each time, then every kReprobe.
    GridTuner steady;
    const std::vector<int> steps = drive(steady, coarse, 600);
    std::vector<std::size_t> looks;  // where it tried -3 after its walk (0, -1, 1, -2, -3)
    for (std::size_t i = 5; i < steps.size(); ++i) {
        CHECK(std::abs(steps[i] + 2) <= 1);
        if (steps[i] == -3) looks.push_back(i);
    }
    std::vector<std::size_t> expected;
    std::size_t settled = 5;  // the first settled detection
    for (std::uint32_t k = 0;; ++k) {
        const std::size_t at = settled + std::min<std::size_t>(GridTuner::kReprobe, std::size_t{GridTuner::kFirstReprobe} << k);
        if (at >= steps.size()) break;
        expected.push_back(at);
        settled = at + 2;  // -3, then -1, then settled at -2 again
    }
    CHECK(looks == expected);
    CHECK(expected.size() == 6);  // after 8, 16, 32, 64, 128, then kReprobe settled detections
    CHECK(steps.back() == -2);
}

TEST_CASE("the grid tuner's first walk on a GPU whose clocks ramp up is measured again, warm", "[grid]") {
    // Each detection of the first dozen runs faster than the one before (clocks ramping), by
    // more than the grids differ: the first walk moves towards whatever it tried last. The
    // warm look after kFirstReprobe detections brings it back to the fastest grid.
    for (int best : {-1, 0, 1}) {
        INFO("lowest time at step " << best);
        GridTuner tuner;
        int detection = 0;
        const auto cost = [&](int step) {
            const double ramp = 1.0 + 0.5 * std::max(0, 12 - detection++) / 12.0;
            return ramp * (1.0 + 0.05 * (step - best) * (step - best));
        };
        const std::vector<int> steps = drive(tuner, cost, 60);
        CHECK(steps.back() == best);
        CHECK(tuner.next(kScene) == best);
    }
}

TEST_CASE("the grid tuner ignores times of another scene, of zero and not a number", "[grid]") {
    GridTuner tuner;
    CHECK(tuner.next(kScene) == 0);
    tuner.report({1, 1}, 0, 1.0);  // another scene
    tuner.report(kScene, 0, 0.0);
    tuner.report(kScene, 0, -1.0);
    tuner.report(kScene, 0, std::numeric_limits<double>::quiet_NaN());
    tuner.report(kScene, GridTuner::kFinest + 1, 1.0);  // off the ladder
    CHECK(tuner.next(kScene) == 0);  // still unmeasured
    tuner.report(kScene, 0, 1.0);
    CHECK(tuner.next(kScene) == -1);  // measured: the coarser neighbour next
    CHECK(tuner.describe(-1).find("trying x0.71") != std::string::npos);
}
