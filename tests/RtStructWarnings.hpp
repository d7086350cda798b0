#pragma once
// What the RTSTRUCT tests ask of a read's warnings.
#include <string>

#include "io/dicom/RtStruct.hpp"

namespace dfrecon {

/// Whether any warning of `load` contains `text`.
inline bool anyWarning(const RtStructLoad& load, const std::string& text) {
    for (const InputWarning& w : load.warnings)
        if (w.message.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace dfrecon
