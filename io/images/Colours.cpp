#include "io/images/Colours.hpp"

#include <algorithm>
#include <cmath>

namespace dfrecon {

namespace {

std::uint8_t channel(double fraction) {
    return static_cast<std::uint8_t>(std::lround(255 * std::clamp(fraction, 0.0, 1.0)));
}

// HSV with hue in [0, 6) sextants, saturation and value in [0, 1].
Rgb fromHsv(double hue, double saturation, double value) {
    const double c = value * saturation, x = c * (1 - std::abs(std::fmod(hue, 2) - 1));
    double r = 0, g = 0, b = 0;
    switch (int(hue)) {
        case 0:
            r = c, g = x;
            break;
        case 1:
            r = x, g = c;
            break;
        case 2:
            g = c, b = x;
            break;
        case 3:
            g = x, b = c;
            break;
        case 4:
            r = x, b = c;
            break;
        default:
            r = c, b = x;
            break;
    }
    const double m = value - c;
    return {channel(r + m), channel(g + m), channel(b + m)};
}

}  // namespace

Rgb sequentialColour(double value, double largest) {
    if (!std::isfinite(value)) return kNoValueColour;
    const double s = largest > 0 ? std::clamp(value / largest, 0.0, 1.0) : 0.0;
    return {channel(2 * s - 0.5), channel(1.5 - std::abs(4 * s - 2)), channel(1.5 - 2 * s)};
}

Rgb divergingColour(double value, double scale) {
    if (!std::isfinite(value)) return kNoValueColour;
    if (scale <= 0) scale = 1;
    const double level = 1 - std::sqrt(std::min(1.0, std::abs(value) / scale));
    const auto strong = std::uint8_t(80 + 175 * level), weak = std::uint8_t(40 * level);
    return value < 0 ? Rgb{weak, weak, strong} : Rgb{strong, weak, weak};
}

Rgb categoricalColour(std::int64_t id) {
    if (id < 0) return kNoValueColour;
    const double hue = std::fmod(double(id) * 137.50776, 360.0) / 60;
    return fromHsv(hue, id % 2 ? 0.55 : 0.8, id % 3 ? 0.95 : 0.75);
}

}  // namespace dfrecon
