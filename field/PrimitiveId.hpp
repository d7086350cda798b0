#pragma once
// The 32-bit id of a contour primitive that a field pixel is nearest to:
//   bit 0       1 = vertex, 0 = segment (segment k joins vertex k and k + 1)
//   bits 1..19  index of the vertex or segment in its contour (< 2^19)
//   bits 20..31 index of the contour in its slice (< 2^12 - 1)
// kNoPrimitive (all bits set, never a valid id) marks pixels of a slice
// without contours.
#include <cstdint>
#include <stdexcept>

namespace dfrecon {

/// A slice with more contours, or a contour with more points, than the ids
/// can index: valid input too large for the fields (the caller names the
/// file; docs/cli.md "Limits on input").
class PrimitiveLimitExceeded : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

inline constexpr std::uint32_t kNoPrimitive = 0xffffffffu;
inline constexpr std::uint32_t kMaxContoursPerSlice = (1u << 12) - 1;
inline constexpr std::uint32_t kMaxPrimitivesPerContour = 1u << 19;

struct PrimitiveId {
    std::uint32_t contour = 0;
    std::uint32_t index = 0;
    bool isVertex = false;

    std::uint32_t encode() const { return contour << 20 | index << 1 | (isVertex ? 1u : 0u); }
    static PrimitiveId decode(std::uint32_t id) {
        return {id >> 20, (id >> 1) & (kMaxPrimitivesPerContour - 1), (id & 1u) != 0};
    }
    bool operator==(const PrimitiveId& o) const {
        return contour == o.contour && index == o.index && isVertex == o.isVertex;
    }
};

}  // namespace dfrecon
