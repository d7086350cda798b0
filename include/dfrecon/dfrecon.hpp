#pragma once
// The public C++ API of dfrecon, one header per capability: read contours,
// reconstruct, fields, simplify, surface distance maps, segment, compare,
// check. Link dfrecon::api (docs/building.md, "Using the libraries").
#include "dfrecon/Algebra.hpp"
#include "dfrecon/Check.hpp"
#include "dfrecon/Compare.hpp"
#include "dfrecon/Contours.hpp"
#include "dfrecon/Field.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "dfrecon/Segment.hpp"
#include "dfrecon/Simplify.hpp"
#include "dfrecon/SurfaceDistanceMaps.hpp"
#include "dfrecon/Version.hpp"
