#pragma once
// The structure (ROI) a mesh is the surface of, as its file names it: the
// ROI's name and, where the contours gave one, its display colour. Mesh
// writers put it where each format has a place (docs/formats.md): a PLY
// header comment and vertex colours, OBJ object and group names with an MTL
// material, VTK field data and a colour array, the STL header.
#include <optional>
#include <string>

#include "io/images/Colours.hpp"

namespace dfrecon {

struct StructureTag {
    std::string name;           // "": none
    std::optional<Rgb> colour;  // 0..255 each

    bool empty() const { return name.empty() && !colour; }
};

}  // namespace dfrecon
