#include "core/progress.h"

#include <algorithm>

namespace tissuemesh {

ProgressTicker::ProgressTicker(const Progress& progress, std::string stage, std::size_t total, std::size_t updates)
    : progress_(progress), stage_(std::move(stage)), total_(total),
      interval_(std::max<std::size_t>(1, total / std::max<std::size_t>(1, updates)))
{
    next_report_ = interval_;
}

void ProgressTicker::step(std::size_t count)
{
    done_ += count;
    if (done_ >= next_report_ || done_ == total_) {
        progress_.update(stage_, total_ == 0 ? 1.0 : static_cast<double>(done_) / static_cast<double>(total_));
        next_report_ = done_ + interval_;
    }
}

} // namespace tissuemesh
