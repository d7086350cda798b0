#include "dfrecon/Version.hpp"

namespace dfrecon {

const char* version() {
    return DFRECON_VERSION;
}

}  // namespace dfrecon
