#include "api/grid_tuner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vkcollide {

double GridTuner::scale(int step) { return std::exp2(0.5 * step); }

std::uint32_t GridTuner::reprobeAfter() const { return reprobes_ >= 5 ? kReprobe : std::min(kReprobe, kFirstReprobe << reprobes_); }

int GridTuner::neighbourToTry() const {
    for (int n : {current_ - 1, current_ + 1})
        if (onLadder(n) && ratio(n) == 0) return n;
    return current_;
}

void GridTuner::startWalk() {
    walking_ = true;
    ratio_ = {};
    unsteady_ = 0;
    trial_ms_ = 0;
}

void GridTuner::settle() {
    walking_ = false;
    settled_ms_ = held_ms_;
    since_settled_ = 0;
    trial_ms_ = 0;
}

int GridTuner::next(const Scene& scene) {
    if (!(scene == scene_)) {
        *this = GridTuner{};
        scene_ = scene;
    }
    // A trial waits for the held step's time after it; a bracket opens on a fresh held time.
    if (!walking_ || trial_ms_ > 0 || !held_fresh_) return current_;
    if (const int n = neighbourToTry(); n != current_) return n;
    // Both neighbours compared: move to the faster one by kBetter or more, or settle.
    int best = current_;
    double best_ratio = 1 - kBetter;
    for (int n : {current_ - 1, current_ + 1})
        if (onLadder(n) && ratio(n) <= best_ratio) best = n, best_ratio = ratio(n);
    if (best == current_) {
        settle();
        return current_;
    }
    // The step left behind was slower than the new one: only the far side is compared.
    const int left = current_;
    current_ = best;
    startWalk();  // a walk from the new step, its held time still to come
    ratio(left) = 1 / best_ratio;
    held_ms_ = 0;
    held_fresh_ = false;
    return current_;
}

void GridTuner::report(const Scene& scene, int step, double gpu_ms) {
    if (!(scene == scene_) || !(gpu_ms > 0) || !onLadder(step) || std::abs(step - current_) > 1) return;
    if (step != current_) {
        // A neighbour's time: its bracket opens on the held step's time before it.
        if (!walking_ || !held_fresh_) return;
        trial_step_ = step;
        trial_ms_ = gpu_ms;
        trial_before_ms_ = held_ms_;
        held_fresh_ = false;
        return;
    }
    held_ms_ = gpu_ms;  // before the bracket closes: settle() keeps it
    held_fresh_ = true;
    if (trial_ms_ > 0) {
        const double before = trial_before_ms_, after = gpu_ms;
        if (std::fabs(after - before) <= kSteady * std::min(before, after)) {
            ratio(trial_step_) = trial_ms_ / (0.5 * (before + after));
        } else if (++unsteady_ >= kMaxUnsteady) {
            settle();  // the clocks keep moving: keep this grid, walk again later
        }
        trial_ms_ = 0;
    }
    if (walking_) return;
    ++since_settled_;
    if (gpu_ms > settled_ms_ * (1 + kDrift) || since_settled_ >= reprobeAfter()) {
        ++reprobes_;
        startWalk();
    }
}

std::string GridTuner::describe(int step) const {
    char text[160];
    if (step != current_)
        std::snprintf(text, sizeof text, "grid tuned per scene: trying x%.2f against x%.2f", scale(step), scale(current_));
    else if (!walking_)
        std::snprintf(text, sizeof text, "grid tuned per scene: x%.2f, the fastest of its neighbours (%.3g ms of GPU)", scale(step),
                      held_ms_);
    else if (held_ms_ > 0)
        std::snprintf(text, sizeof text, "grid tuned per scene: x%.2f (%.3g ms of GPU), comparing its neighbours", scale(step), held_ms_);
    else
        std::snprintf(text, sizeof text, "grid tuned per scene: x%.2f, comparing its neighbours", scale(step));
    return text;
}

}  // namespace vkcollide
