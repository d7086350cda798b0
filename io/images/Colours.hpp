#pragma once
// The colours dfrecon paints results with, one scheme per kind of value, so
// that every file a viewer opens reads the same way:
//   sequentialColour   a non-negative scalar (a geodesic distance): blue at 0
//                      through cyan, green and yellow to red at the largest
//   divergingColour    a signed distance (negative inside: slice fields,
//                      clearance to other meshes): blue inside, red outside,
//                      brightest at zero. A sequential ramp cannot show the
//                      sign, which is the first thing these values are read
//                      for (inside another object or not), and brightness
//                      falling with |d| keeps contact, where it matters, the
//                      most visible.
//   categoricalColour  an id (region, nearest primitive): neighbouring ids
//                      far apart in hue.
// Every function is O(1).
#include <cstdint>

#include "contours/Rgb.hpp"

namespace dfrecon {

/// Where there is no value (unreached, beyond a band, no id).
inline constexpr Rgb kNoValueColour{128, 128, 128};

/// `value` in [0, largest] on the sequential ramp (clamped; largest ≤ 0
/// paints everything as 0); kNoValueColour for a non-finite value.
Rgb sequentialColour(double value, double largest);

/// `value` on the diverging scheme: negative blue, positive red, brightness
/// falling like √(|value| / scale) to its least at |value| ≥ scale (scale ≤ 0
/// counts as 1); kNoValueColour for a non-finite value.
Rgb divergingColour(double value, double scale);

/// A colour for id `id`: hues stepped by the golden angle so that
/// consecutive ids differ most, saturation and value varied too;
/// kNoValueColour for a negative id.
Rgb categoricalColour(std::int64_t id);

}  // namespace dfrecon
