// The next shooter of progressive refinement: the patch with the most unshot power, the
// lowest index among equals, patches with none never (internal header).
//
// Between two shots powers only rise (receivers), except the shooter's, which falls to 0.
// So the best of each block of 64 patches, and of each group of 64 blocks, is kept by a
// comparison per rise; the shooter's block and group are scanned again (128 comparisons);
// and the choice scans the groups (n / 4096). A shot costs its row plus about 200
// comparisons, where a heap took a push per receiver and a logarithmic pop per stale entry.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rad::solve_impl {

class ShooterChoice {
  public:
    static constexpr std::size_t kNone = ~std::size_t(0);
    // Patch i's power, asked of the shooting state (`context`) when a block is scanned: the
    // choice keeps no copy, so a reception writes nothing here but a block's best.
    using PowerOf = double (*)(const void* context, std::size_t i);
    ShooterChoice(std::size_t patches, PowerOf power_of, const void* context);
    // Patch j's power is now `power`, at least what it was.
    void raise(std::size_t j, double power) {
        const Best candidate{power, static_cast<std::uint32_t>(j)};
        if (better(candidate, block_[j / kBlock])) {
            block_[j / kBlock] = candidate;
            if (better(candidate, group_[j / kGroup])) group_[j / kGroup] = candidate;
        }
    }
    // Patch i's power is now less than it was (or as much): its block and group are scanned.
    void lower(std::size_t i);
    // The patch with the most power (the lowest index among equals), or kNone when no patch
    // has any.
    std::size_t best() const;

  private:
    static constexpr std::size_t kBlock = 64, kGroup = 64 * kBlock;
    struct Best {
        double power = 0;
        std::uint32_t patch = 0;
    };
    // More power, or as much with a lower index; no power is never better.
    static bool better(const Best& a, const Best& b) {
        return a.power > 0 && (a.power > b.power || (a.power == b.power && a.patch < b.patch));
    }
    Best scan_block(std::size_t block) const;
    Best scan_group(std::size_t group) const;

    std::size_t patches_;
    PowerOf power_of_;
    const void* context_;
    std::vector<Best> block_, group_; // power 0: none in it has power
};

} // namespace rad::solve_impl
