// The next shooter of progressive refinement: the patch with the most unshot power, the
// lowest index among equals (internal header).
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

namespace rad::solve_impl {

// Patches in buckets by the leading bits of their power: a positive double's bit pattern
// orders as its value, so the top 19 bits (sign, exponent and 7 bits of mantissa) give
// buckets of 1/128 of an octave in the powers' order. The largest power is in the highest
// non-empty bucket (found through a two-level bitmap), and a scan of that bucket alone finds
// it exactly, ties to the lowest index: the same patch as a scan of every patch. A change
// of power costs O(1) (the patch moves between two linked lists when its bucket changes),
// where a heap pays O(log n) for every receiver of every shot.
class PowerQueue {
  public:
    explicit PowerQueue(std::size_t patches)
        : slot_(patches), words_(kBuckets / 64, 0), summary_(kBuckets / 4096, 0),
          head_(kBuckets, kNone) {}

    // Sets patch i's power (>= 0; 0 takes it out).
    void set(std::size_t i, double power) {
        auto& s = slot_[i];
        s.power = power;
        const std::uint32_t bucket = power > 0 ? bucket_of(power) : kNone;
        if (bucket == s.bucket) return;
        if (s.bucket != kNone) unlink(static_cast<std::uint32_t>(i));
        if (bucket != kNone) link(static_cast<std::uint32_t>(i), bucket);
    }

    // The patch with the largest power (lowest index among equals), or -1 when all are 0.
    std::int64_t top() const {
        std::size_t s = summary_.size();
        while (s > 0 && summary_[s - 1] == 0) --s;
        if (s == 0) return -1;
        const std::size_t word = 64 * (s - 1) + 63 - std::countl_zero(summary_[s - 1]);
        const std::size_t bucket = 64 * word + 63 - std::countl_zero(words_[word]);
        std::uint32_t best = kNone;
        for (auto i = head_[bucket]; i != kNone; i = slot_[i].next)
            if (best == kNone || slot_[i].power > slot_[best].power ||
                (slot_[i].power == slot_[best].power && i < best))
                best = i;
        return best;
    }

  private:
    static constexpr std::uint32_t kNone = 0xffffffffu;
    static constexpr int kShift = 45; // 64 - 19 bits
    static constexpr std::size_t kBuckets = std::size_t(1) << (64 - kShift);
    struct Slot {
        double power = 0;
        std::uint32_t bucket = kNone, next = kNone, prev = kNone;
    };
    static std::uint32_t bucket_of(double power) {
        std::uint64_t bits;
        std::memcpy(&bits, &power, sizeof bits);
        return static_cast<std::uint32_t>(bits >> kShift);
    }
    void link(std::uint32_t i, std::uint32_t bucket) {
        auto& s = slot_[i];
        s.bucket = bucket;
        s.prev = kNone;
        s.next = head_[bucket];
        if (s.next != kNone) slot_[s.next].prev = i;
        head_[bucket] = i;
        words_[bucket / 64] |= std::uint64_t(1) << (bucket % 64);
        summary_[bucket / 4096] |= std::uint64_t(1) << (bucket / 64 % 64);
    }
    void unlink(std::uint32_t i) {
        auto& s = slot_[i];
        if (s.prev != kNone)
            slot_[s.prev].next = s.next;
        else
            head_[s.bucket] = s.next;
        if (s.next != kNone) slot_[s.next].prev = s.prev;
        if (head_[s.bucket] == kNone) {
            auto& word = words_[s.bucket / 64];
            word &= ~(std::uint64_t(1) << (s.bucket % 64));
            if (word == 0) summary_[s.bucket / 4096] &= ~(std::uint64_t(1) << (s.bucket / 64 % 64));
        }
        s.bucket = s.next = s.prev = kNone;
    }
    std::vector<Slot> slot_;
    std::vector<std::uint64_t> words_;   // a bit per bucket: not empty
    std::vector<std::uint64_t> summary_; // a bit per word of words_: not zero
    std::vector<std::uint32_t> head_;    // per bucket, its first patch
};

} // namespace rad::solve_impl
