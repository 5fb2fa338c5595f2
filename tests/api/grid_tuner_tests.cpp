// GridTuner (src/api/grid_tuner.hpp) fed made-up GPU times: where a scene's time is lowest
// it settles, it never leaves its ladder, it does not move for less than kBetter, a new
// scene, a slower settled grid or its walk-again schedule (kFirstReprobe detections, twice as
// many each time, up to kReprobe) make it measure again, and clocks that ramp, drift or jump
// between detections (each neighbour compared inside a bracket of the held step's times)
// do not walk it to a slower grid.
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
        CHECK(tuner.next(scene) == step);  // asking again without a report changes nothing
        steps.push_back(step);
        tuner.report(scene, step, cost(step));
    }
    return steps;
}

// The step it holds: the one used most over the last `tail` detections.
int heldOver(const std::vector<int>& steps, std::size_t tail) {
    std::vector<int> counts(GridTuner::kFinest - GridTuner::kCoarsest + 1, 0);
    for (std::size_t i = steps.size() - std::min(tail, steps.size()); i < steps.size(); ++i) ++counts[steps[i] - GridTuner::kCoarsest];
    return int(std::max_element(counts.begin(), counts.end()) - counts.begin()) + GridTuner::kCoarsest;
}

}  // namespace

TEST_CASE("the grid tuner settles where the scene's GPU time is lowest, at most a step past it", "[grid]") {
    for (int best = GridTuner::kCoarsest; best <= GridTuner::kFinest; ++best) {
        INFO("lowest time at step " << best);
        GridTuner tuner;
        const auto cost = [best](int step) { return 1.0 + 0.2 * (step - best) * (step - best); };
        const std::vector<int> steps = drive(tuner, cost, 60);
        // Walking: every step between 0 and the best, and one beyond it at most.
        const int lo = std::min(0, best) - 1, hi = std::max(0, best) + 1;
        for (int s : steps) CHECK((s >= lo && s <= hi));
        // The walk: the start measured, each neighbour tried and bracketed, then per move
        // the new step measured and its far neighbour tried and bracketed.
        const std::size_t walk = 5 + 3 * static_cast<std::size_t>(std::abs(best));
        std::size_t looks = 0;
        for (std::size_t i = walk; i < steps.size(); ++i) {
            CHECK(std::abs(steps[i] - best) <= 1);
            if (steps[i] != best) ++looks;
        }
        CHECK(looks >= 2);  // the first walk again, after kFirstReprobe detections
        CHECK(tuner.next(kScene) == best);
        CHECK(tuner.settled());
        CHECK(GridTuner::scale(best) == Approx(std::exp2(0.5 * best)));
    }
}

TEST_CASE("the grid tuner moves only for a neighbour kBetter faster", "[grid]") {
    GridTuner tuner;
    // Neighbours 2 % faster than the start: not enough.
    const auto cost = [](int step) { return step == 0 ? 1.0 : 0.98; };
    const std::vector<int> steps = drive(tuner, cost, 10);
    CHECK(steps == std::vector<int>{0, -1, 0, 1, 0, 0, 0, 0, 0, 0});
    // 4 % faster: it moves, then compares the far side only.
    GridTuner moved;
    const std::vector<int> then = drive(moved, [](int step) { return step == 0 ? 1.0 : step == -1 ? 0.96 : 1.1; }, 10);
    CHECK(then == std::vector<int>{0, -1, 0, 1, 0, -1, -2, -1, -1, -1});
}

TEST_CASE("the grid tuner measures again for a new scene, a slower settled grid and on its schedule", "[grid]") {
    GridTuner tuner;
    auto coarse = [](int step) { return 1.0 + 0.3 * (step + 2) * (step + 2); };  // best at -2
    drive(tuner, coarse, 30);
    CHECK(tuner.next(kScene) == -2);

    // Another scene (one more object) starts again at the default grid.
    const GridTuner::Scene other{100000, 3};
    CHECK(tuner.next(other) == 0);
    drive(tuner, coarse, 30, other);
    CHECK(tuner.next(other) == -2);

    // The settled grid 30 % slower (the scene deformed): its neighbours are compared again,
    // and a faster one taken.
    auto fine = [](int step) { return 1.0 + 0.3 * (step + 1) * (step + 1); };  // best at -1 now
    tuner.report(other, -2, 1.3 * 2.0);
    CHECK(!tuner.settled());
    const std::vector<int> after = drive(tuner, fine, 12, other);
    CHECK(after.front() != -2);
    CHECK(after.back() == -1);

    // Settled and steady: it walks again after kFirstReprobe settled detections, then after
    // twice as many each time, then every kReprobe; a walk is four detections (-3, -2, -1, -2).
    GridTuner steady;
    const std::vector<int> steps = drive(steady, coarse, 700);
    std::vector<std::size_t> looks;  // where it tried -3 after its first walk
    for (std::size_t i = 12; i < steps.size(); ++i) {
        CHECK(std::abs(steps[i] + 2) <= 1);
        if (steps[i] == -3) looks.push_back(i);
    }
    REQUIRE(looks.size() == 7);  // after 8, 16, 32, 64, 128, then twice kReprobe settled detections
    for (std::size_t k = 1; k < looks.size(); ++k) {
        INFO("walk " << k);
        CHECK(looks[k] - looks[k - 1] == 4 + std::min<std::size_t>(GridTuner::kReprobe, std::size_t{GridTuner::kFirstReprobe} << k));
    }
    CHECK(steps.back() == -2);
}

