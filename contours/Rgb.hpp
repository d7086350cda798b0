#pragma once
// The colour of a structure as files carry it (DICOM ROI Display Color, a
// mesh's vertex colours): 8 bits per channel. The schemes dfrecon paints
// values with are io/images/Colours.
#include <array>
#include <cstdint>

namespace dfrecon {

using Rgb = std::array<std::uint8_t, 3>;

}  // namespace dfrecon
