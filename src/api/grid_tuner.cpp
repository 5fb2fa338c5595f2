#include "api/grid_tuner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vkcollide {

double GridTuner::scale(int step) { return std::exp2(0.5 * step); }

void GridTuner::forgetOthers() {
    const double here = ms(current_);
    ms_ = {};
    ms(current_) = here;
    settled_ms_ = 0;
}

int GridTuner::next(const Scene& scene) {
    if (!(scene == scene_)) {
        *this = GridTuner{};
        scene_ = scene;
    }
    // Each move needs a neighbour kBetter faster than the step it leaves, with the times
    // this call sees: it cannot come back, so the loop ends.
    for (;;) {
        if (ms(current_) == 0) return current_;
        if (current_ > kCoarsest && ms(current_ - 1) == 0) return current_ - 1;
        if (current_ < kFinest && ms(current_ + 1) == 0) return current_ + 1;
        int best = current_;
        for (int n : {current_ - 1, current_ + 1})
            if (n >= kCoarsest && n <= kFinest && ms(n) < ms(best) && ms(n) < ms(current_) * (1 - kBetter)) best = n;
        if (best == current_) break;
        current_ = best;
        settled_ms_ = 0;
    }
    if (settled_ms_ == 0) {
        settled_ms_ = ms(current_);
        since_settled_ = 0;
    }
    return current_;
}

std::uint32_t GridTuner::reprobeAfter() const {
    return reprobes_ >= 5 ? kReprobe : std::min(kReprobe, kFirstReprobe << reprobes_);
}

void GridTuner::report(const Scene& scene, int step, double gpu_ms) {
    if (!(scene == scene_) || !(gpu_ms > 0) || step < kCoarsest || step > kFinest) return;
    ms(step) = gpu_ms;
    if (settled_ms_ > 0 && step == current_) {
        ++since_settled_;
        if (gpu_ms > settled_ms_ * (1 + kDrift) || since_settled_ >= reprobeAfter()) {
            ++reprobes_;
            forgetOthers();
        }
    }
}

std::string GridTuner::describe(int step) const {
    char text[160];
    if (ms(current_) == 0 || step != current_)
        std::snprintf(text, sizeof text, "grid tuned per scene: trying x%.2f", scale(step));
    else if (settled_ms_ > 0)
        std::snprintf(text, sizeof text, "grid tuned per scene: x%.2f, the fastest of its neighbours (%.3g ms of GPU)", scale(step),
                      ms(step));
    else
        std::snprintf(text, sizeof text, "grid tuned per scene: x%.2f (%.3g ms of GPU)", scale(step), ms(step));
    return text;
}

}  // namespace vkcollide
