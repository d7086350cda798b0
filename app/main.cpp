// dfrecon: watertight, error-bounded surfaces from planar contour slices.
// Everything but this call lives in dfrecon_app (app/Program.cpp).
#include "app/Program.hpp"

int main(int argc, char** argv) {
    return dfrecon::app::runProgram(argc, argv);
}
