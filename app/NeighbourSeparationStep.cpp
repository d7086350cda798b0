#include "app/NeighbourSeparationStep.hpp"

#include <sstream>

#include "api/Stopwatch.hpp"

namespace dfrecon::app {

nlohmann::ordered_json neighbourSeparationJson(ocl::Runtime& runtime,
                                               const std::vector<const Roi*>& rois,
                                               std::vector<std::optional<RoiSurface>>& surfaces,
                                               bool move) {
    std::vector<RoiSurface*> taking(surfaces.size(), nullptr);
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        if (surfaces[i]) taking[i] = &*surfaces[i];
    NeighbourSeparationOptions options;
    options.move = move;
    const NeighbourSeparation separation = keepNeighboursApart(runtime, rois, taking, options);

    // What is left between each pair that met, measured on the surfaces as
    // they will be written.
    const Stopwatch watch;
    const std::vector<std::optional<Overlap>> overlaps = neighbourOverlaps(separation, taking);

    nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
    for (std::size_t p = 0; p < separation.pairs.size(); ++p) {
        const NeighbourPair& pair = separation.pairs[p];
        nlohmann::ordered_json row{{"a", rois[pair.a]->name},
                                   {"b", rois[pair.b]->name},
                                   {"overlapOnPlanes", pair.overlapOnPlanes},
                                   {"verticesInsideA", pair.insideA},
                                   {"verticesInsideB", pair.insideB},
                                   {"deepestMm", pair.deepestMm},
                                   {"verticesMovedA", pair.movedA},
                                   {"verticesMovedB", pair.movedB},
                                   {"verticesLeftInsideA", pair.leftInsideA},
                                   {"verticesLeftInsideB", pair.leftInsideB}};
        if (overlaps[p]) {
            row["overlapMm3"] = overlaps[p]->intersectionMm3;
            row["overlapBoundMm3"] = overlaps[p]->intersectionBoundMm3;
        } else {
            row["overlapMm3"] = nullptr;
        }
        pairs.push_back(std::move(row));
    }
    return {{"mode", move ? "apart" : "report"},
            {"seconds", separation.seconds},
            {"overlapSeconds", watch.total()},
            {"pairs", std::move(pairs)}};
}

std::string neighbourSeparationLine(const nlohmann::ordered_json& neighbours) {
    std::size_t met = 0, onPlanes = 0, unmeasured = 0;
    double largest = 0;
    std::string largestPair;
    for (const auto& pair : neighbours["pairs"]) {
        if (pair["overlapOnPlanes"].get<bool>()) {
            ++onPlanes;
            continue;
        }
        ++met;
        if (pair["overlapMm3"].is_null()) {
            ++unmeasured;
            continue;
        }
        const double overlap = pair["overlapMm3"].get<double>();
        if (overlap > largest) {
            largest = overlap;
            largestPair = pair["a"].get<std::string>() + "/" + pair["b"].get<std::string>();
        }
    }
    std::ostringstream line;
    const bool moved = neighbours["mode"] == "apart";
    line << (moved ? "neighbours kept apart: " : "neighbours: ") << met
         << " pairs met between the planes";
    if (met > 0)
        line << (moved ? ", largest overlap left " : ", largest overlap ") << largest << " mm3"
             << (largestPair.empty() ? "" : " (" + largestPair + ")");
    if (unmeasured > 0) line << " (" << unmeasured << " not measured: see --json)";
    if (onPlanes > 0) line << "; " << onPlanes << " pairs overlap on their planes, left as drawn";
    line << "\n";
    return line.str();
}

}  // namespace dfrecon::app