TEST_CASE("the grid tuner's first walk on a GPU whose clocks ramp up is measured again, warm", "[grid]") {
    // Each detection of the first dozen runs faster than the one before (clocks ramping), by
    // more than the grids differ: its brackets are unsteady, the walk gives up, and the walk
    // after kFirstReprobe detections, warm, finds the fastest grid.
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

TEST_CASE("the grid tuner keeps the faster grid while the clocks drift or jump between detections", "[grid]") {
    SECTION("a steady drift larger than the grids' difference") {
        // Every detection 1.5 % faster than the one before (then steady): a neighbour measured
        // after the held step would look 1.5 % faster for the clocks alone, and 4 % for the
        // grids: the bracket takes the drift out in both directions.
        for (const double neighbour : {1.04, 0.955}) {
            INFO("neighbours' time " << neighbour);
            GridTuner tuner;
            int detection = 0;
            const auto cost = [&](int step) {
                const double clocks = std::pow(0.985, std::min(detection++, 40));
                return clocks * (step == 0 ? 1.0 : step == -1 ? neighbour : 1.2);
            };
            const std::vector<int> steps = drive(tuner, cost, 12);
            CHECK(steps[4] == 0);  // the bracket's second held time
            CHECK(heldOver(steps, 5) == (neighbour < 1 ? -1 : 0));
        }
    }
    SECTION("clocks that jump in steps while the walk runs (an H100 leaving an idle state)") {
        // The held step is the fastest; the coarser one 50 % slower (as a touching stack's).
        // The GPU runs 4x slow for 15 detections, 3x for 18 more, then at full clock: no
        // walk may settle on the slower grid, and once warm it holds the fastest one.
        GridTuner tuner;
        int detection = 0;
        const auto cost = [&](int step) {
            const int d = detection++;
            const double clocks = d < 15 ? 4.0 : d < 33 ? 3.0 : 1.0;
            return clocks * (step == 0 ? 1.0 : step < 0 ? 1.5 : 1.3);
        };
        const std::vector<int> steps = drive(tuner, cost, 300);
        for (std::size_t i = 0; i < steps.size(); ++i) {
            INFO("detection " << i);
            // Never more than one detection on a neighbour at a time: it never moves there.
            if (i > 0 && steps[i] != 0) CHECK(steps[i - 1] == 0);
        }
        CHECK(steps.back() == 0);
        CHECK(tuner.settled());
    }
}

TEST_CASE("the grid tuner finds the fastest grid through noise between detections", "[grid]") {
    // Each span off by up to 1.5 % either way (a GPU's jitter), the grids 6 % apart or more:
    // wherever the best grid is, and whatever the noise's seed, it settles there and holds it.
    std::uint32_t seed = 12345;
    const auto noise = [&seed] {
        seed = seed * 1664525u + 1013904223u;  // a fixed LCG: the test repeats exactly
        return 1.0 + 0.03 * (double(seed >> 8) / double(1u << 24) - 0.5);
    };
    for (int best = GridTuner::kCoarsest; best <= GridTuner::kFinest; ++best) {
        for (int trial = 0; trial < 20; ++trial) {
            INFO("lowest time at step " << best << ", trial " << trial);
            GridTuner tuner;
            const auto cost = [&](int step) { return (1.0 + 0.06 * std::abs(step - best)) * noise(); };
            const std::vector<int> steps = drive(tuner, cost, 400);
            CHECK(heldOver(steps, 100) == best);
            std::size_t off = 0;
            for (std::size_t i = 100; i < steps.size(); ++i) off += steps[i] != best;
            CHECK(off <= 12);  // only the walks' looks at the neighbours
        }
    }
}

TEST_CASE("the grid tuner ignores times of another scene, of zero, not a number, and off its neighbours", "[grid]") {
    GridTuner tuner;
    CHECK(tuner.next(kScene) == 0);
    tuner.report({1, 1}, 0, 1.0);  // another scene
    tuner.report(kScene, 0, 0.0);
    tuner.report(kScene, 0, -1.0);
    tuner.report(kScene, 0, std::numeric_limits<double>::quiet_NaN());
    tuner.report(kScene, GridTuner::kFinest + 1, 1.0);  // off the ladder
    tuner.report(kScene, -2, 1.0);  // not a neighbour of the held step
    CHECK(tuner.next(kScene) == 0);  // still unmeasured
    tuner.report(kScene, 0, 1.0);
    CHECK(tuner.next(kScene) == -1);  // measured: the coarser neighbour next
    CHECK(tuner.describe(-1).find("trying x0.71") != std::string::npos);
    tuner.report(kScene, -1, 0.5);
    CHECK(tuner.next(kScene) == 0);  // the bracket closes on the held step
    tuner.report(kScene, 0, 1.0);
    CHECK(tuner.next(kScene) == 1);
    tuner.report(kScene, 1, 2.0);
    tuner.report(kScene, 0, 1.0);
    CHECK(tuner.next(kScene) == -1);  // moved: half the time
    CHECK(tuner.describe(-1).find("comparing its neighbours") != std::string::npos);
}
