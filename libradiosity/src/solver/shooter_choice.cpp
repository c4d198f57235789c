#include "shooter_choice.hpp"

#include <algorithm>

namespace rad::solve_impl {

ShooterChoice::ShooterChoice(std::size_t patches, PowerOf power_of, const void* context)
    : patches_(patches), power_of_(power_of), context_(context),
      block_((patches + kBlock - 1) / kBlock), group_((patches + kGroup - 1) / kGroup) {
    for (std::size_t b = 0; b < block_.size(); ++b) block_[b] = scan_block(b);
    for (std::size_t g = 0; g < group_.size(); ++g) group_[g] = scan_group(g);
}

ShooterChoice::Best ShooterChoice::scan_block(std::size_t block) const {
    Best best;
    const std::size_t end = std::min(patches_, (block + 1) * kBlock);
    for (std::size_t j = block * kBlock; j < end; ++j) {
        const Best candidate{power_of_(context_, j), static_cast<std::uint32_t>(j)};
        if (better(candidate, best)) best = candidate;
    }
    return best;
}

ShooterChoice::Best ShooterChoice::scan_group(std::size_t group) const {
    Best best;
    const std::size_t end = std::min(block_.size(), (group + 1) * (kGroup / kBlock));
    for (std::size_t b = group * (kGroup / kBlock); b < end; ++b)
        if (better(block_[b], best)) best = block_[b];
    return best;
}

void ShooterChoice::lower(std::size_t i) {
    block_[i / kBlock] = scan_block(i / kBlock);
    group_[i / kGroup] = scan_group(i / kGroup);
}

std::size_t ShooterChoice::best() const {
    Best best;
    for (const auto& g : group_)
        if (better(g, best)) best = g;
    return best.power > 0 ? best.patch : kNone;
}

} // namespace rad::solve_impl
